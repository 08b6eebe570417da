// YAML and JSON give the same Scene; printing the effective settings and loading them back
// gives an identical Scene.
#include <cmath>

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/scene/scene_io.h"
#include "tests/scene/scene_compare.h"

namespace sky {
namespace {

using test::expectSameScene;

TEST(SceneRoundTrip, EmptyFilesGiveDefaults) {
  Scene defaults;
  expectSameScene(loadSceneText("", ConfigFormat::Yaml, "e.yaml"), defaults);
  expectSameScene(loadSceneText("{}", ConfigFormat::Json, "e.json"), defaults);
  // The defaults themselves: an instant, and the built-in palette.
  EXPECT_FALSE(defaults.time.isRange());
  EXPECT_EQ(defaults.time.frameCount(), 1);
  EXPECT_EQ(defaults.lighting.palette, defaultPalette());
}

TEST(SceneRoundTrip, YamlAndJsonAgree) {
  // The same scene, with keys in other orders, the time range as interval text in one and
  // as a map in the other, and the palette in block style in one and flow style in the other.
  const char* yaml = R"(
output:
  width: 640
  height: 360.0
  name: "noon"
  exposure_ev: 0.5
camera:
  latitude: -33.8688
  longitude: 151.2093
  altitude_m: 12.5
  heading: -45
  pitch: 1e1
  vertical_fov: 70
time: 2024-12-21T12:00:00.5+11:00/2024-12-22T00:00+11:00/PT1H30M
sun:
  elevation: 40.25
  azimuth: 10
  disc_scale: 100
moon:
  azimuth: 300
  elevation: -4
  earthshine: 2.5
sky:
  glow_size: 0.2
lighting:
  turbidity: 0.35
  star_brightness: 1e3
  palette:
    - sun_elevation: -10
      sky_color: [0.1, 0.2, 0.3]
      fog_color: [0, 0, 0]
      glow_color: [1, 0.5, 0.25]
      cloud_lit: [1, 1, 1]
      cloud_dark: [0.5, 0.5, 0.5]
      ambient_top: [0.25, 0.25, 0.25]
      ambient_bottom: [0.125, 0.125, 0.125]
    - {sun_elevation: 45.5, sky_color: [0.07, 0.2, 0.65], fog_color: [0.5, 0.62, 0.8],
       glow_color: [1, 0.85, 0.65], cloud_lit: [0.9, 0.9, 0.92], cloud_dark: [0.45, 0.5, 0.6],
       ambient_top: [0.3, 0.4, 0.6], ambient_bottom: [0.15, 0.15, 0.14]}
)";
  const char* json = R"({
  "lighting": {"star_brightness": 1000, "turbidity": 0.35, "palette": [
    {"sun_elevation": -10, "sky_color": [0.1, 0.2, 0.3], "fog_color": [0, 0, 0],
     "glow_color": [1, 0.5, 0.25], "cloud_lit": [1, 1, 1], "cloud_dark": [0.5, 0.5, 0.5],
     "ambient_top": [0.25, 0.25, 0.25], "ambient_bottom": [0.125, 0.125, 0.125]},
    {"ambient_bottom": [0.15, 0.15, 0.14], "ambient_top": [0.3, 0.4, 0.6],
     "cloud_dark": [0.45, 0.5, 0.6], "cloud_lit": [0.9, 0.9, 0.92], "glow_color": [1, 0.85, 0.65],
     "fog_color": [0.5, 0.62, 0.8], "sky_color": [0.07, 0.2, 0.65], "sun_elevation": 45.5}]},
  "sky": {"glow_size": 0.2},
  "moon": {"earthshine": 2.5, "elevation": -4, "azimuth": 300},
  "sun": {"disc_scale": 100, "azimuth": 10, "elevation": 40.25},
  "time": {"step": "90m", "end": "2024-12-22T00:00:00+11:00",
           "start": "2024-12-21T12:00:00.5+11:00"},
  "camera": {"latitude": -33.8688, "longitude": 151.2093, "altitude_m": 12.5, "heading": -45,
             "pitch": 1e1, "vertical_fov": 70},
  "output": {"width": 640, "height": 360.0, "name": "noon", "exposure_ev": 0.5}
})";
  Scene a = loadSceneText(yaml, ConfigFormat::Yaml, "a.yaml");
  Scene b = loadSceneText(json, ConfigFormat::Json, "b.json");
  expectSameScene(a, b);
  EXPECT_EQ(a.output.height, 360);
  EXPECT_EQ(a.camera.pitch, 10.0);
  EXPECT_EQ(a.sun.azimuth, 10.0);
  EXPECT_EQ(a.sun.discScale, 100.0);
  EXPECT_EQ(a.moon.azimuth, 300.0);
  EXPECT_EQ(a.moon.elevation, -4.0);
  EXPECT_EQ(a.moon.discScale, 1.0);  // untouched keys keep their defaults
  EXPECT_EQ(a.lighting.pressureHpa, Scene().lighting.pressureHpa);
  EXPECT_EQ(a.lighting.starBrightness, 1000.0);
  ASSERT_EQ(a.lighting.palette.size(), 2u);
  EXPECT_EQ(a.lighting.palette[0].sunElevation, -10.0);
  EXPECT_EQ(a.lighting.palette[0].glowColor, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(a.lighting.palette[1].sunElevation, 45.5);
  EXPECT_EQ(a.lighting.palette[1].cloudLit, glm::vec3(0.9f, 0.9f, 0.92f));
  EXPECT_EQ(a.time.start.offsetMinutes, 11 * 60);
  EXPECT_EQ(a.time.start.subsecond, 0.5);
  ASSERT_TRUE(a.time.end.has_value());
  EXPECT_EQ(a.time.end->format(), "2024-12-22T00:00:00+11:00");
  EXPECT_EQ(a.time.stepSeconds, 5400.0);
  EXPECT_EQ(writeScene(a, ConfigFormat::Yaml), writeScene(b, ConfigFormat::Yaml));
}

