#include "spectral_sky_compare.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "engine/core/error.h"
#include "engine/render/renderer.h"

namespace sky::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dvec3 enu(double azimuthDeg, double elevationDeg) {
  const double az = azimuthDeg * kPi / 180.0, el = elevationDeg * kPi / 180.0;
  return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

// The q-quantile of `values` where each counts `weights`.
double weightedQuantile(const std::vector<double>& values, const std::vector<double>& weights,
                        double q) {
  std::vector<size_t> order(values.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] < values[b]; });
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  double sum = 0.0;
  for (size_t i : order) {
    sum += weights[i];
    if (sum >= q * total) return values[i];
  }
  return values.empty() ? 0.0 : values[order.back()];
}

}  // namespace

BruteForceQuality referenceQuality(const std::string& name) {
  BruteForceQuality q;
  if (name == "test") {
    q.viewSteps = 48;
    q.scatterPoints = 6;
    q.sphereBands = 4;
    q.sphereAzimuths = 8;
    q.sphereSteps = 16;
    q.transferAltitudes = 24;
    q.columnRadii = 48;
    q.columnAngles = 128;
    q.columnSteps = 64;
  } else if (name == "fine") {
    q.viewSteps = 192;
    q.scatterPoints = 24;
    q.sphereBands = 16;
    q.sphereAzimuths = 32;
    q.sphereSteps = 48;
    q.transferAltitudes = 96;
    q.columnRadii = 192;
    q.columnAngles = 512;
    q.columnSteps = 256;
  } else if (name != "default") {
    inputError("reference quality '" + name + "' (test, default or fine)");
  }
  return q;
}

int HalfDome::probeColumn(int k) const {
  // The sun's azimuth falls on the boundary between two columns when width is even.
  const int sunColumn = static_cast<int>(std::lround(kCompareSunAzimuthDeg / 360.0 * width));
  return (sunColumn + k) % width;
}

double HalfDome::elevationDeg(int row) const {
  return 90.0 - 180.0 * (row + 0.5) / height;
}

glm::dvec3 HalfDome::direction(int row, int k) const {
  return enu(360.0 * (probeColumn(k) + 0.5) / width, elevationDeg(row));
}

std::vector<glm::dvec3> HalfDome::directions() const {
  std::vector<glm::dvec3> out;
  for (int row = 0; row < rows(); ++row)
    for (int k = 0; k < columns(); ++k) out.push_back(direction(row, k));
  return out;
}

std::vector<glm::dvec3> halfDomeOf(const ReadbackImage& probe, const HalfDome& dome) {
  std::vector<glm::dvec3> out;
  for (int row = 0; row < dome.rows(); ++row)
    for (int k = 0; k < dome.columns(); ++k) {
      const float* p = &probe.pixels[(static_cast<size_t>(row) * probe.width +
                                      static_cast<size_t>(dome.probeColumn(k))) *
                                     probe.channels];
      out.emplace_back(p[0], p[1], p[2]);
    }
  return out;
}

SkyStats compareSky(const std::vector<glm::dvec3>& sky, const std::vector<glm::dvec3>& ref,
                    const HalfDome& dome) {
  std::vector<double> luminance, chroma, weights;
  SkyStats s;
  for (int row = 0; row < dome.rows(); ++row)
    for (int k = 0; k < dome.columns(); ++k) {
      const size_t i = static_cast<size_t>(row * dome.columns() + k);
      // Solid angle of an equirectangular cell: proportional to cos(elevation).
      weights.push_back(std::cos(dome.elevationDeg(row) * kPi / 180.0));
      luminance.push_back(std::abs(luminance709(sky[i]) / luminance709(ref[i]) - 1.0));
      const glm::dvec2 c = chromaticity709(sky[i]), w = chromaticity709(ref[i]);
      chroma.push_back(std::max(std::abs(c.x / w.x - 1.0), std::abs(c.y / w.y - 1.0)));
      if (row == 0) {
        s.zenith += sky[i] / double(dome.columns());
        s.zenithRef += ref[i] / double(dome.columns());
      }
    }
  s.luminanceMedian = weightedQuantile(luminance, weights, 0.5);
  s.luminanceP90 = weightedQuantile(luminance, weights, 0.9);
  s.luminanceMax = *std::max_element(luminance.begin(), luminance.end());
  s.chromaMedian = weightedQuantile(chroma, weights, 0.5);
  s.chromaP90 = weightedQuantile(chroma, weights, 0.9);
  return s;
}

double turbidityOfPreetham(double T) {
  return (0.04608 * T - 0.04586) * std::pow(0.55, -1.3);
}

std::vector<SkyCase> standardCases(const std::vector<double>& sunElevationsDeg) {
  std::vector<SkyCase> out;
  const std::pair<const char*, double> kinds[] = {
      {"T 2", turbidityOfPreetham(2.0)}, {"T 3", turbidityOfPreetham(3.0)}, {"default", -1.0}};
  for (const auto& [name, turbidity] : kinds)
    for (double e : sunElevationsDeg) {
      SkyCase c;
      c.name = name;
      c.scene.sky.model = SkyModel::Physical;
      if (turbidity >= 0.0) c.scene.lighting.turbidity = turbidity;
      c.sunElevationDeg = e;
      out.push_back(c);
    }
  return out;
}

glm::dvec3 caseSunDirection(const SkyCase& c) {
  return enu(kCompareSunAzimuthDeg, c.sunElevationDeg);
}

AtmosphereLuts::Frame caseFrame(const SkyCase& c, glm::dvec3 sun) {
  AtmosphereLuts::Frame f;
  f.atmosphere = physicalAtmosphere(c.scene);
  f.cameraAltitudeM = kCompareAltitudeKm * 1e3;
  f.sunDirection = glm::vec3(caseSunDirection(c));
  f.sunIlluminance = glm::vec3(sun);
  f.moonDirection = glm::vec3(enu(kCompareSunAzimuthDeg + 180.0, -30.0));
  f.moonIlluminance = glm::vec3(0.0f);
  // The aerial perspective is not compared; any camera will do.
  f.view.right = glm::vec4(1, 0, 0, 0.5f);
  f.view.up = glm::vec4(0, 0, 1, 0.5f);
  f.view.forward = glm::vec4(0, 1, 0, 0.01f);
  f.view.size = glm::uvec4(64, 36, 0, 0);
  return f;
}

ReadbackImage renderProbe(GraphRuntime& runtime, AtmosphereLuts& luts,
                          const AtmosphereLuts::Frame& frame, int width, int height) {
  FrameGraph graph(runtime);
  const AtmosphereLuts::Outputs out = luts.addTo(graph, frame);
  graph.requestOutput(
      luts.addSkyProbe(graph, out, static_cast<uint32_t>(width), static_cast<uint32_t>(height)),
      "probe");
  FrameResult result = graph.execute();
  return result.output("probe");
}

}  // namespace sky::test
