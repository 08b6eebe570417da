#pragma once
// THE description of the scene file format. Reading (strict validation), writing
// (`skyrender validate`) and the JSON Schema (configs/schema/scene.schema.json) all walk
// these functions, so adding a key is one line here and nothing else.
//
// A visitor V provides:
//   section(key, settingsStruct, description)          a nested map, described by describe()
//   field(key, int|double|glm::vec3&, NumberRange, description)
//   field(key, std::optional<double>&, NumberRange, description)   absent unless given
//   field(key, glm::dvec2&, NumberRange, description)  a pair [from, to] (e.g. a lat range)
//   field(key, bool&, description)                     true or false
//   field(key, std::string&, TextRule, description)
//   field(key, E&, description)                        a choice: an enum with enumNames() (scene.h)
//   field(key, TimeSettings&, description)             an instant or a range (scene.h)
//   field(key, std::optional<IsoTime>&, description)   an instant, absent unless given
//   list(key, std::vector<T>&, ListRule, description)  a list of maps, T described by describe()
//   bothOrNeither(keyA, keyB)                          two optional keys given together
//   check(key, ok, what)                               a rule across fields (reader only)
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
  v.field("exposure", s.exposure,
          "how the display exposes the physical image: auto (the lighting model's night lift), "
          "histogram (metered from the frame, adapting over a sequence) or fixed (exposure_ev "
          "alone); never applied to the EXR");
  v.field("exposure_ev", s.exposureEv, NumberRange{-20, 20},
          "stops added to the display exposure (not applied to EXR output)");
  v.field("exposure_adaptation_s", s.exposureAdaptationS, NumberRange{0, 3600},
          "exposure histogram: time constant in scene seconds with which a sequence's "
          "exposure follows the metered one (0: at once)");
  v.field("night_look", s.nightLook,
          "the display's night look: dim scenes lose colour and shift toward blue as the eye's "
          "rods take over (Purkinje), by their physical luminance (not the EXR)");
  v.field("display", s.display, TextRule{1}, "OCIO display");
  v.field("view", s.view, TextRule{1}, "OCIO view");
  v.field("dither", s.dither,
          "dither the 8-bit PNG before rounding, so smooth gradients show no bands (not the EXR)");
  v.field("perception", s.perception,
          "also write the perception layers to the EXR: the clouds' optical depth and hit "
          "distance, a label and cloud type per pixel, the air's transmittance and the ground's "
          "cloud shadow (docs/outputs.md)");
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
  v.field("roll", s.roll, NumberRange{-180, 180},
          "rotation about the view direction in degrees: positive banks the camera right, as an "
          "aircraft, so the image turns counter-clockwise (perspective)");
  v.field("vertical_fov", s.verticalFov, NumberRange{1, 179},
          "vertical field of view in degrees (perspective)");
  v.field("projection", s.projection,
          "perspective (a pinhole camera) or equirectangular (the whole sphere, 360 x 180 "
          "degrees centred on heading; pitch, roll and vertical_fov are ignored)");
  v.field("mode", s.mode,
          "observer (a camera at latitude, longitude and altitude_m) or geographic_topdown (the "
          "weather region mapped exactly onto the image, row 0 north, column 0 west, looking "
          "straight down from above the clouds)");
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
  v.field("model", s.model,
          "clear-sky model: kozlov (palette colours, Kozlov 3.1) or physical (Hillaire 2020 "
          "atmosphere)");
  v.field("glow_size", s.glowSize, NumberRange{0, 1}, "size s of the glow around the sun and moon");
  v.field("glow_exponent", s.glowExponent, NumberRange{1, 64},
          "exponent n of the glow l = s max(V.S, 0)^n (Kozlov 3.1: 2; larger is tighter)");
  v.field("haze_height", s.hazeHeight, NumberRange{0.001, 1},
          "haze height hmax as a fraction of the dome height");
}

