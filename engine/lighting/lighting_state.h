#pragma once
// The one lighting model (DESIGN "One lighting API"): from a scene and an instant, where the
// sun and moon are, how much light each gives, which is the key light, the night lift, and
// the palette colours by sun elevation. Computed once per frame; every pass reads `gpu`.
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "engine/lighting/ephemeris.h"
#include "engine/scene/scene.h"
#include "shaders/common/lighting_shared.h"

namespace sky {

struct BodyLight {
  double azimuthDeg = 0.0;    // from north through east, [0, 360)
  double elevationDeg = 0.0;  // apparent (refracted), or the scene's override
  bool overridden = false;    // placed by the scene's azimuth/elevation, not the ephemeris
  glm::dvec3 direction{0.0};  // unit, east-north-up
  double angularRadiusDeg = 0.0;
  double illuminanceLux = 0.0;  // at the ground, normal incidence, physical (no night lift)
};

struct LightingState {
  IsoTime time;
  Ephemeris ephemeris;
  BodyLight sun;
  BodyLight moon;
  double dayFactor = 1.0;    // light::dayFactor of the sun's elevation
  double nightLiftEv = 0.0;  // stops the night lights are lifted by
  // output.exposure auto's stops: the night lift, or a low sun's gentler lift before it
  // (light::autoExposureEv).
  double autoExposureEv = 0.0;
  std::string key;           // "sun" (day factor >= 0.5) or "moon"
  PaletteKey palette;        // at the sun's elevation
  PaletteKey moonPalette;    // at the moon's elevation, scaled to moonlight
  double overcast = 0.0;     // the local weather's hidden sky fraction (applyOvercast)
  shared::LightingState gpu{};
};

// Unit direction for an azimuth (from north through east) and elevation, in degrees.
glm::dvec3 enuDirection(double azimuthDeg, double elevationDeg);

// Linear interpolation between the keyframes around `sunElevationDeg` (clamped to the
// first and last keyframe). `keys` is sorted by sun elevation, as the scene reader ensures.
PaletteKey interpolatePalette(const std::vector<PaletteKey>& keys, double sunElevationDeg);

// Everything for one instant. Throws sky::Error(BadInput) for an impossible observer.
LightingState computeLighting(const Scene& scene, const IsoTime& time);

// The local weather's part in the light (Kozlov section 5; engine/weather/local_weather.h):
// with a fraction `overcast` of the sky hidden by cloud around the camera, the ground gets
// G/G0 = 1 - 0.75 N^3.4 of its clear-sky light (Kasten and Czeplak 1980), so the ambient from
// below (the ground's bounce) drops by that; the light from above turns grey, the cloud
// covering the blue (same luminance, saturation x (1 - N)); and the horizon haze of the
// kozlov sky rises from sky.haze_height toward the zenith by half of N, the air under cloud
// being moister and murkier. Updates `palette`, `moonPalette`, `overcast` and `gpu`.
void applyOvercast(LightingState& state, const SkySettings& sky, double overcast);

// Whether the moon's light may be left out of a frame (shaders/common/lighting.glsl,
// LIGHTING_MOON 0): with the sun above the horizon moonlight is a few millionths of sunlight
// (a full moon's 0.3 lux against 100 000), far under a pixel's precision.
bool moonLightNegligible(const shared::LightingState& state);

// The state as JSON, for `skyrender ephemeris` and render reports:
// {"time_utc", "sun": {...}, "moon": {...}, "light": {"key", "day_factor", ...}}.
nlohmann::ordered_json lightingJson(const LightingState& state);

}  // namespace sky