TEST(SceneRoundTrip, WriteThenLoadIsIdentical) {
  Scene instant = test::unusualScene();  // every field set except a range
  instant.time.end.reset();
  instant.time.stepSeconds = 0.0;
  Scene onePaletteKey;
  onePaletteKey.lighting.palette = {defaultPalette()[4]};
  Scene tinyStep;  // a step printed as plain seconds with many digits
  tinyStep.time.end = tinyStep.time.start.plusSeconds(0.001);
  tinyStep.time.stepSeconds = 1e-7;
  for (const Scene& scene : {Scene(), test::unusualScene(), instant, onePaletteKey, tinyStep}) {
    for (ConfigFormat format : {ConfigFormat::Yaml, ConfigFormat::Json}) {
      SCOPED_TRACE(format == ConfigFormat::Yaml ? "YAML" : "JSON");
      std::string text = writeScene(scene, format);
      Scene back = loadSceneText(text, format, "printed");
      expectSameScene(back, scene);
      // Printing is a fixed point.
      EXPECT_EQ(writeScene(back, format), text);
    }
  }
}

// Failures `f` reports, without failing this test.
template <class F>
int failuresOf(F&& f) {
  ::testing::TestPartResultArray failures;
  {
    ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &failures);
    f();
  }
  return failures.size();
}

TEST(SceneRoundTrip, UnusualSceneDiffersFromTheDefaultEverywhere) {
  // Guards the round trip above: a field left at its default in unusualScene() would pass
  // it even if the reader or writer forgot that field: every scalar above and the palette's
  // length (3 against 8). 66 before the clouds: + camera mode, 24 cloud and 13 + 2 + 9 + 2
  // weather values; then high_clouds.cover_source and weather time, local radius, evolution
  // and automaton. The weather region counts once (given against absent) where its four
  // numbers counted before, and camera_region_km once; then atmosphere.aerosols (the ground
  // albedo moved from atmosphere to ground with its three channels) and output.exposure,
  // exposure_adaptation_s and night_look; then clouds.quality, clouds.light and
  // clouds.temporal's three; then clouds.samples.
  EXPECT_EQ(failuresOf([] { expectSameScene(test::unusualScene(), Scene()); }),
            66 + 1 + 24 + 13 + 2 + 9 + 2 + 1 + 4 - 4 + 1 + 1 + 1 + 3 + 5 + 1);
  const std::vector<PaletteKey> palette = test::unusualScene().lighting.palette;
  for (size_t i = 0; i < palette.size(); ++i) {
    const PaletteKey& k = palette[i];
    EXPECT_NE(k.sunElevation, 0.0) << i;
    for (const glm::vec3& c : {k.skyColor, k.fogColor, k.glowColor, k.cloudLit, k.cloudDark,
                               k.ambientTop, k.ambientBottom})
      EXPECT_NE(c, glm::vec3(0.0f)) << i;
    if (i > 0) {
      EXPECT_GT(k.sunElevation, palette[i - 1].sunElevation);
    }
  }
}

