#pragma once
// The LUT sky (the sky probe of passes/atmosphere_luts) against the spectral reference over the
// dome: which directions, what is measured, and the cases of docs/atmosphere.md. Shared by
// spectral_sky_test.cpp and the spectral_sky command.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/scene/scene.h"
#include "passes/atmosphere_luts/atmosphere_luts.h"
#include "spectral_sky_reference.h"

namespace sky::test {

// The reference's resolutions: "test" (the tests' coarse one), "default" and "fine" (the
// command's; 2 and 4 times "test" in most dimensions). Input error for another name.
BruteForceQuality referenceQuality(const std::string& name);
// The wavelength step the tests use with "test" (nm).
constexpr int kTestWavelengthStepNm = 20;

// The camera of the comparisons: 200 m up, the sun due south (azimuth 180).
constexpr double kCompareAltitudeKm = 0.2;
constexpr double kCompareSunAzimuthDeg = 180.0;

// The upper half of a width x height sky probe (equirectangular, column 0 north, row 0 the
// zenith) on the side of the sun's vertical plane east of it; the other side is its mirror
// image (the sky is symmetric about that plane and so is the sky-view LUT).
struct HalfDome {
  int width = 72, height = 36;
  int rows() const { return height / 2; }
  int columns() const { return width / 2; }
  // Probe pixel of half-dome cell (row, k), k = 0 next to the sun's azimuth.
  int probeColumn(int k) const;
  glm::dvec3 direction(int row, int k) const;
  double elevationDeg(int row) const;
  std::vector<glm::dvec3> directions() const;  // row-major, rows() x columns()
};

// Probe pixels of the half dome, in directions() order.
std::vector<glm::dvec3> halfDomeOf(const ReadbackImage& probe, const HalfDome& dome);

struct SkyStats {
  // |Y / Y_ref - 1| over the half dome, quantiles weighted by solid angle.
  double luminanceMedian = 0.0, luminanceP90 = 0.0, luminanceMax = 0.0;
  // max(|x / x_ref - 1|, |y / y_ref - 1|) of the CIE xy chromaticity, as the clear-sky test.
  double chromaMedian = 0.0, chromaP90 = 0.0;
  // Mean of the top row (2.5 degrees from the zenith on a 72 x 36 probe) and its R/G.
  glm::dvec3 zenith{0.0}, zenithRef{0.0};
  double zenithRg() const { return zenith.r / zenith.g; }
  double zenithRgRef() const { return zenithRef.r / zenithRef.g; }
};

SkyStats compareSky(const std::vector<glm::dvec3>& sky, const std::vector<glm::dvec3>& ref,
                    const HalfDome& dome);

// One case of the comparison: a scene (sky.model physical) and the sun's elevation.
struct SkyCase {
  std::string name;
  Scene scene;
  double sunElevationDeg = 30.0;
};
// lighting.turbidity of Preetham's turbidity T, as the clear-sky test maps it: Angstrom's
// beta = 0.04608 T - 0.04586 at 1 um, tau(550 nm) = beta 0.55^-1.3.
double turbidityOfPreetham(double T);
// Preetham T 2 and 3 and the default scene, each with the sun at each elevation.
std::vector<SkyCase> standardCases(const std::vector<double>& sunElevationsDeg);

// The frame of a case: the sun at kCompareSunAzimuthDeg, the camera kCompareAltitudeKm up, the
// sun's illuminance `sun` (renderer units, rgb), the moon dark.
AtmosphereLuts::Frame caseFrame(const SkyCase& c, glm::dvec3 sun);
glm::dvec3 caseSunDirection(const SkyCase& c);

// Renders the LUTs and a width x height probe for `frame`; returns the probe.
ReadbackImage renderProbe(GraphRuntime& runtime, AtmosphereLuts& luts,
                          const AtmosphereLuts::Frame& frame, int width, int height);

}  // namespace sky::test