template <class V>
void describe(V& v, AtmosphereSettings& s) {
  constexpr NumberRange kCoefficient{0, 1e4};
  constexpr NumberRange kScaleHeight{0.01, 100};
  v.field("ground_radius_km", s.groundRadiusKm, NumberRange{100, 100000}, "planet radius in km");
  v.field("thickness_km", s.thicknessKm, NumberRange{1, 1000},
          "height of the top of the atmosphere above the ground, km");
  v.field("rayleigh_scattering", s.rayleighScattering, kCoefficient,
          "Rayleigh scattering at sea level per channel, 1/Mm (10^-6 per metre)");
  v.field("rayleigh_scale_height_km", s.rayleighScaleHeightKm, kScaleHeight,
          "Rayleigh density scale height, km");
  v.field("aerosols", s.aerosols,
          "where the Mie (aerosol) coefficients come from: turbidity (lighting.turbidity, the "
          "aerosol optical depth the sun's light crosses, spread over mie_scale_height_km) or "
          "settings (mie_scattering and mie_extinction below)");
  v.field("mie_scattering", s.mieScattering, kCoefficient,
          "Mie scattering at sea level, 1/Mm (aerosols: settings)");
  v.field("mie_extinction", s.mieExtinction, kCoefficient,
          "Mie extinction at sea level, 1/Mm (at least mie_scattering; aerosols: settings)");
  v.field("mie_scale_height_km", s.mieScaleHeightKm, kScaleHeight, "Mie density scale height, km");
  v.field("mie_anisotropy", s.mieAnisotropy, NumberRange{-0.99, 0.99},
          "Mie phase asymmetry g (Cornette-Shanks; aerosols: settings, turbidity uses "
          "continental aerosol's 0.6)");
  v.field("ozone_absorption", s.ozoneAbsorption, kCoefficient,
          "ozone absorption at the peak of its layer per channel, 1/Mm");
  v.field("ozone_center_km", s.ozoneCenterKm, NumberRange{0, 1000},
          "altitude of the ozone peak, km");
  v.field("ozone_half_width_km", s.ozoneHalfWidthKm, NumberRange{0.01, 100},
          "half width of the ozone tent profile, km");
  v.check("mie_extinction", s.mieExtinction >= s.mieScattering,
          "must be at least mie_scattering (extinction = scattering + absorption)");
  v.check("ozone_center_km", s.ozoneCenterKm < s.thicknessKm,
          "must lie below the top of the atmosphere (thickness_km)");
}

template <class V>
void describe(V& v, GroundSettings& s) {
  v.field("albedo", s.albedo, NumberRange{0, 1},
          "Lambertian reflectance per channel (linear Rec.709); also the physical sky's ground "
          "bounce");
}

template <class V>
void describe(V& v, HighCloudSettings& s) {
  v.field("source", s.source,
          "where the coefficient texture comes from: procedural (baked from noise and "
          "cover, cached on disk) or image (files given below)");
  v.field("style", s.style,
          "procedural cloud style: cirrus streaks, cirrostratus veil or cirrocumulus ripples");
  v.field("cover", s.cover, NumberRange{0, 1},
          "procedural high-cloud cover fraction (0: no high clouds)");
  v.field("cover_map", s.coverMap, TextRule{0, 4096},
          "optional greyscale PNG/EXR multiplying cover over one texture tile (relative "
          "paths are relative to the scene file)");
  v.field("coefficients", s.coefficients, TextRule{0, 4096},
          "image source: RGBA PNG/EXR coefficient texture (R thin lit parts, G dense parts, B "
          "clear sky, A sparse edges)");
  v.field("normals", s.normals, TextRule{0, 4096},
          "image source: tangent-space normal map PNG/EXR of the same size (empty: derived "
          "from the coefficients)");
  v.field("resolution", s.resolution, NumberRange{64, 4096},
          "procedural texture size in texels (a power of two)");
  v.field("seed", s.seed, NumberRange{0, 2147483647}, "procedural noise seed");
  v.field("altitude_m", s.altitudeM, NumberRange{1000, 20000},
          "altitude of the high-cloud layer above sea level, metres");
  v.field("tile_size_km", s.tileSizeKm, NumberRange{0.1, 10000},
          "ground size of one repeat of the texture, km");
  v.field("wind_speed_ms", s.windSpeedMs, NumberRange{0, 200},
          "wind speed at the layer, m/s (moves the texture with time)");
  v.field("wind_from", s.windFrom, NumberRange{-360, 360},
          "direction the wind blows from, degrees clockwise from north (the texture drifts "
          "with it; a procedural texture's streaks lie along it)");
  v.field("edge_glow_deg", s.edgeGlowDeg, NumberRange{0.5, 90},
          "angular width l of the glow of sparse edges around the light (Kozlov 3.4), degrees");
  v.field("brightness", s.brightness, NumberRange{0, 100}, "multiplies the cloud colour terms");
  v.field("cover_source", s.coverSource,
          "procedural: the cover from `cover` (scene), from the weather map's high layer per "
          "pixel (weather, needs weather.source file) or weather when the map has a high layer "
          "(auto)");
  v.check("resolution", (s.resolution & (s.resolution - 1)) == 0, "must be a power of two");
  v.check("coefficients", s.source != HighCloudSource::Image || !s.coefficients.empty(),
          "is required when source is image");
}