TEST(SceneRoundTrip, PaletteComparisonSeesEveryComponent) {
  // expectSamePalette must notice a change to any one number of any one key.
  const std::vector<PaletteKey> palette = test::unusualScene().lighting.palette;
  glm::vec3 PaletteKey::*colors[] = {&PaletteKey::skyColor,     &PaletteKey::fogColor,
                                     &PaletteKey::glowColor,    &PaletteKey::cloudLit,
                                     &PaletteKey::cloudDark,    &PaletteKey::ambientTop,
                                     &PaletteKey::ambientBottom};
  for (size_t i = 0; i < palette.size(); ++i) {
    std::vector<PaletteKey> changed = palette;
    changed[i].sunElevation += 1e-6;
    EXPECT_EQ(failuresOf([&] { test::expectSamePalette(changed, palette); }), 1) << i;
    for (glm::vec3 PaletteKey::*color : colors) {
      for (int c = 0; c < 3; ++c) {
        changed = palette;
        (changed[i].*color)[c] = std::nextafter((changed[i].*color)[c], 2e6f);
        EXPECT_EQ(failuresOf([&] { test::expectSamePalette(changed, palette); }), 1)
            << i << " component " << c;
      }
    }
  }
  EXPECT_EQ(failuresOf([&] { test::expectSamePalette(palette, palette); }), 0);
}

TEST(SceneRoundTrip, TimeFormsGiveTheSameRange) {
  const char* forms[] = {
      "time: 2024-06-21T00:00Z/2024-06-22T00:00Z/15m\n",
      "time: \"2024-06-21T00:00:00Z/2024-06-22T00:00:00+00:00/PT15M\"\n",
      "time:\n  start: 2024-06-21T00:00Z\n  end: 2024-06-22T00:00:00Z\n  step: 900s\n",
      "time: {step: 0.25h, start: \"2024-06-21T00:00:00Z\", end: 2024-06-22T00:00Z}\n",
  };
  for (const char* text : forms) {
    SCOPED_TRACE(text);
    Scene s = loadSceneText(text, ConfigFormat::Yaml, "t.yaml");
    EXPECT_EQ(s.time.start.format(), "2024-06-21T00:00:00Z");
    ASSERT_TRUE(s.time.isRange());
    EXPECT_EQ(s.time.end->format(), "2024-06-22T00:00:00Z");
    EXPECT_EQ(s.time.stepSeconds, 900.0);
    EXPECT_EQ(s.time.frameCount(), 97);
  }
  Scene json = loadSceneText(
      R"({"time": {"start": "2024-06-21T00:00Z", "end": "2024-06-22T00:00Z", "step": "15m"}})",
      ConfigFormat::Json, "t.json");
  EXPECT_EQ(json.time.stepSeconds, 900.0);
  EXPECT_EQ(loadSceneText("{\"time\": \"2024-06-21T00:00Z/2024-06-22T00:00Z/15m\"}",
                          ConfigFormat::Json, "t.json")
                .time.end,
            json.time.end);
  // A single instant stays an instant: no end, no step.
  Scene instant = loadSceneText("time: 2024-06-21T00:00Z\n", ConfigFormat::Yaml, "t.yaml");
  EXPECT_FALSE(instant.time.isRange());
  EXPECT_EQ(instant.time.stepSeconds, 0.0);
  // end == start is a one-frame range, kept as a range.
  Scene one =
      loadSceneText("time: 2024-06-21T00:00Z/2024-06-21T00:00Z/1s\n", ConfigFormat::Yaml, "t.yaml");
  EXPECT_TRUE(one.time.isRange());
  EXPECT_EQ(one.time.frameCount(), 1);
  // Ranges are printed as maps with the step in the short form.
  EXPECT_NE(writeScene(json, ConfigFormat::Yaml)
                .find("time:\n  start: \"2024-06-21T00:00:00Z\"\n  end: \"2024-06-22T00:00:00Z\"\n"
                      "  step: \"15m\"\nsun:\n"),
            std::string::npos);
}

