#pragma once
// The scene: plain settings structs, filled from YAML or JSON (engine/scene/scene_io.h).
// Defaults here are the defaults of the file format; `skyrender validate` prints them back.
// File keys are snake_case versions of the member names (exposureEv -> exposure_ev).
// Keys, ranges and descriptions are written once, in engine/scene/scene_fields.h: a new
// member here needs one line there to be read, printed and put in the JSON Schema.
#include <cstdint>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "engine/scene/iso_time.h"

namespace sky {

struct OutputSettings {
  int width = 1280;              // pixels, 1..16384
  int height = 720;              // pixels, 1..16384
  std::string name = "sky";      // file stem: [A-Za-z0-9._-], not starting with '.'
  double exposureEv = 0.0;       // display exposure in stops, -20..20 (not applied to EXR)
  std::string display = "sRGB";  // OCIO display
  std::string view = "ACES 1.0 - SDR Video";  // OCIO view
};

struct CameraSettings {
  double latitude = 47.37;    // degrees, -90..90
  double longitude = 8.54;    // degrees, -180..180
  double altitudeM = 500.0;   // metres above sea level, -500..100000
  double heading = 180.0;     // degrees clockwise from north, -360..360
  double pitch = 15.0;        // degrees above the horizon, -90..90
  double verticalFov = 60.0;  // degrees, 1..179
};

struct TimeSettings {
  IsoTime instant = IsoTime::parse("2024-06-21T12:00:00+02:00").value();  // key `time`
};

// An explicit sun placement (art direction, tests). When azimuth/elevation are absent the
// sun follows `time` and the camera position.
struct SunSettings {
  std::optional<double> azimuth;    // degrees from north through east, -360..360
  std::optional<double> elevation;  // degrees above the horizon, -90..90
  double angularDiameter = 0.53;    // degrees, 0.01..20
  double discIntensity = 40.0;      // disc radiance as a multiple of sky.sun_color, 0..1e6
};

// Kozlov 3.1 clear sky: C = (Csky h + Cfog (1 - h)) (1 - l) + Csun l.
struct SkySettings {
  glm::vec3 skyColor{0.07f, 0.20f, 0.65f};  // Csky, scene-linear, each 0..1e6
  glm::vec3 fogColor{0.50f, 0.62f, 0.80f};  // Cfog
  glm::vec3 sunColor{1.00f, 0.85f, 0.65f};  // Csun (glow and disc colour)
  double glowSize = 0.30;                   // s, 0..1
  double hazeHeight = 0.20;                 // hmax as a fraction of the dome height, 0.001..1
};

struct Scene {
  OutputSettings output;
  CameraSettings camera;
  TimeSettings time;
  SunSettings sun;
  SkySettings sky;
};

}  // namespace sky
