#pragma once
// A slow, independent CPU reference of the LUTs' model (Hillaire 2020, extended in issue 30)
// in double precision: no LUTs anywhere. Transmittance is integrated along each ray as it is
// needed, and the multiple-scattering terms are evaluated directly at every point that needs
// them, by integrating the once-scattered light over the sphere of directions: Psi_ms
// (Hillaire (5)-(11), with the true phase functions at the first scattering) and the second
// order's dipole and quadrupole (shaders/common/atmosphere_shared.h). It checks the LUTs'
// resolution; spectral_sky_reference.h checks the model. Lengths in km, radii from the
// planet centre, the camera on the z axis; radiance per unit illuminance in physical units
// (1/sr) unless a function says otherwise.
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/scene/scene.h"

namespace sky::test {

// Gauss-Legendre nodes and weights (x, w) on [-1, 1].
std::vector<std::pair<double, double>> gaussLegendre(int n);

// The first two Legendre moments (p_1, p_2) of the Cornette-Shanks phase function, P = sum
// (2l + 1) p_l P_l(c) / (4 pi): p_1 is its mean cosine.
glm::dvec2 cornetteShanksMoments(double g);

// The multiple-scattering LUT's layers at one point (shaders/common/atmosphere_shared.h), per
// unit illuminance, 1/sr: Psi_ms and the second order's dipole and quadrupole in the frame of
// the point (up, and the horizontal toward the light).
struct ReferenceMultipleScattering {
  glm::dvec3 psi{0.0};
  glm::dvec3 dipoleUp{0.0}, dipoleLight{0.0};
  glm::dvec3 quadrupoleUp{0.0}, quadrupoleLight{0.0}, quadrupoleCross{0.0};
};

struct ReferenceAtmosphere {
  double groundRadius = 0, topRadius = 0;
  glm::dvec3 rayleigh{0.0};  // 1/km at the ground
  double rayleighHeight = 0;
  glm::dvec3 mieScattering{0.0}, mieExtinction{0.0};  // 1/km at the ground, per channel
  double mieHeight = 0, mieG = 0;
  glm::dvec3 ozone{0.0};  // 1/km at the tent's peak
  double ozoneCenter = 0, ozoneHalfWidth = 0;
  glm::dvec3 albedo{0.0};

  explicit ReferenceAtmosphere(const AtmosphereSettings& s);
};

// Integration resolution. The defaults were checked against a run with 4-16 times as many
// samples in every dimension (384 view steps, Psi_ms every 1/32 of the ray, 96 light steps,
// 16x16 directions over 2 x 16 x 16 of the sphere, 64 steps along each): over 42 rays for the sun
// at 30 and 2 degrees, from the zenith to 30 degrees below the horizon, they agree within 2.2 % per
// channel and 0.3 % of the brightest value.
struct ReferenceQuality {
  int viewSteps = 64;      // along a view ray
  int viewMsSteps = 6;     // segments along a view ray between direct Psi_ms evaluations
  int lightSteps = 16;     // transmittance toward the light
  int sphereBands = 4;     // Gauss-Legendre nodes in cos(zenith), above and below the horizon
  int sphereAzimuths = 4;  // over the half circle (the other half is its mirror image)
  int sphereSteps = 10;    // along each direction of the sphere
};

class AtmosphereReference {
public:
  AtmosphereReference(const AtmosphereSettings& s, ReferenceQuality q = {});

  const ReferenceAtmosphere& atmosphere() const { return mA; }

  // Extinction at an altitude (km), 1/km.
  glm::dvec3 extinction(double altitude) const;
  // Optical depth along a straight segment from `origin` (planet-centred) in direction `dir`.
  glm::dvec3 opticalDepth(glm::dvec3 origin, glm::dvec3 dir, double length, int steps) const;
  // Distance from radius r along cos(zenith) mu to the ground, or to the top if it misses.
  double rayLength(double r, double mu) const;
  // Transmittance from `pos` toward direction L to the top of the atmosphere; 0 if the ground
  // is in the way.
  glm::dvec3 transmittanceToLight(glm::dvec3 pos, glm::dvec3 L) const;
  // Hillaire's Psi_ms at radius r for a light at cos(zenith) muS, evaluated directly (with
  // the true phase functions at the first scattering), and with it the second order's moments.
  glm::dvec3 psiMs(double r, double muS) const;
  ReferenceMultipleScattering multipleScattering(double r, double muS) const;
  // Radiance the air scatters toward the camera at radius r0 along V, light L: single +
  // multiple scattering to the top of the atmosphere or the ground (the ground itself is the
  // composite's, as in the sky-view LUT).
  glm::dvec3 skyRadiance(double r0, glm::dvec3 V, glm::dvec3 L) const;
  // The light in-scattered between the camera and `distance` km along V (no ground), and the
  // transmittance over that segment.
  glm::dvec3 inScattered(double r0, glm::dvec3 V, glm::dvec3 L, double distance,
                         glm::dvec3* transmittance = nullptr) const;

private:
  // Integrates the in-scattered light along a ray.
  glm::dvec3 march(double r0, glm::dvec3 V, glm::dvec3 L, double length,
                   glm::dvec3* transmittance) const;

  ReferenceAtmosphere mA;
  ReferenceQuality mQ;
};

}  // namespace sky::test