TEST(SceneRoundTrip, PrintedYamlLooksLikeAScene) {
  Scene s;
  s.sun.azimuth = 200;
  s.sun.elevation = 35;
  // Two of the default keys keep the text short; every other value is the default.
  s.lighting.palette = {defaultPalette()[0], defaultPalette()[4]};
  EXPECT_EQ(writeScene(s, ConfigFormat::Yaml),
            "output:\n"
            "  width: 1280\n"
            "  height: 720\n"
            "  name: \"sky\"\n"
            "  exposure: \"auto\"\n"
            "  exposure_ev: 0\n"
            "  exposure_adaptation_s: 0\n"
            "  night_look: true\n"
            "  display: \"sRGB\"\n"
            "  view: \"AgX\"\n"
            "  dither: true\n"
            "  perception: false\n"
            "camera:\n"
            "  latitude: 47.37\n"
            "  longitude: 8.54\n"
            "  altitude_m: 500\n"
            "  heading: 180\n"
            "  pitch: 15\n"
            "  roll: 0\n"
            "  vertical_fov: 60\n"
            "  projection: \"perspective\"\n"
            "  mode: \"observer\"\n"
            "time: \"2024-06-21T12:00:00+02:00\"\n"
            "sun:\n"
            "  azimuth: 200\n"
            "  elevation: 35\n"
            "  angular_diameter: 0.53\n"
            "  disc_scale: 1\n"
            "moon:\n"
            "  disc_scale: 1\n"
            "  earthshine: 1\n"
            "sky:\n"
            "  model: \"kozlov\"\n"
            "  glow_size: 0.5\n"
            "  glow_exponent: 8\n"
            "  haze_height: 0.7\n"
            "atmosphere:\n"
            "  ground_radius_km: 6360\n"
            "  thickness_km: 100\n"
            "  rayleigh_scattering: [7.051, 13.827, 32.19]\n"
            "  rayleigh_scale_height_km: 8\n"
            "  aerosols: \"turbidity\"\n"
            "  mie_scattering: 3.996\n"
            "  mie_extinction: 4.4\n"
            "  mie_scale_height_km: 1.2\n"
            "  mie_anisotropy: 0.8\n"
            "  ozone_absorption: [2.703, 1.73, 0]\n"
            "  ozone_center_km: 25\n"
            "  ozone_half_width_km: 15\n"
            "ground:\n"
            "  albedo: [0.1, 0.12, 0.07]\n"
            "high_clouds:\n"
            "  source: \"procedural\"\n"
            "  style: \"cirrus\"\n"
            "  cover: 0\n"
            "  cover_map: \"\"\n"
            "  coefficients: \"\"\n"
            "  normals: \"\"\n"
            "  resolution: 1024\n"
            "  seed: 1\n"
            "  altitude_m: 9000\n"
            "  tile_size_km: 30\n"
            "  wind_speed_ms: 15\n"
            "  wind_from: 270\n"
            "  edge_glow_deg: 10\n"
            "  brightness: 1\n"
            "  cover_source: \"auto\"\n"
            "clouds:\n"
            "  quality: \"standard\"\n"
            "  temporal:\n"
            "    mode: \"off\"\n"
            "    block: 4\n"
            "    resolution: \"full\"\n"
            "  light: \"march\"\n"
            "  model: \"lu2023\"\n"
            "  coverage: \"calibrated\"\n"
            "  extinction: 0.1\n"
            "  g: 0.6\n"
            "  phase: \"dual_lobe\"\n"
            "  g_back: -0.3\n"
            "  back_weight: 0.2\n"
            "  attenuation_clamp: 0.02\n"
            "  step_m: 20\n"
            "  step_growth: 0.002\n"
            "  max_steps: 512\n"
            "  samples: 1\n"
            "  denoise: true\n"
            "  light_steps: 5\n"
            "  light_split: 2\n"
            "  light_distance_m: 1200\n"
            "  transmittance_cutoff: 0.05\n"
            "  energy_conserving: true\n"
            "  scattering_octaves: 3\n"
            "  multiple_scattering: 2.2\n"
            "  edge_sharpness: 4\n"
            "  shape_scale_km: 5\n"
            "  detail_scale_km: 0.4\n"
            "  wind_speed_ms: 10\n"
            "  wind_from: 270\n"
            "  low:\n"
            "    base_m: 500\n"
            "    top_m: 2500\n"
            "  mid:\n"
            "    base_m: 3000\n"
            "    top_m: 6500\n"
            "weather:\n"
            "  source: \"procedural\"\n"
            "  camera_region_km: 800\n"
            "  cover_low: 0\n"
            "  cover_mid: 0\n"
            "  spread: 0.5\n"
            "  scale_km: 150\n"
            "  seed: 1\n"
            "  resolution: 256\n"
            "  cloud_type: \"cumulus\"\n"
            "  image: \"\"\n"
            "  file: \"\"\n"
            "  cover: \"rh\"\n"
            "  low:\n"
            "    bottom_hpa: 1000\n"
            "    top_hpa: 800\n"
            "    rh_critical: 0.8\n"
            "  mid:\n"
            "    bottom_hpa: 800\n"
            "    top_hpa: 450\n"
            "    rh_critical: 0.65\n"
            "  high:\n"
            "    bottom_hpa: 450\n"
            "    top_hpa: 150\n"
            "    rh_critical: 0.8\n"
            "  advection: \"none\"\n"
            "  steering_hpa: 500\n"
            "  local_radius_km: 5\n"
            "  evolution: \"none\"\n"
            "  automaton:\n"
            "    step_s: 300\n"
            "    window_h: 6\n"
            "    lifetime_min: 30\n"
            "    strength: 1\n"
            "lighting:\n"
            "  pressure_hpa: 1010\n"
            "  temperature_c: 10\n"
            "  turbidity: 0.15\n"
            "  night_adaptation: 0.75\n"
            "  star_brightness: 1\n"
            "  star_extinction: 0.2\n"
            "  palette:\n"
            "    - sun_elevation: -90\n"
            "      sky_color: [0.0022, 0.0035, 0.008]\n"
            "      fog_color: [0.003, 0.0033, 0.004]\n"
            "      glow_color: [0, 0, 0]\n"
            "      cloud_lit: [0.003, 0.0032, 0.004]\n"
            "      cloud_dark: [0.0015, 0.0016, 0.002]\n"
            "      ambient_top: [0.002, 0.0025, 0.004]\n"
            "      ambient_bottom: [0.0012, 0.0012, 0.0012]\n"
            "    - sun_elevation: 0\n"
            "      sky_color: [0.075, 0.078, 0.141]\n"
            "      fog_color: [0.5, 0.3, 0.15]\n"
            "      glow_color: [2, 1, 0.8]\n"
            "      cloud_lit: [0.9, 0.45, 0.2]\n"
            "      cloud_dark: [0.15, 0.12, 0.15]\n"
            "      ambient_top: [0.08, 0.1, 0.18]\n"
            "      ambient_bottom: [0.04, 0.03, 0.03]\n");
}

