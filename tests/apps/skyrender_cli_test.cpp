// skyrender as a user runs it: outputs, exit codes, one-line errors with the key path, and
// no output file left behind by a failed run. The binary inherits SKY_VALIDATION=1 from
// ctest; any validation message on its stderr fails the test.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/core/files.h"
#include "tests/apps/cli_fixture.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

TEST_F(SkyrenderCli, RendersTheDefaultSceneIntoExrPngAndReport) {
  CliRun r = run("render --out " + out() + " --width 64 --height 36 --dump-graph " +
                 (mDir / "graph.dot").string());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("sky.exr"));

  LayeredImage exr = readExr(mDir / "out" / "sky.exr");
  EXPECT_EQ(exr.width, 64);
  EXPECT_EQ(exr.height, 36);
  ASSERT_NE(exr.find(""), nullptr);
  EXPECT_EQ(exr.find("")->channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  ASSERT_NE(exr.find("sky"), nullptr);

  Image8 png = readPng(mDir / "out" / "sky.png");
  EXPECT_EQ(png.width, 64);
  EXPECT_EQ(png.height, 36);

  nlohmann::json report = nlohmann::json::parse(readTextFile(mDir / "out" / "sky.json"));
  EXPECT_FALSE(report["device"].get<std::string>().empty());
  ASSERT_GE(report["passes"].size(), 1u);
  std::vector<std::string> passNames;
  for (const auto& p : report["passes"]) {
    passNames.push_back(p["name"]);
    EXPECT_GE(p["gpu_ms"].get<double>(), 0.0);
  }
  // By day (the sun 21 degrees up) the stars are drowned in the sky: no star passes. The
  // weather map is uploaded in the first frame's graph, by transfer passes. A still filters
  // its clouds' grain (cloud_denoise).
  EXPECT_THAT(passNames,
              ::testing::ElementsAre("sky_high_clouds", "upload weather_map", "upload weather_coarse",
                                     "cloud_ambient", "volumetric_clouds", "cloud_denoise",
                                     "cloud_shadow", "atmosphere_composite", "readback"));
  EXPECT_EQ(report["light"]["key"], "sun");
  EXPECT_EQ(report["time"], "2024-06-21T19:00:00+02:00");
  EXPECT_TRUE(report.contains("gpu_ms_total"));
  EXPECT_EQ(report["settings"]["output"]["width"], 64);

  std::string dot = readTextFile(mDir / "graph.dot");
  EXPECT_THAT(dot, HasSubstr("atmosphere_composite"));
  EXPECT_THAT(dot, HasSubstr("readback"));
}

// The report says what a frame paid besides drawing (docs/outputs.md): the first frame of a
// process carries the Renderer's construction and its pipelines, a later one neither, and
// the setup is the sum of its parts.
TEST_F(SkyrenderCli, TheReportSaysWhatTheFirstFramePaidBesidesDrawing) {
  CliRun r = run("render --out " + out() +
                 " --width 32 --height 18 --time 2024-06-21T19:00+02:00/2024-06-21T19:01+02:00/1m");
  ASSERT_EQ(r.rc, 0) << r.err;
  nlohmann::json first = nlohmann::json::parse(readTextFile(mDir / "out" / "sky_0001.json"));
  nlohmann::json second = nlohmann::json::parse(readTextFile(mDir / "out" / "sky_0002.json"));
  const auto& a = first["render_costs"];
  const auto& b = second["render_costs"];
  EXPECT_GT(a["renderer_ms"].get<double>(), 0.0);
  EXPECT_GT(a["renderer_pipelines_ms"].get<double>(), 0.0);
  EXPECT_LE(a["renderer_pipelines_ms"].get<double>(), a["renderer_ms"].get<double>());
  EXPECT_GT(a["textures_ms"].get<double>(), 0.0);  // the noise, loaded or baked
  EXPECT_NEAR(a["setup_ms"].get<double>(),
              a["renderer_pipelines_ms"].get<double>() + a["pipelines_ms"].get<double>() +
                  a["textures_ms"].get<double>() + a["lut_bake_gpu_ms"].get<double>(),
              1e-6);
  EXPECT_GE(a["render_ms"].get<double>(), a["pipelines_ms"].get<double>());
  EXPECT_EQ(b["renderer_ms"].get<double>(), 0.0);
  EXPECT_EQ(b["renderer_pipelines_ms"].get<double>(), 0.0);
  // The second frame finds every pipeline made and the textures on the GPU.
  EXPECT_LT(b["setup_ms"].get<double>(), 0.2 * a["setup_ms"].get<double>());
}

TEST_F(SkyrenderCli, NameTimeAndSetOverridesReachTheRender) {
  CliRun r = run("render --out " + out() +
                 " --name custom --width 32 --height 18 --time 2024-12-21T08:30:00+01:00 "
                 "--set sun.azimuth=90 --set sun.elevation=10 --set output.view=Raw");
  ASSERT_EQ(r.rc, 0) << r.err;
  nlohmann::json report = nlohmann::json::parse(readTextFile(mDir / "out" / "custom.json"));
  EXPECT_EQ(report["settings"]["time"], "2024-12-21T08:30:00+01:00");
  EXPECT_EQ(report["sun"]["azimuth_deg"], 90.0);
  EXPECT_EQ(report["ocio"]["view"], "Raw");
}