template <class V>
void describe(V& v, CloudLayerSettings& s) {
  v.field("base_m", s.baseM, NumberRange{0, 30000}, "layer base above sea level, metres");
  v.field("top_m", s.topM, NumberRange{0, 30000}, "layer top above sea level, metres");
  v.check("top_m", s.topM > s.baseM, "must be above base_m");
}

template <class V>
void describe(V& v, CloudTemporalSettings& s) {
  v.field("mode", s.mode,
          "on: each frame of a sequence (a time-lapse, a window, a benchmark pan) marches "
          "1 / block^2 of the pixels and reprojects the rest from the frames before; a single "
          "frame always marches them all");
  v.field("block", s.block, NumberRange{1, 4},
          "each frame marches one pixel of every block x block square (4: a sixteenth)");
  v.field("resolution", s.resolution,
          "full: the clouds are marched and kept at the view's size; half: at half its width "
          "and height, upsampled depth-aware (four times fewer pixels to march; the first "
          "frame then differs from the still)");
}

template <class V>
void describe(V& v, CloudSettings& s) {
  v.field("quality", s.quality,
          "standard: the raymarch tuned for speed; reference: the ground truth it is measured "
          "against (small fixed steps, no early exit or empty-space skipping, a long light "
          "march, no temporal reuse; many times slower)");
  v.section("temporal", s.temporal,
            "temporal reuse across the frames of a sequence (docs/clouds.md)");
  v.field("light", s.light,
          "volume: the light through the clouds from a light volume made with a fine march "
          "(each sample marches only its nearest steps); march: a march toward the light at "
          "every sample (the reference always marches, finely)");
  v.field("model", s.model,
          "density and noise model: lu2023 (Lu et al. 2023) or tang2019 (Tang et al. 2019)");
  v.field("coverage", s.coverage,
          "how cover sets the noise threshold: calibrated (the covered area equals the cover) "
          "or paper (Lu's remap with 1 - CMc)");
  v.field("extinction", s.extinction, NumberRange{1e-5, 1},
          "extinction coefficient per metre at density 1 (Lu's beta)");
  v.field("g", s.g, NumberRange{-0.99, 0.99}, "Henyey-Greenstein asymmetry (Lu (23))");
  v.field("phase", s.phase,
          "phase function: hg (Lu (23)) or dual_lobe (adds a back-scattering lobe)");
  v.field("g_back", s.gBack, NumberRange{-0.99, 0}, "asymmetry of the back-scattering lobe");
  v.field("back_weight", s.backWeight, NumberRange{0, 1}, "share of the back-scattering lobe");
  v.field("attenuation_clamp", s.attenuationClamp, NumberRange{0, 1},
          "Lu's ac (22): the light's attenuation is at most that of this fraction of the "
          "densest possible path toward the light (1: no clamp)");
  v.field("step_m", s.stepM, NumberRange{1, 10000}, "view-ray step near the camera, metres");
  v.field("step_growth", s.stepGrowth, NumberRange{0, 1},
          "extra step length per metre of distance (steps grow linearly)");
  v.field("max_steps", s.maxSteps, NumberRange{1, 4096}, "most steps along one view ray");
  // Each march is an unbiased draw of the pixel's grain; N of them, at their own positions in
  // the pixel and their own starts along the ray, average it away (N times the march's cost).
  v.field("samples", s.samples, NumberRange{1, 64},
          "marches per pixel, averaged, each at its own place in the pixel: more converge a "
          "still's grain and antialias its cloud edges, at that many times the cost");
  // At most 16: the short steps double in length (cloud_lighting.glsl), so 16 already spans
  // 1:32768 and more would overflow the shader's 1 << i.
  v.field("denoise", s.denoise,
          "filter the grain of one march per pixel out of a frame with no temporal reuse, "
          "keeping outlines (a 3 x 3 mean of the neighbours alike in depth); only with "
          "samples 1 and quality standard");
  v.field("light_steps", s.lightSteps, NumberRange{1, 16},
          "short steps toward the light, followed by one long step");
  // Each short step's one sample is a random draw of its optical depth, and a noisy optical
  // depth brightens on average (Jensen: the mean of exp(-tau) exceeds exp of the mean): 2
  // brings the default scene from 33 to 40 dB against the reference march, overcast from 35
  // to 51, for about a quarter more time (docs/clouds.md).
  v.field("light_split", s.lightSplit, NumberRange{1, 4},
          "samples per short light step, the long step taking twice as many (1: one each, "
          "the long step three; faster, with shadowed parts lighter than the reference's)");
  v.field("light_distance_m", s.lightDistanceM, NumberRange{1, 100000},
          "distance toward the light covered by the short steps, metres");
  v.field("transmittance_cutoff", s.transmittanceCutoff, NumberRange{0, 1},
          "stop marching a ray once its transmittance falls below this; what is left of it "
          "takes the light of the last sample (the cloud behind is opaque)");
  v.field("energy_conserving", s.energyConserving,
          "integrate each step's scattering analytically (Hillaire 2016)");
  v.field("scattering_octaves", s.scatteringOctaves, NumberRange{1, 8},
          "multiple-scattering octaves (Wrenninge); 1 is single scattering");
  v.field("multiple_scattering", s.multipleScattering, NumberRange{0, 4},
          "strength of the diffusion term for light scattered many times (sun, sky and "
          "ground; docs/cloud-model.md); 0 leaves the octaves and Tang's ambient alone");
  v.field("edge_sharpness", s.edgeSharpness, NumberRange{1, 32},
          "how much faster the density rises at a cloud's boundary than the noise does, "
          "1 - (1 - d)^k (1: the noise's own ramp)");
  v.field("shape_scale_km", s.shapeScaleKm, NumberRange{0.1, 1000},
          "ground size of one repeat of the shape noise, km");
  v.field("detail_scale_km", s.detailScaleKm, NumberRange{0.01, 100},
          "ground size of one repeat of the detail noise, km");
  v.field("wind_speed_ms", s.windSpeedMs, NumberRange{0, 200},
          "wind speed moving the cloud noise, m/s");
  v.field("wind_from", s.windFrom, NumberRange{-360, 360},
          "direction the wind blows from, degrees clockwise from north");
  v.section("low", s.low, "the low cloud layer (stratus, stratocumulus, cumulus)");
  v.section("mid", s.mid, "the mid cloud layer (altostratus, altocumulus)");
  v.check("mid", s.mid.baseM >= s.low.topM, "base_m must not lie below low.top_m");
}