TEST(SceneRoundTrip, PrintedJsonLooksLikeAScene) {
  Scene s;
  s.time.start = IsoTime::parse("2024-06-21T00:00:00+02:00").value();
  s.time.end = IsoTime::parse("2024-06-22T01:30:00.5+02:00").value();
  s.time.stepSeconds = 5400.5;
  s.moon.azimuth = 90;
  s.moon.elevation = 12.5;
  s.lighting.palette = {defaultPalette()[5]};
  EXPECT_EQ(writeScene(s, ConfigFormat::Json),
            "{\n"
            "  \"output\": {\n"
            "    \"width\": 1280,\n"
            "    \"height\": 720,\n"
            "    \"name\": \"sky\",\n"
            "    \"exposure\": \"auto\",\n"
            "    \"exposure_ev\": 0,\n"
            "    \"exposure_adaptation_s\": 0,\n"
            "    \"night_look\": true,\n"
            "    \"display\": \"sRGB\",\n"
            "    \"view\": \"AgX\",\n"
            "    \"dither\": true,\n"
            "    \"perception\": false\n"
            "  },\n"
            "  \"camera\": {\n"
            "    \"latitude\": 47.37,\n"
            "    \"longitude\": 8.54,\n"
            "    \"altitude_m\": 500,\n"
            "    \"heading\": 180,\n"
            "    \"pitch\": 15,\n"
            "    \"roll\": 0,\n"
            "    \"vertical_fov\": 60,\n"
            "    \"projection\": \"perspective\",\n"
            "    \"mode\": \"observer\"\n"
            "  },\n"
            "  \"time\": {\n"
            "    \"start\": \"2024-06-21T00:00:00+02:00\",\n"
            "    \"end\": \"2024-06-22T01:30:00.5+02:00\",\n"
            "    \"step\": \"5400.5s\"\n"
            "  },\n"
            "  \"sun\": {\n"
            "    \"angular_diameter\": 0.53,\n"
            "    \"disc_scale\": 1\n"
            "  },\n"
            "  \"moon\": {\n"
            "    \"azimuth\": 90,\n"
            "    \"elevation\": 12.5,\n"
            "    \"disc_scale\": 1,\n"
            "    \"earthshine\": 1\n"
            "  },\n"
            "  \"sky\": {\n"
            "    \"model\": \"kozlov\",\n"
            "    \"glow_size\": 0.5,\n"
            "    \"glow_exponent\": 8,\n"
            "    \"haze_height\": 0.7\n"
            "  },\n"
            "  \"atmosphere\": {\n"
            "    \"ground_radius_km\": 6360,\n"
            "    \"thickness_km\": 100,\n"
            "    \"rayleigh_scattering\": [7.051, 13.827, 32.19],\n"
            "    \"rayleigh_scale_height_km\": 8,\n"
            "    \"aerosols\": \"turbidity\",\n"
            "    \"mie_scattering\": 3.996,\n"
            "    \"mie_extinction\": 4.4,\n"
            "    \"mie_scale_height_km\": 1.2,\n"
            "    \"mie_anisotropy\": 0.8,\n"
            "    \"ozone_absorption\": [2.703, 1.73, 0],\n"
            "    \"ozone_center_km\": 25,\n"
            "    \"ozone_half_width_km\": 15\n"
            "  },\n"
            "  \"ground\": {\n"
            "    \"albedo\": [0.1, 0.12, 0.07]\n"
            "  },\n"
            "  \"high_clouds\": {\n"
            "    \"source\": \"procedural\",\n"
            "    \"style\": \"cirrus\",\n"
            "    \"cover\": 0,\n"
            "    \"cover_map\": \"\",\n"
            "    \"coefficients\": \"\",\n"
            "    \"normals\": \"\",\n"
            "    \"resolution\": 1024,\n"
            "    \"seed\": 1,\n"
            "    \"altitude_m\": 9000,\n"
            "    \"tile_size_km\": 30,\n"
            "    \"wind_speed_ms\": 15,\n"
            "    \"wind_from\": 270,\n"
            "    \"edge_glow_deg\": 10,\n"
            "    \"brightness\": 1,\n"
            "    \"cover_source\": \"auto\"\n"
            "  },\n"
            "  \"clouds\": {\n"
            "    \"quality\": \"standard\",\n"
            "    \"temporal\": {\n"
            "      \"mode\": \"off\",\n"
            "      \"block\": 4,\n"
            "      \"resolution\": \"full\"\n"
            "    },\n"
            "    \"light\": \"march\",\n"
            "    \"model\": \"lu2023\",\n"
            "    \"coverage\": \"calibrated\",\n"
            "    \"extinction\": 0.1,\n"
            "    \"g\": 0.6,\n"
            "    \"phase\": \"dual_lobe\",\n"
            "    \"g_back\": -0.3,\n"
            "    \"back_weight\": 0.2,\n"
            "    \"attenuation_clamp\": 0.02,\n"
            "    \"step_m\": 20,\n"
            "    \"step_growth\": 0.002,\n"
            "    \"max_steps\": 512,\n"
            "    \"samples\": 1,\n"
            "    \"denoise\": true,\n"
            "    \"light_steps\": 5,\n"
            "    \"light_split\": 2,\n"
            "    \"light_distance_m\": 1200,\n"
            "    \"transmittance_cutoff\": 0.05,\n"
            "    \"energy_conserving\": true,\n"
            "    \"scattering_octaves\": 3,\n"
            "    \"multiple_scattering\": 2.2,\n"
            "    \"edge_sharpness\": 4,\n"
            "    \"shape_scale_km\": 5,\n"
            "    \"detail_scale_km\": 0.4,\n"
            "    \"wind_speed_ms\": 10,\n"
            "    \"wind_from\": 270,\n"
            "    \"low\": {\n"
            "      \"base_m\": 500,\n"
            "      \"top_m\": 2500\n"
            "    },\n"
            "    \"mid\": {\n"
            "      \"base_m\": 3000,\n"
            "      \"top_m\": 6500\n"
            "    }\n"
            "  },\n"
            "  \"weather\": {\n"
            "    \"source\": \"procedural\",\n"
            "    \"camera_region_km\": 800,\n"
            "    \"cover_low\": 0,\n"
            "    \"cover_mid\": 0,\n"
            "    \"spread\": 0.5,\n"
            "    \"scale_km\": 150,\n"
            "    \"seed\": 1,\n"
            "    \"resolution\": 256,\n"
            "    \"cloud_type\": \"cumulus\",\n"
            "    \"image\": \"\",\n"
            "    \"file\": \"\",\n"
            "    \"cover\": \"rh\",\n"
            "    \"low\": {\n"
            "      \"bottom_hpa\": 1000,\n"
            "      \"top_hpa\": 800,\n"
            "      \"rh_critical\": 0.8\n"
            "    },\n"
            "    \"mid\": {\n"
            "      \"bottom_hpa\": 800,\n"
            "      \"top_hpa\": 450,\n"
            "      \"rh_critical\": 0.65\n"
            "    },\n"
            "    \"high\": {\n"
            "      \"bottom_hpa\": 450,\n"
            "      \"top_hpa\": 150,\n"
            "      \"rh_critical\": 0.8\n"
            "    },\n"
            "    \"advection\": \"none\",\n"
            "    \"steering_hpa\": 500,\n"
            "    \"local_radius_km\": 5,\n"
            "    \"evolution\": \"none\",\n"
            "    \"automaton\": {\n"
            "      \"step_s\": 300,\n"
            "      \"window_h\": 6,\n"
            "      \"lifetime_min\": 30,\n"
            "      \"strength\": 1\n"
            "    }\n"
            "  },\n"
            "  \"lighting\": {\n"
            "    \"pressure_hpa\": 1010,\n"
            "    \"temperature_c\": 10,\n"
            "    \"turbidity\": 0.15,\n"
            "    \"night_adaptation\": 0.75,\n"
            "    \"star_brightness\": 1,\n"
            "    \"star_extinction\": 0.2,\n"
            "    \"palette\": [\n"
            "      {\n"
            "        \"sun_elevation\": 10,\n"
            "        \"sky_color\": [0.096, 0.155, 0.29],\n"
            "        \"fog_color\": [0.68, 0.76, 0.72],\n"
            "        \"glow_color\": [3.4, 3.2, 2.9],\n"
            "        \"cloud_lit\": [1, 0.75, 0.5],\n"
            "        \"cloud_dark\": [0.35, 0.35, 0.45],\n"
            "        \"ambient_top\": [0.2, 0.25, 0.4],\n"
            "        \"ambient_bottom\": [0.1, 0.08, 0.07]\n"
            "      }\n"
            "    ]\n"
            "  }\n"
            "}\n");
}