TEST_F(SkyrenderCli, ThePngIsDitheredUnlessTurnedOff) {
  // The default scene's twilight sky, 64 x 36: dithered, the PNG differs from the rounded one
  // in many codes but by one at most, and never in alpha; the EXR is the same.
  for (const char* dither : {"true", "false"}) {
    CliRun r = run(std::string("render --out ") + out() + " --name " +
                   (dither[0] == 't' ? "on" : "off") +
                   " --width 64 --height 36 --set output.dither=" + dither);
    ASSERT_EQ(r.rc, 0) << r.err;
  }
  const Image8 on = readPng(mDir / "out" / "on.png"), off = readPng(mDir / "out" / "off.png");
  ASSERT_EQ(on.pixels.size(), off.pixels.size());
  size_t changed = 0;
  for (size_t i = 0; i < on.pixels.size(); ++i) {
    const int diff = std::abs(int(on.pixels[i]) - int(off.pixels[i]));
    EXPECT_LE(diff, 1) << "byte " << i;
    if (i % 4 == 3) {
      EXPECT_EQ(diff, 0) << "alpha, byte " << i;
    }
    changed += diff > 0 ? 1 : 0;
  }
  // Triangular dither of one code moves the codes of values away from a code's middle, about a
  // third of them: 34 % of the colour bytes here.
  EXPECT_GT(changed, on.pixels.size() / 8) << "the dither is applied";
  EXPECT_EQ(readExr(mDir / "out" / "on.exr").layers.at(0).pixels,
            readExr(mDir / "out" / "off.exr").layers.at(0).pixels);
}

TEST_F(SkyrenderCli, SunFollowsTimeAndPlaceWithoutOverride) {
  fs::path scene = write("noon.yaml",
                         "output: {width: 16, height: 9}\n"
                         "camera: {latitude: 0, longitude: 0}\n"
                         "time: 2024-03-20T12:07:00Z\n");
  CliRun r = run("render " + scene.string() + " --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  nlohmann::json report = nlohmann::json::parse(readTextFile(mDir / "out" / "sky.json"));
  EXPECT_EQ(report["sun"]["source"], "ephemeris");
  EXPECT_GT(report["sun"]["elevation_deg"].get<double>(), 89.0);  // equinox noon on the equator
}

TEST_F(SkyrenderCli, BadConfigsExitTwoWithKeyPathAndWriteNothing) {
  expectBadInput(write("unknown.yaml", "output:\n  widht: 64\n").string(),
                 {"unknown.yaml:2:3", "output.widht", "did you mean 'width'"});
  expectBadInput(write("type.yaml", "camera:\n  latitude: north\n").string(),
                 {"type.yaml:2:", "camera.latitude", "number"});
  expectBadInput(write("range.yaml", "camera:\n  latitude: 95\n").string(),
                 {"range.yaml:2:", "camera.latitude", "95"});
  expectBadInput(write("broken.yaml", "output:\n  width: [64\n").string(),
                 {"broken.yaml:", "YAML"});
  expectBadInput(write("broken.json", "{\"output\": {\"width\": 64,}}").string(),
                 {"broken.json:1:", "JSON"});
  expectBadInput(write("range.json", "{\n  \"output\": {\"width\": 0}\n}").string(),
                 {"range.json:2:", "output.width"});
  expectBadInput((mDir / "missing.yaml").string(), {"missing.yaml", "cannot open"});
  expectBadInput(write("nan.yaml", "sky:\n  glow_size: .nan\n").string(),
                 {"nan.yaml:2:", "sky.glow_size"});
}

TEST_F(SkyrenderCli, BadArgumentsExitTwo) {
  expectBadInput("--width 0", {"output.width"});
  expectBadInput("--width 100000", {"output.width"});
  expectBadInput("--set camera.pitch=91", {"camera.pitch"});
  expectBadInput("--frobnicate", {"unknown option '--frobnicate'"});
  expectBadInput("--time 2024-01-01T00:00:00", {"time", "zone"});
  expectBadInput("--gpu no-such-device", {"--gpu no-such-device", "available"});
  expectBadInput("--set output.display=Nope", {"output.display", "Nope", "available: sRGB"});
  expectBadInput("--set output.view=Nope", {"output.view", "Nope", "AgX", "ACES 1.0 - SDR Video"});
  expectBadInput("--ocio " + (mDir / "none.ocio").string(), {"none.ocio"});
  CliRun r = run("frobnicate");
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("unknown command 'frobnicate'"));
}

TEST_F(SkyrenderCli, NoVulkanDeviceIsOneClearError) {
  // No driver manifest the loader can read: no device at all. Validation is off here because
  // the layer would report the loader's complaints, which is not what this test is about.
  CliRun r = run(
      "render --width 8 --height 8 --out " + out(),
      "env SKY_VALIDATION=0 VK_ICD_FILENAMES=/nonexistent.json VK_DRIVER_FILES=/nonexistent.json");
  EXPECT_EQ(r.rc, 1);
  EXPECT_EQ(r.err,
            "error: no Vulkan 1.3 device found (install mesa-vulkan-drivers for the CPU device "
            "lavapipe)\n");
  EXPECT_TRUE(outEmpty());
}

TEST_F(SkyrenderCli, BrokenShaderIsOneLineWithFileAndLineAndWritesNothing) {
  // A copy of shaders/ whose composite shader has an error on line 3.
  const fs::path shaders = mDir / "shaders";
  fs::copy(fs::path(std::getenv("SKY_DATA_DIR")) / "shaders", shaders, fs::copy_options::recursive);
  std::string text = readTextFile(shaders / "atmosphere_composite.comp");
  size_t secondLine = text.find('\n') + 1;
  text.insert(text.find('\n', secondLine) + 1, "this is not glsl;\n");
  std::ofstream(shaders / "atmosphere_composite.comp", std::ios::trunc) << text;
  CliRun r =
      run("render --width 8 --height 8 --out " + out(), "env SKY_SHADER_DIR=" + shaders.string());
  EXPECT_EQ(r.rc, 1);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("atmosphere_composite.comp:3: error:"));
  EXPECT_TRUE(outEmpty());
}

