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
//   field(key, TimeSettings&, description)             an instant or a range (scene.h)
//   list(key, std::vector<T>&, ListRule, description)  a list of maps, T described by describe()
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
  v.field("disc_scale", s.discScale, NumberRange{0, 1000},
          "multiplies the physical sun disc radiance (1: physical)");
}

template <class V>
void describe(V& v, MoonSettings& s) {
  v.field(
      "azimuth", s.azimuth, NumberRange{-360, 360},
      "explicit moon azimuth in degrees from north through east (default: from time and place)");
  v.field("elevation", s.elevation, NumberRange{-90, 90},
          "explicit moon elevation in degrees above the horizon (default: from time and place)");
  v.bothOrNeither("azimuth", "elevation");
  v.field("disc_scale", s.discScale, NumberRange{0, 1000},
          "multiplies the physical moon disc radiance (1: physical)");
  v.field("earthshine", s.earthshine, NumberRange{0, 100},
          "multiplies the modelled earthshine on the moon's dark part (1: physical)");
}

template <class V>
void describe(V& v, SkySettings& s) {
  v.field("glow_size", s.glowSize, NumberRange{0, 1}, "size s of the glow around the sun and moon");
  v.field("haze_height", s.hazeHeight, NumberRange{0.001, 1},
          "haze height hmax as a fraction of the dome height");
}

template <class V>
void describe(V& v, PaletteKey& s) {
  constexpr NumberRange kColor{0, 1e6};
  v.field("sun_elevation", s.sunElevation, NumberRange{-90, 90},
          "apparent sun elevation in degrees at which these colours apply");
  v.field("sky_color", s.skyColor, kColor, "zenith sky colour Csky, scene-linear [r, g, b]");
  v.field("fog_color", s.fogColor, kColor, "horizon haze colour Cfog");
  v.field("glow_color", s.glowColor, kColor, "glow around the light Csun (Kozlov 3.1)");
  v.field("cloud_lit", s.cloudLit, kColor, "dense cloud colour toward the light C1 (Kozlov 3.3)");
  v.field("cloud_dark", s.cloudDark, kColor, "dense cloud colour away from the light C2");
  v.field("ambient_top", s.ambientTop, kColor, "ambient light from above (sky)");
  v.field("ambient_bottom", s.ambientBottom, kColor, "ambient light from below (ground)");
}

template <class V>
void describe(V& v, LightingSettings& s) {
  v.field("pressure_hpa", s.pressureHpa, NumberRange{0, 1200},
          "air pressure at the observer for refraction, hPa (0 turns refraction off)");
  v.field("temperature_c", s.temperatureC, NumberRange{-100, 100},
          "air temperature at the observer for refraction, degrees C");
  v.field("turbidity", s.turbidity, NumberRange{0, 5},
          "aerosol optical depth at 550 nm (reddening of sun and moon light)");
  v.field("night_adaptation", s.nightAdaptation, NumberRange{0, 1},
          "fraction of the darkening after sunset (in stops) that the exposure makes up for "
          "moon and stars");
  v.field("star_brightness", s.starBrightness, NumberRange{0, 1e6},
          "multiplies the catalogue star fluxes (1: physical)");
  v.field("star_extinction", s.starExtinction, NumberRange{0, 2},
          "atmospheric extinction of starlight in magnitudes per air mass");
  v.list("palette", s.palette, ListRule{1, 64, "sun_elevation"},
         "Kozlov colours by sun elevation, interpolated in between (list from night to day)");
}

template <class V>
void describe(V& v, Scene& s) {
  v.section("output", s.output, "image size, file name and display transform");
  v.section("camera", s.camera, "observer position and view");
  v.field("time", s.time,
          "date and time in ISO 8601 with a zone, e.g. 2024-06-21T12:00:00+02:00, or a "
          "time-lapse: START/END/STEP or {start, end, step} with a step such as 15m");
  v.section("sun", s.sun, "sun placement and disc");
  v.section("moon", s.moon, "moon placement, disc and earthshine");
  v.section("sky", s.sky, "clear-sky geometry (Kozlov 3.1)");
  v.section("lighting", s.lighting, "refraction, light through the atmosphere, night and palette");
}

}  // namespace sky