template <class V>
void describe(V& v, WeatherRegion& s) {
  v.field("lat", s.lat, NumberRange{-90, 90}, "[south, north] latitudes in degrees");
  v.field("lon", s.lon, NumberRange{-180, 360}, "[west, east] longitudes in degrees");
  v.check("lat", s.lat[0] < s.lat[1], "south (first) must be below north (second)");
  v.check("lon", s.lon[0] < s.lon[1] && s.lon[1] - s.lon[0] <= 360,
          "west (first) must be below east (second), at most 360 degrees apart");
}

template <class V>
void describe(V& v, WeatherLevelSettings& s) {
  v.field("bottom_hpa", s.bottomHpa, NumberRange{1, 1100},
          "the layer's lower bound, hPa (the higher pressure)");
  v.field("top_hpa", s.topHpa, NumberRange{1, 1100}, "the layer's upper bound, hPa");
  v.field("rh_critical", s.rhCritical, NumberRange{0, 0.99},
          "critical relative humidity rh_cr of Lu (1)(2), as a fraction");
  v.check("top_hpa", s.topHpa < s.bottomHpa, "must be below bottom_hpa (higher up)");
}

template <class V>
void describe(V& v, WeatherAutomatonSettings& s) {
  v.field("step_s", s.stepS, NumberRange{10, 3600}, "scene time per automaton step, seconds");
  v.field("window_h", s.windowH, NumberRange{0.1, 240},
          "without forecast steps to run between: the automaton restarts every window_h "
          "hours, hours");
  v.field("lifetime_min", s.lifetimeMin, NumberRange{1, 1440},
          "mean life of a cloud cell before it dissolves (Dobashi's extinction), minutes");
  v.field("strength", s.strength, NumberRange{0, 1},
          "how far the automaton's smoothed density replaces the map's cover (0: not at all)");
}

