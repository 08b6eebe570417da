#pragma once
// THE description of the scene file format. Reading (strict validation), writing
// (`skyrender validate`) and the JSON Schema (configs/schema/scene.schema.json) all walk
// these functions, so adding a key is one line here and nothing else.
//
// A visitor V provides:
//   section(key, settingsStruct, description)          a nested map, described by describe()
//   field(key, int|double|glm::vec3&, NumberRange, description)
//   field(key, std::optional<double>&, NumberRange, description)   absent unless given
//   field(key, std::string&, TextRule, description)
//   field(key, IsoTime&, description)                  ISO 8601 text with a zone
//   bothOrNeither(keyA, keyB)                          two optional keys given together
// Keys are the snake_case form of the member names.
#include "engine/scene/field_rules.h"
#include "engine/scene/scene.h"

namespace sky {

template <class V>
void describe(V& v, OutputSettings& s) {
  v.field("width", s.width, NumberRange{1, 16384}, "image width in pixels");
  v.field("height", s.height, NumberRange{1, 16384}, "image height in pixels");
  v.field("name", s.name,
          TextRule{1, 200, "^[A-Za-z0-9_-][A-Za-z0-9._-]*$",
                   "letters, digits, '.', '_' and '-', not starting with '.'"},
          "output file stem (no folder, no extension)");
  v.field("exposure_ev", s.exposureEv, NumberRange{-20, 20},
          "display exposure in stops (not applied to EXR output)");
  v.field("display", s.display, TextRule{1}, "OCIO display");
  v.field("view", s.view, TextRule{1}, "OCIO view");
}

template <class V>
void describe(V& v, CameraSettings& s) {
  v.field("latitude", s.latitude, NumberRange{-90, 90},
          "observer latitude in degrees, north positive");
  v.field("longitude", s.longitude, NumberRange{-180, 180},
          "observer longitude in degrees, east positive");
  v.field("altitude_m", s.altitudeM, NumberRange{-500, 100000},
          "observer altitude in metres above sea level");
  v.field("heading", s.heading, NumberRange{-360, 360},
          "view direction in degrees clockwise from north");
  v.field("pitch", s.pitch, NumberRange{-90, 90}, "view direction in degrees above the horizon");
  v.field("vertical_fov", s.verticalFov, NumberRange{1, 179}, "vertical field of view in degrees");
}

template <class V>
void describe(V& v, SunSettings& s) {
  v.field("azimuth", s.azimuth, NumberRange{-360, 360},
          "explicit sun azimuth in degrees from north through east (default: from time and place)");
  v.field("elevation", s.elevation, NumberRange{-90, 90},
          "explicit sun elevation in degrees above the horizon (default: from time and place)");
  v.bothOrNeither("azimuth", "elevation");
  v.field("angular_diameter", s.angularDiameter, NumberRange{0.01, 20},
          "sun disc diameter in degrees");
  v.field("disc_intensity", s.discIntensity, NumberRange{0, 1e6},
          "sun disc radiance as a multiple of sky.sun_color");
}

template <class V>
void describe(V& v, SkySettings& s) {
  v.field("sky_color", s.skyColor, NumberRange{0, 1e6},
          "zenith sky colour Csky, scene-linear [r, g, b]");
  v.field("fog_color", s.fogColor, NumberRange{0, 1e6},
          "horizon haze colour Cfog, scene-linear [r, g, b]");
  v.field("sun_color", s.sunColor, NumberRange{0, 1e6},
          "sun glow and disc colour Csun, scene-linear [r, g, b]");
  v.field("glow_size", s.glowSize, NumberRange{0, 1}, "size s of the glow around the sun");
  v.field("haze_height", s.hazeHeight, NumberRange{0.001, 1},
          "haze height hmax as a fraction of the dome height");
}

template <class V>
void describe(V& v, Scene& s) {
  v.section("output", s.output, "image size, file name and display transform");
  v.section("camera", s.camera, "observer position and view");
  v.field("time", s.time.instant,
          "date and time in ISO 8601 with a zone, e.g. 2024-06-21T12:00:00+02:00");
  v.section("sun", s.sun, "sun placement and disc");
  v.section("sky", s.sky, "clear-sky colours (Kozlov 3.1)");
}

}  // namespace sky