TEST_F(SkyrenderCli, DevicesListsThePickedDevice) {
  CliRun r = run("devices");
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("0: "));
  EXPECT_THAT(r.out, HasSubstr("<- picked"));
}

TEST_F(SkyrenderCli, UnwritableOutputFolderIsBadInput) {
  fs::path file = write("not_a_folder", "x");
  CliRun r = run("render --width 8 --height 8 --out " + file.string());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("not_a_folder"));
}

TEST_F(SkyrenderCli, ValidatePrintsSettingsThatReproduceTheScene) {
  fs::path scene =
      write("s.yaml", "output: {width: 64, height: 36}\nsun: {azimuth: 120, elevation: 8.5}\n");
  CliRun first = run("validate " + scene.string());
  ASSERT_EQ(first.rc, 0) << first.err;
  EXPECT_THAT(first.out, HasSubstr("vertical_fov"));  // defaults are filled in
  fs::path printed = write("printed.yaml", first.out);
  CliRun second = run("validate " + printed.string());
  ASSERT_EQ(second.rc, 0) << second.err;
  EXPECT_EQ(first.out, second.out);

  // And the printed file renders the same image as the original.
  ASSERT_EQ(run("render " + scene.string() + " --out " + out() + " --name a").rc, 0);
  ASSERT_EQ(run("render " + printed.string() + " --out " + out() + " --name b").rc, 0);
  EXPECT_EQ(readTextFile(mDir / "out" / "a.exr"), readTextFile(mDir / "out" / "b.exr"));

  fs::path json = write("s.json", "{\"output\": {\"width\": 64}}");
  CliRun j = run("validate " + json.string());
  ASSERT_EQ(j.rc, 0) << j.err;
  nlohmann::json parsed = nlohmann::json::parse(j.out);
  EXPECT_EQ(parsed["output"]["width"], 64);
}

TEST_F(SkyrenderCli, SchemaCommandPrintsTheCheckedInSchema) {
  CliRun r = run("schema");
  ASSERT_EQ(r.rc, 0);
  const fs::path schema =
      fs::path(std::getenv("SKY_DATA_DIR")) / "configs" / "schema" / "scene.schema.json";
  EXPECT_EQ(r.out, readTextFile(schema));
}

// The NREL SPA test case (Reda & Andreas 2008, table A4.1): zenith 50.11162, azimuth
// 194.34024 with their delta T of 67 s; ours differs by under 0.0005 degrees.
TEST_F(SkyrenderCli, EphemerisPrintsSunMoonAndLightAsJson) {
  CliRun r =
      run("ephemeris --lat 39.742476 --lon -105.1786 --time 2003-10-17T12:30:30-07:00 "
          "--height-m 1830.14 --pressure-hpa 820 --temperature-c 11");
  ASSERT_EQ(r.rc, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["time_utc"], "2003-10-17T19:30:30Z");
  EXPECT_NEAR(90.0 - j["sun"]["elevation_deg"].get<double>(), 50.11162, 5e-4);
  EXPECT_NEAR(j["sun"]["azimuth_deg"].get<double>(), 194.34024, 5e-4);
  EXPECT_NEAR(j["sun"]["distance_au"].get<double>(), 0.9965, 1e-3);
  for (const char* key : {"azimuth_deg", "elevation_deg", "distance_km", "illuminated_fraction",
                          "phase_angle_deg", "bright_limb_angle_deg"})
    EXPECT_TRUE(j["moon"].contains(key)) << key;
  const double az = j["moon"]["azimuth_deg"];
  EXPECT_GE(az, 0.0);
  EXPECT_LT(az, 360.0);
  EXPECT_EQ(j["light"]["key"], "sun");
  EXPECT_EQ(j["light"]["day_factor"], 1.0);

  // Defaults: sea level, 1010 hPa, 10 C; the full-moon midnight is lit by the moon.
  r = run("ephemeris --lat 47.37 --lon 8.54 --time 2024-06-22T01:08:00Z");
  ASSERT_EQ(r.rc, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["light"]["key"], "moon");
  EXPECT_GT(j["moon"]["illuminated_fraction"].get<double>(), 0.99);
  EXPECT_LT(j["light"]["day_factor"].get<double>(), 0.5);
}

TEST_F(SkyrenderCli, EphemerisBadInputIsOneLineExitTwo) {
  auto expectBad = [&](const std::string& args, const std::string& fragment) {
    CliRun r = run("ephemeris " + args);
    EXPECT_EQ(r.rc, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr(fragment));
    EXPECT_TRUE(r.out.empty());
  };
  expectBad("--lat 91 --lon 0 --time 2024-01-01T00:00Z", "--lat 91: out of range [-90, 90]");
  expectBad("--lat 0 --lon 180.5 --time 2024-01-01T00:00Z", "--lon 180.5: out of range");
  expectBad("--lat north --lon 0 --time 2024-01-01T00:00Z", "--lat 'north': expected a number");
  expectBad("--lat 0 --lon 0 --time 2024-02-30T00:00Z", "not a valid time: day out of range");
  expectBad("--lat 0 --lon 0 --time 2024-01-01T00:00", "missing time zone");
  expectBad("--lon 0 --time 2024-01-01T00:00Z", "--lat is required");
  expectBad("--lat 0 --lon 0 --time 2024-01-01T00:00Z --pressure-hpa -1", "--pressure-hpa -1");
}

