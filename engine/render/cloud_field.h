#pragma once
// The volumetric clouds' density field on the CPU, for queries (the public API's line of
// sight, transmittance and density): the twin of cloudSampleAtLla in
// shaders/common/cloud_field.glsl, at full detail (a footprint of 0, as the density export
// and the density slice read it) unless a sample's width is given, made from the frame's
// own CloudParams, weather map and baked noise, so it is the field the raymarch marches
// through. The air between two points
// is the physical atmosphere's medium (shaders/common/atmosphere.glsl atmosphereMedium).
// tests/cloud_volume/cloud_field_test.cpp compares it with the GPU's density export.
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "engine/clouds/noise_volume.h"
#include "engine/weather/geo.h"
#include "engine/weather/weather_map.h"
#include "shaders/common/atmosphere_shared.h"
#include "shaders/common/volumetric_clouds_shared.h"

namespace sky {

// One point of the field.
struct CloudFieldSample {
  float density = 0.0f;  // Lu's density with the map's density scale; extinction = this x
                         // CloudParams::extinction (1/m)
  int layer = -1;        // 0 low, 1 mid, -1 neither
  float cover = 0.0f;    // the weather map's cover of that layer there
  float type = 0.0f;     // the map's cloud type (0 stratiform, 0.5 cellular, 1 convective)
};

// What the field is made from (engine/render/renderer.h Renderer::cloudField fills it).
struct CloudFieldInputs {
  shared::CloudParams params{};    // cloudParams() of the frame, as the raymarch gets them
  bool tang = false;               // clouds.model tang2019 (CLOUD_TANG)
  bool calibrated = true;          // clouds.coverage calibrated (CLOUD_CALIBRATED)
  bool rolls = true;               // the map has stratocumulus rolls (CLOUD_ROLLS)
  bool cumulus = true;             // the map has cumulus (CLOUD_CUMULUS, cloudCumulusWeight)
  GeoPosition camera;              // the ENU frame's origin (params.geo's)
  WeatherMap weather;              // the map the frame's textures hold
  NoiseVolume shape, detail;       // the baked noise (CloudNoise's CPU copies)
  NoiseVolume curl;                // the curl texture: size^2 texels, one slice
  shared::AtmosphereParams air{};  // the physical atmosphere (atmosphereParams)
  bool anyCover = false;           // the map has low or mid cover somewhere
};

class CloudField {
public:
  explicit CloudField(CloudFieldInputs inputs);

  // The cloud at a point of the camera's ENU frame (m), as a sample `footprintM` wide sees
  // it: the raymarch's level of detail (docs/clouds.md), 0 for full detail.
  CloudFieldSample sample(const glm::dvec3& enu, float footprintM = 0.0f) const;
  // Extinction through cloud at a point, 1/m.
  double extinction(const glm::dvec3& enu) const;
  // Optical depth through cloud along the segment a -> b (ENU, m), sampled every `stepM` at
  // the middle of each step (the last one shortened to end at b).
  double cloudOpticalDepth(const glm::dvec3& a, const glm::dvec3& b, double stepM) const;
  // The air's extinction (R, G, B; 1/m) at a point: the physical atmosphere's medium.
  glm::dvec3 airExtinction(const glm::dvec3& enu) const;
  // The air's optical depth (R, G, B) along the segment, below the atmosphere's top.
  glm::dvec3 airOpticalDepth(const glm::dvec3& a, const glm::dvec3& b) const;
  // The distance along the ray from `origin` (ENU) in direction `dir` (unit) at which its
  // cloud optical depth passes `tau`, within `maxM`; nullopt when it does not.
  std::optional<double> distanceToOpticalDepth(const glm::dvec3& origin, const glm::dvec3& dir,
                                               double maxM, double tau, double stepM) const;

  // Between the camera's ENU frame and latitude, longitude (degrees), altitude (m).
  glm::dvec3 enuOf(double latDeg, double lonDeg, double altitudeM) const;
  glm::dvec3 latLonAltitudeOf(const glm::dvec3& enu) const;
  // The weather map's (low cover, mid cover, type, density scale) at a place: zero outside
  // the map's region.
  glm::vec4 weatherAt(double latDeg, double lonDeg) const;

  const shared::CloudParams& params() const { return mIn.params; }
  const shared::AtmosphereParams& air() const { return mIn.air; }
  bool anyCover() const { return mIn.anyCover; }

private:
  float coverageThreshold(int layer, float type, float cover) const;
  glm::vec2 farMeanDensity(int layer, float type, float cover, float ph) const;

  CloudFieldInputs mIn;
};

// Linear filtering with repeat addressing of an RGBA8 volume (or, with `size` texels a
// side and one slice, a plane), as a Vulkan sampler reads it: texel centres at (i + 0.5) /
// size, coordinates taken modulo 1. Exposed for tests.
glm::vec4 sampleRepeat(const NoiseVolume& volume, const glm::vec3& uvw);
glm::vec4 sampleRepeat(const NoiseVolume& plane, const glm::vec2& uv);

}  // namespace sky