TEST(SceneRoundTrip, OptionalPlacementsArePrintedOnlyWhenSet) {
  for (ConfigFormat format : {ConfigFormat::Yaml, ConfigFormat::Json}) {
    std::string text = writeScene(Scene(), format);
    EXPECT_EQ(text.find("azimuth"), std::string::npos) << text;
    EXPECT_EQ(text.find("\"elevation\""), std::string::npos) << text;
    EXPECT_EQ(text.find(" elevation:"), std::string::npos) << text;
  }
  std::string json = writeScene(Scene(), ConfigFormat::Json);
  EXPECT_NE(json.find("\"sun\": {\n    \"angular_diameter\": 0.53,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"moon\": {\n    \"disc_scale\": 1,"), std::string::npos) << json;
  Scene moonOnly;
  moonOnly.moon.azimuth = 1;
  moonOnly.moon.elevation = 2;
  nlohmann::json j = sceneToJson(moonOnly);
  EXPECT_FALSE(j["sun"].contains("azimuth"));
  EXPECT_EQ(j["moon"]["azimuth"], 1);
  EXPECT_EQ(j["moon"]["elevation"], 2);
}

TEST(SceneRoundTrip, PrintedJsonIsJson) {
  Scene s = test::unusualScene();
  nlohmann::json parsed = nlohmann::json::parse(writeScene(s, ConfigFormat::Json));
  EXPECT_EQ(parsed["output"]["display"], "Display \"P3\"");
  EXPECT_EQ(parsed["output"]["width"], 64);
  EXPECT_TRUE(parsed["output"]["width"].is_number_integer());
  EXPECT_EQ(parsed["sun"]["azimuth"], 200.1);
  EXPECT_EQ(parsed["moon"]["elevation"], -0.30000000000000004);
  EXPECT_EQ(parsed["time"]["start"], "2024-12-21T05:30:00.125-03:30");
  EXPECT_EQ(parsed["time"]["end"], "2024-12-21T10:30:00.375+01:00");
  EXPECT_EQ(parsed["time"]["step"], "61.3s");
  const nlohmann::json& palette = parsed["lighting"]["palette"];
  ASSERT_TRUE(palette.is_array());
  ASSERT_EQ(palette.size(), 3u);
  for (const nlohmann::json& key : palette) {
    EXPECT_TRUE(key.is_object());
    EXPECT_EQ(key.size(), 8u);
  }
  EXPECT_EQ(palette[0]["sun_elevation"], -89.99999999999999);
  EXPECT_EQ(palette[0]["sky_color"][0], 1e-40);  // the float's shortest text
  EXPECT_EQ(palette[2]["sun_elevation"], 90);
  EXPECT_TRUE(palette[2]["sun_elevation"].is_number_integer());
}