TEST_F(SkyrenderCli, BadTimeRangesExitTwoAndWriteNothing) {
  expectBadInput("--time 2024-06-21T00:00Z/2024-06-22T00:00Z/-15m",
                 {"time", "'-15m' must be positive"});
  expectBadInput("--time 2024-06-21T00:00Z/2024-06-22T00:00Z/0s", {"time", "must be positive"});
  expectBadInput("--time 2024-06-22T00:00Z/2024-06-21T00:00Z/15m", {"time", "is before the start"});
  expectBadInput("--time 2024-06-21T00:00Z/2024-06-22T00:00Z/often", {"time", "not a duration"});
  expectBadInput("--time 2024-06-21T00:00Z/2024-06-22T00:00Z", {"time", "START/END/STEP"});
  expectBadInput(write("range.yaml",
                       "time:\n  start: 2024-06-21T00:00Z\n  end: 2024-06-20T00:00Z\n"
                       "  step: 1h\n")
                     .string(),
                 {"range.yaml:3:", "time.end", "is before the start"});
}

// A 24-hour time-lapse of the default scene: numbered frames, each with its own time, and no
// jump between consecutive frames. Bound: the mean absolute change of the display image
// between frames 5 minutes apart stays under 6 % of full scale. Measured on lavapipe: at most
// 3.0 %, near the end of civil twilight looking into the afterglow, where the palette really
// dims fastest; a pop of a palette keyframe, the key light or the night lift moves the image by
// 10-30 % at once.
TEST_F(SkyrenderCli, DayTimeLapseHasNoJumpsBetweenFrames) {
  // Without the volumetric clouds: in 5 minutes the wind carries them 3 km, so a cloud
  // crossing the sun is a real jump; their own time-lapse is tested in
  // tests/volumetric_clouds. Everything here is lighting.
  CliRun r = run("render --width 64 --height 36 --out " + out() +
                 " --set weather.cover_low=0"
                 " --time 2024-06-21T12:00:00+02:00/2024-06-22T12:00:00+02:00/5m");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote 289 frames sky_0001 ... sky_0289"));
  EXPECT_FALSE(fs::exists(mDir / "out" / "sky_0290.png"));
  nlohmann::json last = nlohmann::json::parse(readTextFile(mDir / "out" / "sky_0289.json"));
  EXPECT_EQ(last["time"], "2024-06-22T12:00:00+02:00");
  std::vector<std::string> keys;
  double worst = 0.0;
  int worstFrame = 0;
  Image8 previous = readPng(mDir / "out" / "sky_0001.png");
  for (int i = 2; i <= 289; ++i) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "sky_%04d", i);
    Image8 frame = readPng(mDir / "out" / (std::string(stem) + ".png"));
    ASSERT_EQ(frame.pixels.size(), previous.pixels.size());
    double sum = 0.0;
    for (size_t k = 0; k < frame.pixels.size(); ++k)
      sum += std::abs(int(frame.pixels[k]) - int(previous.pixels[k]));
    const double mean = sum / frame.pixels.size() / 255.0;
    if (mean > worst) worst = mean, worstFrame = i;
    previous = std::move(frame);
    nlohmann::json report =
        nlohmann::json::parse(readTextFile(mDir / "out" / (std::string(stem) + ".json")));
    if (keys.empty() || keys.back() != report["light"]["key"])
      keys.push_back(report["light"]["key"]);
  }
  EXPECT_LT(worst, 0.06) << "largest change between consecutive frames, at frame " << worstFrame;
  RecordProperty("largest_frame_change", std::to_string(worst));
  std::printf("largest mean change between frames: %.4f at frame %d\n", worst, worstFrame);
  // The key light went from sun to moon and back, once each.
  EXPECT_EQ(keys, (std::vector<std::string>{"sun", "moon", "sun"}));
}

TEST_F(SkyrenderCli, BadHighCloudAndAtmosphereInputExitsTwo) {
  const std::string tiny = "--width 16 --height 9 ";
  expectBadInput(tiny + "--set high_clouds.source=image --set high_clouds.coefficients=" +
                     (mDir / "none.png").string(),
                 {"high_clouds.coefficients", "none.png"});
  // An RGB image where RGBA is needed, and a non-square one.
  LayeredImage flat;
  flat.width = 16;
  flat.height = 16;
  flat.layers.push_back({"", {"R", "G", "B"}, std::vector<float>(16 * 16 * 3, 0.5f)});
  writeExr(mDir / "rgb.exr", flat);
  expectBadInput(tiny + "--set high_clouds.source=image --set high_clouds.coefficients=" +
                     (mDir / "rgb.exr").string(),
                 {"high_clouds.coefficients", "rgb.exr", "RGBA"});
  flat.width = 32;
  flat.layers[0] = {"", {"R", "G", "B", "A"}, std::vector<float>(32 * 16 * 4, 0.5f)};
  writeExr(mDir / "wide.exr", flat);
  expectBadInput(tiny + "--set high_clouds.source=image --set high_clouds.coefficients=" +
                     (mDir / "wide.exr").string(),
                 {"high_clouds.coefficients", "wide.exr", "square"});
  expectBadInput(tiny + "--set atmosphere.mie_scale_height_km=-1.2",
                 {"atmosphere.mie_scale_height_km", "out of range"});
  expectBadInput(tiny + "--set high_clouds.resolution=300",
                 {"high_clouds.resolution", "power of two"});
  // The Kozlov sky has no atmosphere LUTs: the frame's own images are the valid names.
  expectBadInput(tiny + "--debug-output transmittance_lut",
                 {"--debug-output transmittance_lut", "no such image", "valid: ", "beauty"});
  expectBadInput(tiny + "--debug-output nope", {"--debug-output nope", "valid: ", "beauty"});
}