template <class V>
void describe(V& v, WeatherSettings& s) {
  v.field("source", s.source,
          "where the weather map comes from: procedural (fbm cover), image (painted) or file "
          "(a GRIB2 or NetCDF forecast)");
  v.section("region", s.region,
            "the map's lat/lon bounds, both keys (absent: a square of camera_region_km centred "
            "on the camera, clipped to the data for source file)");
  v.field("camera_region_km", s.cameraRegionKm, NumberRange{10, 10000},
          "without region: the side of the square the map covers around the camera, km (the "
          "default reaches past the horizon of clouds up to 6.5 km seen from the ground)");
  v.field("cover_low", s.coverLow, NumberRange{0, 1}, "procedural: mean low-layer cover");
  v.field("cover_mid", s.coverMid, NumberRange{0, 1}, "procedural: mean mid-layer cover");
  v.field("spread", s.spread, NumberRange{0, 1},
          "procedural: how far the cover varies around its mean (0: uniform)");
  v.field("scale_km", s.scaleKm, NumberRange{1, 100000},
          "procedural: feature size of the cover pattern, km");
  v.field("seed", s.seed, NumberRange{0, 2147483647}, "procedural: noise seed");
  v.field("resolution", s.resolution, NumberRange{8, 8192},
          "procedural: map texels along the region's longer side");
  v.field("cloud_type", s.cloudType,
          "procedural: cloud type (the type channel: stratus and altostratus 0, "
          "stratocumulus and altocumulus 0.5, cumulus 1)");
  v.field("image", s.image, TextRule{0, 4096},
          "image source: RGBA PNG/EXR over the region (R low cover, G mid cover, B type, A "
          "density scale); row 0 is the north edge");
  v.field("file", s.file, TextRule{0, 4096},
          "file source: a GRIB2 or NetCDF forecast (relative paths are relative to the scene "
          "file)");
  v.field("cover", s.cover,
          "file source: cover from relative humidity (rh, Lu (1)(2)) or the model's own layer "
          "cloud cover (tcc)");
  v.section("low", s.low, "file source: the low layer's pressure levels and rh_cr");
  v.section("mid", s.mid, "file source: the mid layer's pressure levels and rh_cr");
  v.section("high", s.high, "file source: the high layer's pressure levels and rh_cr");
  v.field("advection", s.advection,
          "how the map moves with time: not at all (none), with the forecast file's wind at "
          "steering_hpa outside the file's steps (data), or with clouds.wind_speed_ms and "
          "wind_from (wind); between a file's steps the cover is interpolated");
  v.field("steering_hpa", s.steeringHpa, NumberRange{1, 1100},
          "file source: the pressure level whose wind (u, v) carries the clouds, hPa");
  v.field("time", s.time,
          "the instant (ISO 8601) the map shows at the scene's first frame, later frames moving "
          "on with the scene's time; absent or empty: the scene's time");
  v.field("local_radius_km", s.localRadiusKm, NumberRange{0.1, 200},
          "radius over which the cover around the camera is filtered into the local weather "
          "(overcast) that dims the ambient light and thickens the haze, km (Kozlov 5)");
  v.field("evolution", s.evolution,
          "clouds that grow and dissolve between forecast steps: none, or ca (a cellular "
          "automaton, Liu et al. 2015 after Dobashi et al. 2000)");
  v.section("automaton", s.automaton, "evolution ca: the cellular automaton's time steps");
  v.check("advection", s.advection != WeatherAdvection::Data || s.source == WeatherMapSource::File,
          "data needs source file (the wind comes from the forecast); wind uses the scene's");
  v.check("image", s.source != WeatherMapSource::Image || !s.image.empty(),
          "is required when source is image");
  v.check("file", s.source != WeatherMapSource::File || !s.file.empty(),
          "is required when source is file");
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
          "share of the stops the night sky's light at the horizon (twilight and moon) has lost "
          "since day that the automatic exposure makes up");
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
  v.section("sky", s.sky, "clear-sky model and Kozlov 3.1 geometry");
  v.section("atmosphere", s.atmosphere,
            "the planet's atmosphere for sky.model physical (Hillaire 2020)");
  v.section("ground", s.ground, "the ground below the horizon, lit and shadowed by the clouds");
  v.section("high_clouds", s.highClouds,
            "high-cloud layer: coefficient texture, normal map, altitude and wind (Kozlov)");
  v.section("clouds", s.clouds,
            "volumetric low and mid clouds: model, lighting and raymarch (Lu, Tang)");
  v.section("weather", s.weather, "the weather map: region, cover and cloud type");
  v.section("lighting", s.lighting, "refraction, light through the atmosphere, night and palette");
  v.check("output", !s.output.perception || s.camera.mode == CameraMode::Observer,
          "perception needs camera.mode observer: a geographic_topdown map has no observer's "
          "rays to label");
}

}  // namespace sky