TEST(SceneRoundTrip, SceneToJsonForReports) {
  Scene s = test::unusualScene();
  nlohmann::json j = sceneToJson(s);
  EXPECT_EQ(j["output"]["width"], 64);
  EXPECT_TRUE(j["output"]["width"].is_number_integer());
  EXPECT_EQ(j["camera"]["heading"], 1.0 / 3.0);
  // The float's shortest text, not 0.10000000149.
  EXPECT_EQ(j["lighting"]["palette"][0]["sky_color"][2], 0.1);
  EXPECT_EQ(j["sun"]["elevation"], 1e-7);
  EXPECT_EQ(j["time"]["start"], "2024-12-21T05:30:00.125-03:30");
  EXPECT_EQ(j["lighting"]["star_extinction"], 1e-300);
  EXPECT_FALSE(sceneToJson(Scene())["sun"].contains("azimuth"));
  EXPECT_EQ(sceneToJson(Scene())["time"], "2024-06-21T12:00:00+02:00");
  // The report reads back as the same scene.
  test::expectSameScene(loadSceneText(j.dump(), ConfigFormat::Json, "report.json"), s);
}

TEST(SceneRoundTrip, HalfAPlacementCannotBePrinted) {
  Scene sun;
  sun.sun.azimuth = 10;
  Scene moon;
  moon.moon.elevation = 10;
  for (const Scene& s : {sun, moon}) {
    try {
      writeScene(s, ConfigFormat::Yaml);
      ADD_FAILURE() << "expected an internal error";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Internal);
    }
  }
}

}  // namespace
}  // namespace sky