TEST_F(SkyrenderCli, DebugOutputsAreWrittenBesideTheFrame) {
  CliRun r =
      run("render --width 32 --height 18 --name dbg --set sky.model=physical "
          "--set high_clouds.cover=0.5 --set high_clouds.resolution=64 "
          "--debug-output coefficients,normals --debug-output transmittance_lut "
          "--debug-output multiscattering_lut,sky_view_sun_lut,sky_view_moon_lut "
          "--debug-output aerial_perspective --out " +
          out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const fs::path dir = out();
  EXPECT_EQ(readExr(dir / "dbg.coefficients.exr").width, 64);
  EXPECT_EQ(readExr(dir / "dbg.normals.exr").height, 64);
  LayeredImage t = readExr(dir / "dbg.transmittance_lut.exr");
  EXPECT_EQ(t.width, 256);
  EXPECT_EQ(t.height, 64);
  EXPECT_EQ(readExr(dir / "dbg.multiscattering_lut.exr").width, 5 * 32);  // 5 blocks of 32x32
  EXPECT_EQ(readExr(dir / "dbg.sky_view_sun_lut.exr").width, 192);
  EXPECT_EQ(readExr(dir / "dbg.sky_view_moon_lut.exr").height, 108);
  LayeredImage ap = readExr(dir / "dbg.aerial_perspective.exr");
  EXPECT_EQ(ap.width, 32 * 32);
  EXPECT_EQ(ap.height, 32);
  LayeredImage frame = readExr(dir / "dbg.exr");
  ASSERT_NE(frame.find("high_clouds"), nullptr);
  EXPECT_EQ(frame.find("high_clouds")->channels.size(), 4u);
  const nlohmann::json report = nlohmann::json::parse(readTextFile(dir / "dbg.json"));
  EXPECT_EQ(report["debug_outputs"].size(), 7u);
  EXPECT_TRUE(report["high_cloud_textures"].contains("baked"));
}

TEST_F(SkyrenderCli, BadCloudAndWeatherInputExitsTwoWithFileLineAndKey) {
  const std::string tiny = " --width 16 --height 9";
  expectBadInput(
      write("layer.yaml", "clouds:\n  low:\n    base_m: 3000\n    top_m: 2000\n").string() + tiny,
      {"layer.yaml:4:", "clouds.low.top_m", "must be above base_m"});
  expectBadInput(write("stacked.yaml",
                       "clouds:\n  low: {base_m: 500, top_m: 2500}\n  mid: {base_m: 2000, "
                       "top_m: 5000}\n")
                         .string() +
                     tiny,
                 {"stacked.yaml:3:", "clouds.mid", "low.top_m"});
  expectBadInput(write("cover.yaml", "weather:\n  cover_low: 1.5\n").string() + tiny,
                 {"cover.yaml:2:", "weather.cover_low", "1.5", "out of range [0, 1]"});
  expectBadInput(
      write("region.yaml", "weather:\n  region:\n    lat: [50, 45]\n    lon: [5, 12]\n").string() +
          tiny,
      {"region.yaml:3:", "weather.region.lat", "south"});
  expectBadInput(write("model.yaml", "clouds:\n  model: schneider2015\n").string() + tiny,
                 {"model.yaml:2:", "clouds.model", "schneider2015", "lu2023 or tang2019"});
  expectBadInput(write("flag.yaml", "clouds:\n  energy_conserving: yes\n").string() + tiny,
                 {"flag.yaml:2:", "clouds.energy_conserving", "true or false"});
  expectBadInput("--set weather.cover_low=1.5" + tiny,
                 {"--set weather.cover_low=1.5", "weather.cover_low"});
  // An image path is resolved against the scene's folder and named as the scene wrote it.
  expectBadInput(
      write("painted.yaml", "weather:\n  source: image\n  image: missing_map.png\n").string() +
          tiny,
      {"weather.image", "missing_map.png"});
}

TEST_F(SkyrenderCli, CloudDebugOutputWithoutCloudsIsBadInput) {
  // The default scene has cumulus; without cover there is no cloud pass to look into.
  expectBadInput("--width 16 --height 9 --set weather.cover_low=0 --debug-output cloud_steps",
                 {"--debug-output cloud_steps", "no such image", "valid: ", "beauty"});
}

// A uniformly 70 % covered cumulus layer overhead: the frame carries the clouds layer, the
// report says the clouds were drawn and what the local weather was, and the clouds' debug
// images come out at their sizes.
TEST_F(SkyrenderCli, CloudyRenderWritesCloudLayerReportAndDebugImages) {
  fs::path scene = write("cloudy.yaml",
                         "output: {width: 32, height: 18, name: cloudy}\n"
                         "camera: {altitude_m: 0, heading: 200, pitch: 30}\n"
                         "time: 2024-06-21T12:00:00+02:00\n"
                         "weather: {cover_low: 0.7, spread: 0, cloud_type: cumulus}\n");
  CliRun r = run("render " + scene.string() + " --out " + out() +
                 " --debug-output cloud_steps,cloud_density_slice,weather_map");
  ASSERT_EQ(r.rc, 0) << r.err;
  const fs::path dir = out();
  LayeredImage exr = readExr(dir / "cloudy.exr");
  const ImageLayer* clouds = exr.find("clouds");
  ASSERT_NE(clouds, nullptr);
  EXPECT_EQ(clouds->channels, (std::vector<std::string>{"R", "G", "B", "A", "depth"}));
  EXPECT_EQ(exr.find("weather"), nullptr) << "the weather layer is for top-down renders only";
  // Looking 30 degrees up into 70 % cover: most pixels see cloud, and a cloud's depth is at
  // least the distance up to the layer's base (500 m).
  int cloudy = 0;
  for (size_t i = 0; i < clouds->pixels.size(); i += 5) {
    const float alpha = clouds->pixels[i + 3], depth = clouds->pixels[i + 4];
    EXPECT_GE(alpha, 0.0f);
    EXPECT_LE(alpha, 1.0f);
    if (alpha > 0.5f) {
      ++cloudy;
      EXPECT_GT(depth, 500.0f);
    }
  }
  EXPECT_GT(cloudy, 32 * 18 / 2);

  const nlohmann::json report = nlohmann::json::parse(readTextFile(dir / "cloudy.json"));
  EXPECT_EQ(report["volumetric_clouds"]["present"], true);
  // The weather at the camera (Kozlov 5): spread 0 makes the cover 0.7 everywhere, and it is
  // the overcast the light was set by.
  EXPECT_NEAR(report["local_weather"]["cover_low"].get<double>(), 0.7, 1e-3);
  EXPECT_NEAR(report["local_weather"]["overcast"].get<double>(), 0.7, 1e-3);
  EXPECT_EQ(report["local_weather"]["radius_km"], 5.0);
  EXPECT_NEAR(report["light"]["overcast"].get<double>(), 0.7, 1e-3);
  EXPECT_THAT(report["exr_layers"].get<std::vector<std::string>>(), ::testing::Contains("clouds"));
  std::vector<std::string> passNames;
  for (const auto& p : report["passes"]) passNames.push_back(p["name"]);
  EXPECT_THAT(passNames, ::testing::Contains("volumetric_clouds"));
  EXPECT_THAT(passNames, ::testing::Contains("cloud_density_slice"));

  LayeredImage steps = readExr(dir / "cloudy.cloud_steps.exr");
  EXPECT_EQ(steps.width, 32);
  EXPECT_EQ(steps.height, 18);
  LayeredImage slice = readExr(dir / "cloudy.cloud_density_slice.exr");
  EXPECT_EQ(slice.width, 512);
  EXPECT_EQ(slice.height, 128);
  LayeredImage map = readExr(dir / "cloudy.weather_map.exr");
  EXPECT_EQ(std::max(map.width, map.height), 256);  // weather.resolution along the longer side
}

// camera.mode geographic_topdown maps the weather region onto the image and adds the map's
// cover as a layer; `skyrender dsc` compares the two (Lu (28)). 64x64 pixels in 8x8 blocks:
// 64 blocks. Measured on lavapipe with the calibrated coverage: dsc 1.000, mae 0.028,
// correlation 0.996; the bounds only catch a render that no longer follows its map.
TEST_F(SkyrenderCli, TopDownRenderThenDscPrintsFourLines) {
  fs::path scene = write("topdown.yaml",
                         "output: {width: 64, height: 64, name: top}\n"
                         "camera: {mode: geographic_topdown}\n"
                         "time: 2024-06-21T12:00:00+02:00\n"
                         "weather: {cover_low: 0.5, spread: 1, cloud_type: cumulus}\n");
  CliRun r = run("render " + scene.string() + " --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  LayeredImage exr = readExr(mDir / "out" / "top.exr");
  ASSERT_NE(exr.find("weather"), nullptr);
  EXPECT_EQ(exr.find("weather")->channels, (std::vector<std::string>{"cover_low", "cover_mid"}));

  CliRun d = run("dsc " + (mDir / "out" / "top.exr").string());
  ASSERT_EQ(d.rc, 0) << d.err;
  std::istringstream lines(d.out);
  std::vector<std::string> names;
  std::map<std::string, double> values;
  std::string name;
  double value = 0.0;
  while (lines >> name >> value) {
    names.push_back(name);
    values[name] = value;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"dsc", "mae", "correlation", "blocks"})) << d.out;
  EXPECT_EQ(std::count(d.out.begin(), d.out.end(), '\n'), 4) << d.out;
  EXPECT_EQ(values["blocks"], 64.0);
  EXPECT_GT(values["dsc"], 0.8);
  EXPECT_LT(values["mae"], 0.1);
  EXPECT_GT(values["correlation"], 0.8);

  // A perspective render has no weather layer to compare with.
  ASSERT_EQ(run("render --width 16 --height 9 --name persp --out " + out()).rc, 0);
  CliRun bad = run("dsc " + (mDir / "out" / "persp.exr").string());
  EXPECT_EQ(bad.rc, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_THAT(bad.err, HasSubstr("persp.exr"));
  EXPECT_THAT(bad.err, HasSubstr("geographic_topdown"));
}

TEST_F(SkyrenderCli, HelpDocumentsEveryOption) {
  CliRun r = run("render --help");
  EXPECT_EQ(r.rc, 0);
  for (const char* opt :
       {"--out", "--name", "--width", "--height", "--time", "--set", "--dump-graph", "--gpu",
        "--ocio", "START/END/STEP", "--debug-output", "high_clouds.R/G/B/A", "--debug-passes",
        "--debug-output list"})
    EXPECT_THAT(r.out, HasSubstr(opt));
  r = run("ephemeris --help");
  EXPECT_EQ(r.rc, 0);
  for (const char* opt :
       {"--lat", "--lon", "--time", "--height-m", "--pressure-hpa", "--temperature-c"})
    EXPECT_THAT(r.out, HasSubstr(opt));
}

// The forecast example as a user runs it, at dusk: weather.time, the file's wind, the
// automaton and the high layer from the data all on, from the command line.
TEST_F(SkyrenderCli, ForecastExampleRendersAtDusk) {
  const fs::path example =
      fs::path(std::getenv("SKY_DATA_DIR")) / "configs" / "examples" / "gfs_east_asia.yaml";
  CliRun r = run("render " + example.string() + " --width 48 --height 27 --name dusk" +
                 " --time 2011-01-15T09:30:00Z --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(readTextFile(mDir / "out" / "dusk.json"));
  EXPECT_EQ(report["volumetric_clouds"]["present"], true);
  EXPECT_EQ(report["settings"]["weather"]["evolution"], "ca");
  EXPECT_LT(report["sun"]["elevation_deg"].get<double>(), 5.0);
  EXPECT_TRUE(report.contains("local_weather"));
}

TEST_F(SkyrenderCli, WeatherCommandWritesTheForecastMapAndFigures) {
  const fs::path grib = fs::path(std::getenv("SKY_DATA_DIR")) / "tests" / "data" / "weather" /
                        "gfs_2p5deg_r_gh_t_tcc_uv500.grib2";
  // Lu et al.'s region; the figures are those of tests/weather_layers on the same file.
  CliRun r = run("weather " + grib.string() + " --set weather.region.lat=[0,55]" +
                 " --set weather.region.lon=[39,105] --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("256x241 map over lat [0, 55], lon [39, 105], cover from rh"));
  // The layers' altitudes per texel from gh: 1000 hPa near sea level, 800 hPa near 2 km.
  EXPECT_THAT(r.out, HasSubstr("low  covered 0.343  mean cover 0.136  base 43 to 368 m  top "
                               "1847 to 2058 m"));
  EXPECT_THAT(r.out, HasSubstr("dsc vs tcc 0.608"));
  EXPECT_THAT(r.out, HasSubstr("high covered 0.575"));
  const LayeredImage exr = readExr(mDir / "out" / "gfs_2p5deg_r_gh_t_tcc_uv500.weather.exr");
  EXPECT_EQ(exr.width, 256);
  EXPECT_EQ(exr.height, 241);
  ASSERT_NE(exr.find(""), nullptr);
  // EXR keeps channels sorted by name.
  const ImageLayer& map = *exr.find("");
  EXPECT_EQ(map.channels, (std::vector<std::string>{
                              "cover_high", "cover_low", "cover_mid", "high_base_m", "high_top_m",
                              "low_base_m", "low_top_m", "mid_base_m", "mid_top_m", "type"}));
  // Every texel's layers are stacked: low base < low top = mid base < mid top = high base <
  // high top (the default levels share their bounds).
  const size_t n = map.channels.size();
  for (size_t i = 0; i < map.pixels.size(); i += n) {
    const float* p = &map.pixels[i];
    ASSERT_LT(p[5], p[6]);
    ASSERT_EQ(p[6], p[7]);
    ASSERT_LT(p[7], p[8]);
    ASSERT_EQ(p[8], p[3]);
    ASSERT_LT(p[3], p[4]);
    ASSERT_GT(p[4], 10000.0f) << "150 hPa lies above 10 km";
  }
  EXPECT_NE(exr.attributes.find("skylayers:high_top_m"), exr.attributes.end());
  EXPECT_TRUE(fs::exists(mDir / "out" / "gfs_2p5deg_r_gh_t_tcc_uv500.weather.png"));

  // A file that is not a forecast: exit 2, one line naming the key and the file.
  const fs::path bogus = write("bogus.grib2", "not a GRIB message");
  CliRun bad = run("weather " + bogus.string() + " --out " + out());
  EXPECT_EQ(bad.rc, 2);
  EXPECT_THAT(bad.err, HasSubstr("weather.file: "));
  EXPECT_THAT(bad.err, HasSubstr("bogus.grib2"));
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

}  // namespace
}  // namespace sky

namespace sky {
namespace {

// The names `render --debug-output list ARGS` prints, one per line after the header.
std::vector<std::string> listedImages(const CliRun& r) {
  std::vector<std::string> names;
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);  // the header
  while (std::getline(lines, line)) names.push_back(line.substr(0, line.find(' ')));
  return names;
}

// Issue 17: the frame graph is the one registry of debug outputs. Every image a default frame
// has is listed, can be asked for by its name and comes back; a name it lacks is one error
// line that lists the valid ones.
TEST_F(SkyrenderCli, EveryImageOfTheDefaultFrameCanBeRequestedByName) {
  const std::string tiny = " --width 32 --height 18 --set high_clouds.resolution=64";
  CliRun list = run("render --debug-output list" + tiny);
  ASSERT_EQ(list.rc, 0) << list.err;
  const std::vector<std::string> names = listedImages(list);
  for (const char* expected : {"beauty", "sky", "high_clouds", "clouds", "clouds_depth",
                               "cloud_steps", "cloud_shadow", "cloud_density_slice",
                               "weather_map", "high_cloud_coefficients", "cloud_noise_shape"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size())
      << "names are unique:\n"
      << list.out;
  EXPECT_TRUE(outEmpty()) << "list renders nothing";

  std::string all;
  for (const std::string& n : names) all += (all.empty() ? "" : ",") + n;
  CliRun r = run("render --name f --debug-output " + all + tiny + " --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  for (const std::string& n : names) {
    const fs::path file = fs::path(out()) / ("f." + n + ".exr");
    ASSERT_TRUE(fs::exists(file)) << file;
    const LayeredImage image = readExr(file);
    EXPECT_GT(image.width, 0) << n;
    ASSERT_FALSE(image.layers.empty()) << n;
  }
  EXPECT_EQ(readExr(fs::path(out()) / "f.beauty.exr").width, 32);
  EXPECT_EQ(readExr(fs::path(out()) / "f.cloud_noise_shape.exr").width, 128 * 128)
      << "a 3D image has its slices side by side";

  // Unknown: one line naming it and every valid name, nothing written.
  fs::remove_all(out());
  fs::create_directories(out());
  std::vector<std::string> fragments = {"--debug-output no_such_image", "valid: "};
  fragments.insert(fragments.end(), names.begin(), names.end());
  expectBadInput("--debug-output beauty,no_such_image" + tiny, fragments);
}

// With the physical sky and temporal reuse the frame has the atmosphere's LUTs and the
// clouds' histories, named by their part in the frame, each once.
TEST_F(SkyrenderCli, PhysicalTemporalFrameListsItsLutsAndHistories) {
  CliRun list = run(
      "render --debug-output list --width 32 --height 18 --set high_clouds.resolution=64 "
      "--set sky.model=physical --set clouds.temporal.mode=on");
  ASSERT_EQ(list.rc, 0) << list.err;
  const std::vector<std::string> names = listedImages(list);
  for (const char* expected :
       {"atmosphere_transmittance", "atmosphere_multiscattering", "atmosphere_sky_view_sun",
        "atmosphere_aerial_perspective", "clouds_history", "clouds_history_previous",
        "clouds_depth_history"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end())
        << expected << "\n"
        << list.out;
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size())
      << list.out;
  EXPECT_THAT(list.out, HasSubstr("cloud_temporal"));  // the pass that writes the history
}

// A buffer that holds an image (the stars' flux per pixel, after a header) is listed and
// read back like an image: one channel, the frame's size, the flux in V = 0 units.
TEST_F(SkyrenderCli, ABufferThatHoldsAnImageIsViewableByName) {
  const std::string night =
      std::string(std::getenv("SKY_DATA_DIR")) + "/configs/tests/night_full_moon.yaml";
  CliRun list = run("render " + night + " --debug-output list --width 64 --height 36");
  ASSERT_EQ(list.rc, 0) << list.err;
  EXPECT_THAT(list.out, HasSubstr("star_flux"));
  CliRun r = run("render " + night + " --name n --debug-output star_flux --width 64 --height 36 "
                 "--out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const LayeredImage flux = readExr(fs::path(out()) / "n.star_flux.exr");
  ASSERT_EQ(flux.width, 64);
  ASSERT_EQ(flux.height, 36);
  ASSERT_EQ(flux.layers.at(0).channels.size(), 1u);
  float most = 0.0f;
  for (float v : flux.layers[0].pixels) {
    EXPECT_GE(v, 0.0f);
    most = std::max(most, v);
  }
  // A wide night view holds stars down to magnitude 2 or so: flux 10^(-0.8) and more.
  EXPECT_GT(most, 0.1f);
}

// --debug-passes: one labelled contact sheet of every image, the frame-sized ones as EXR
// layers debug.<name>, the others in their own files.
TEST_F(SkyrenderCli, DebugPassesWritesAContactSheetAndLayers) {
  CliRun r = run(
      "render --name f --debug-passes --width 32 --height 18 "
      "--set high_clouds.resolution=64 --out " +
      out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const fs::path dir = out();
  const Image8 sheet = readPng(dir / "f.passes.png");
  // Four tiles across, each 384 wide with 8 of padding; rows of labelled tiles.
  EXPECT_EQ(sheet.width, 4 * (384 + 8) + 8);
  EXPECT_GT(sheet.height, 4 * 250);
  // Not blank: many distinct colours (images, false colour, text on the background).
  std::set<uint32_t> colours;
  for (size_t i = 0; i + 2 < sheet.pixels.size(); i += size_t(sheet.channels))
    colours.insert(uint32_t(sheet.pixels[i]) << 16 | uint32_t(sheet.pixels[i + 1]) << 8 |
                   sheet.pixels[i + 2]);
  EXPECT_GT(colours.size(), 1000u);
  const LayeredImage exr = readExr(dir / "f.exr");
  for (const char* layer : {"debug.beauty", "debug.clouds", "debug.cloud_steps", "debug.sky"})
    EXPECT_NE(exr.find(layer), nullptr) << layer;
  ASSERT_NE(exr.find("debug.cloud_steps"), nullptr);
  // Named as the pass names them (readExr lists channels other than R, G, B, A by name).
  EXPECT_EQ(exr.find("debug.cloud_steps")->channels, (std::vector<std::string>{"light", "view"}));
  EXPECT_TRUE(fs::exists(dir / "f.cloud_shadow.exr")) << "384 x 384: its own file";
  EXPECT_TRUE(fs::exists(dir / "f.weather_map.exr"));
  EXPECT_FALSE(fs::exists(dir / "f.beauty.exr")) << "a layer of f.exr";
}

}  // namespace
}  // namespace sky
