// What a new user meets in the first hour (issue 13), each as the user hits it with the
// shipped binary: scene files that are folders or empty, forecast files and procedural
// clouds away from the default region, printed scenes that must render from anywhere, error
// messages and output folders after a failure, each command's help, numbers that must read
// well, interrupts and an unwritable cache.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <regex>
#include <thread>

#include <nlohmann/json.hpp>

#include "engine/io/exr.h"
#include "engine/scene/scene_io.h"
#include "tests/apps/cli_fixture.h"
#include "tests/weather_files/grib_writer.h"

extern char** environ;

namespace sky {
namespace {

nlohmann::json readJson(const fs::path& p) {
  return nlohmann::json::parse(readTextFile(p));
}

fs::path dataDir() {
  return fs::path(std::getenv("SKY_DATA_DIR"));
}

fs::path gfsFile() {
  return dataDir() / "tests" / "data" / "weather" / "gfs_2p5deg_r_gh_t_tcc_uv500.grib2";
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A North American Lambert conformal grid like NAM's (30 x 25 points 40 km apart, standard
// parallels 25N, first point 20N 120W), with relative humidity on one level in each of the
// default layers (925, 700 and 300 hPa) so every layer has data.
void writeLambertForecast(const fs::path& file) {
  constexpr long kNx = 30, kNy = 25;
  for (long level : {925L, 700L, 300L}) {
    std::vector<double> rh(kNx * kNy);
    for (long j = 0; j < kNy; ++j)
      for (long i = 0; i < kNx; ++i) rh[size_t(j * kNx + i)] = 60.0 + 40.0 * ((i + j) % 7) / 6.0;
    test::GribWriter w("regular_ll_pl_grib2");
    w.set("gridDefinitionTemplateNumber", 30L)
        .set("shapeOfTheEarth", 6L)
        .set("Nx", kNx)
        .set("Ny", kNy)
        .set("latitudeOfFirstGridPointInDegrees", 20.0)
        .set("longitudeOfFirstGridPointInDegrees", 240.0)
        .set("LaDInDegrees", 25.0)
        .set("LoVInDegrees", 265.0)
        .set("Latin1InDegrees", 25.0)
        .set("Latin2InDegrees", 25.0)
        .set("DxInMetres", 40000.0)
        .set("DyInMetres", 40000.0)
        .set("iScansNegatively", 0L)
        .set("jScansPositively", 1L)
        .set("numberOfDataPoints", kNx * kNy)
        .set("typeOfLevel", "isobaricInhPa")
        .set("level", level)
        .set("shortName", "r")
        .values(rh);
    w.appendTo(file);
  }
}

// "map over lat [S, N], lon [W, E]" as printed by skyrender weather.
struct PrintedRegion {
  double south = 0, north = 0, west = 0, east = 0;
};
PrintedRegion printedRegion(const std::string& out) {
  std::smatch m;
  const std::regex re(
      R"(map over lat \[([-0-9.e]+), ([-0-9.e]+)\], lon \[([-0-9.e]+), ([-0-9.e]+)\])");
  EXPECT_TRUE(std::regex_search(out, m, re)) << out;
  if (m.size() != 5) return {};
  return {std::stod(m[1]), std::stod(m[2]), std::stod(m[3]), std::stod(m[4])};
}

// ---- 2.1 scene files that are not scenes ---------------------------------------------------

TEST_F(SkyrenderCli, AFolderNamedLikeASceneIsAnError) {
  fs::create_directories(mDir / "s.yaml");
  CliRun r = run("render " + (mDir / "s.yaml").string() + " --out " + out());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("s.yaml: is a directory"));
  EXPECT_EQ(count(r.err, "\n"), 1u) << r.err;
  EXPECT_TRUE(outEmpty());
  r = run("validate " + (mDir / "s.yaml").string());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("is a directory"));
}

TEST_F(SkyrenderCli, AnEmptySceneFileIsAnErrorThatSaysHowToGetTheDefaults) {
  for (const auto& [name, text] :
       {std::pair{"empty.yaml", ""}, {"comments.yaml", "# nothing\n\n"}, {"empty.json", "  \n"}}) {
    CliRun r = run("render " + write(name, text).string() + " --out " + out());
    EXPECT_EQ(r.rc, 2) << name;
    EXPECT_THAT(r.err, HasSubstr(std::string(name) + ": the scene file is empty"));
    EXPECT_THAT(r.err, HasSubstr("give no scene file"));
    EXPECT_THAT(r.err, HasSubstr("write {}"));
    EXPECT_TRUE(outEmpty());
  }
  // {} is a scene of the format's defaults, as the message says.
  CliRun r = run("render " + write("defaults.yaml", "{}\n").string() +
                 " --width 16 --height 9 --out " + out());
  EXPECT_EQ(r.rc, 0) << r.err;
}

// ---- 2.2 and 2.3 the weather region ---------------------------------------------------------

TEST_F(SkyrenderCli, WeatherWithoutARegionShowsTheFilesWholeGrid) {
  const fs::path nam = mDir / "nam_lambert.grib2";
  writeLambertForecast(nam);
  CliRun r = run("weather " + nam.string() + " --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const PrintedRegion p = printedRegion(r.out);
  // The grid's first point is 20N 120W, and it runs 1160 x 960 km north-east of it.
  EXPECT_GT(p.south, 19.0);
  EXPECT_LT(p.north, 32.0);
  EXPECT_GT(p.north - p.south, 5.0);
  EXPECT_GT(p.east - p.west, 8.0);
  EXPECT_GT(std::remainder(p.west - (-120.0), 360.0), -1.0);
  EXPECT_TRUE(fs::exists(mDir / "out" / "nam_lambert.weather.exr"));

  // A regular global grid: all of it.
  r = run("weather " + gfsFile().string() + " --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("map over lat [-90, 90], lon [0, 360]"));
}

TEST_F(SkyrenderCli, AForecastRenderWithoutARegionTakesTheSquareAroundTheCamera) {
  // The default camera (47.37N 8.54E) over the global GFS file: 800 km around it.
  CliRun r = run("render --width 32 --height 18 --set weather.source=file --set weather.file=" +
                 gfsFile().string() + " --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const nlohmann::json map = readJson(mDir / "out" / "sky.json")["weather_map"];
  EXPECT_EQ(map["given"], false);
  const double south = map["region"]["lat"][0], north = map["region"]["lat"][1];
  const double west = map["region"]["lon"][0], east = map["region"]["lon"][1];
  EXPECT_NEAR(north - south, 800.0 / 111.195, 1e-3);
  EXPECT_NEAR(0.5 * (south + north), 47.37, 0.1);
  EXPECT_NEAR(0.5 * (west + east), 8.54, 0.1);
  EXPECT_NEAR((east - west) * std::cos(47.37 * M_PI / 180.0), 800.0 / 111.195, 0.1);

  // Clipped to the data: a Lambert grid over the western US seen from 28N 110W.
  const fs::path nam = mDir / "nam_lambert.grib2";
  writeLambertForecast(nam);
  r = run("render --width 32 --height 18 --set weather.source=file --set weather.file=" +
          nam.string() + " --set camera.latitude=28 --set camera.longitude=-110 --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const nlohmann::json clipped = readJson(mDir / "out" / "sky.json")["weather_map"];
  EXPECT_GT(clipped["region"]["lat"][0].get<double>(), 20.0);
  EXPECT_LT(clipped["region"]["lat"][1].get<double>() - clipped["region"]["lat"][0].get<double>(),
            800.0 / 111.195 - 0.5);

  // Far from the data: one line that says what to do.
  fs::remove_all(mDir / "out");
  fs::create_directories(mDir / "out");
  r = run("render --width 32 --height 18 --set weather.source=file --set weather.file=" +
          nam.string() + " --set camera.latitude=-30 --set camera.longitude=20 --out " + out());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("weather.region: not given, and the data"));
  EXPECT_THAT(r.err, HasSubstr("set weather.region or move the camera"));
  EXPECT_TRUE(outEmpty());
}

TEST_F(SkyrenderCli, ProceduralCloudsComeAlongWhereverTheCameraGoes) {
  CliRun r =
      run("render --width 64 --height 36 --set camera.latitude=30 --set camera.longitude=116"
          " --out " +
          out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const nlohmann::json report = readJson(mDir / "out" / "sky.json");
  EXPECT_EQ(report["volumetric_clouds"]["present"], true);
  ASSERT_TRUE(report.contains("weather_map"));
  const double south = report["weather_map"]["region"]["lat"][0];
  const double north = report["weather_map"]["region"]["lat"][1];
  EXPECT_LT(south, 30.0);
  EXPECT_GT(north, 30.0);
  // Clouds in the picture, not only on the map.
  const LayeredImage exr = readExr(mDir / "out" / "sky.exr");
  const ImageLayer* clouds = exr.find("clouds");
  ASSERT_NE(clouds, nullptr);
  double opacity = 0.0;
  for (size_t i = 3; i < clouds->pixels.size(); i += clouds->channels.size())
    opacity += clouds->pixels[i];
  EXPECT_GT(opacity / double(exr.width * exr.height), 0.1) << "mean cloud opacity";
}

// ---- 2.4 printed scenes render from anywhere ------------------------------------------------

TEST_F(SkyrenderCli, ValidatePrintsPathsThatWorkFromAnywhere) {
  const fs::path example = dataDir() / "configs" / "examples" / "gfs_east_asia.yaml";
  CliRun r = run("validate " + example.string());
  ASSERT_EQ(r.rc, 0) << r.err;
  const fs::path printed = write("x.yaml", r.out);
  const Scene scene = loadSceneFile(printed);
  EXPECT_TRUE(fs::path(scene.weather.file).is_absolute()) << scene.weather.file;
  EXPECT_TRUE(fs::exists(scene.weather.file));
  r = run("render " + printed.string() + " --width 24 --height 14 --out " + out());
  EXPECT_EQ(r.rc, 0) << r.err;
}

// ---- 2.5 errors name the user's files; a failed run leaves no folder ------------------------

TEST_F(SkyrenderCli, AWriteErrorNamesTheFileAskedForNotATemporary) {
  // /proc/self exists but takes no files: every output write fails.
  CliRun r = run("render --width 16 --height 9 --out /proc/self");
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, Not(HasSubstr(".tmp-")));
  EXPECT_THAT(r.err, HasSubstr("/proc/self/sky."));
}

TEST_F(SkyrenderCli, AFailedRenderRemovesTheFoldersItCreated) {
  const fs::path fresh = mDir / "new" / "deeper";
  CliRun r =
      run("render --width 16 --height 9 --set weather.source=file --set "
          "weather.file=/no/such.grib2 --out " +
          fresh.string());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("weather.file"));
  EXPECT_FALSE(fs::exists(mDir / "new")) << "the run made it and wrote nothing into it";
  // A folder that was there before stays.
  r =
      run("render --width 16 --height 9 --set weather.source=file --set "
          "weather.file=/no/such.grib2 --out " +
          out());
  EXPECT_EQ(r.rc, 2);
  EXPECT_TRUE(fs::is_directory(mDir / "out"));
}

// ---- 2.6 help and arguments -----------------------------------------------------------------

TEST_F(SkyrenderCli, EachCommandHasItsOwnHelp) {
  std::vector<std::string> pages;
  for (const char* command :
       {"render", "validate", "ephemeris", "schema", "devices", "dsc", "weather"}) {
    CliRun r = run(std::string(command) + " --help");
    EXPECT_EQ(r.rc, 0) << command;
    EXPECT_THAT(r.out, HasSubstr(std::string("usage: skyrender ") + command)) << command;
    for (const std::string& other : pages) EXPECT_NE(r.out, other) << command;
    pages.push_back(r.out);
  }
  CliRun r = run("--help");
  EXPECT_EQ(r.rc, 0);
  for (const char* command : {"render", "validate", "ephemeris", "schema", "devices", "dsc",
                              "weather", "--version", "SKY_CACHE_DIR"})
    EXPECT_THAT(r.out, HasSubstr(command));
  // The EXR's layers as they are stored.
  r = run("render --help");
  EXPECT_THAT(r.out, HasSubstr("in 32-bit float"));
  EXPECT_THAT(r.out, Not(HasSubstr("Rec.709, half float")));
}

TEST_F(SkyrenderCli, VersionAndArgumentsAreCheckedAlike) {
  CliRun r = run("--version");
  EXPECT_EQ(r.rc, 0);
  EXPECT_THAT(r.out, HasSubstr("skyrender 0."));
  for (const char* command : {"devices foo", "schema foo", "ephemeris foo"}) {
    r = run(command);
    EXPECT_EQ(r.rc, 2) << command;
    EXPECT_THAT(r.err, HasSubstr("takes no arguments: 'foo'")) << command;
    EXPECT_THAT(r.err, HasSubstr("--help")) << command;
  }
  r = run("dsc");
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("dsc needs one render EXR"));
  r = run("weather a.grib2 b.grib2");
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("weather takes one forecast file, got also 'b.grib2'"));
  r = run("render --nope");
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("render: unknown option '--nope' (see skyrender render --help)"));
}

// ---- 2.7 numbers that read well ---------------------------------------------------------------

TEST_F(SkyrenderCli, DscRefusesTooFewBlocksForACorrelation) {
  const fs::path example = dataDir() / "configs" / "examples" / "topdown_dsc.yaml";
  CliRun r = run("render " + example.string() + " --width 32 --height 32 --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string exr = (mDir / "out" / "topdown_dsc.exr").string();
  r = run("dsc " + exr + " --cell 1000");
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("--cell 1000: the 32x32 render holds 1 x 1 blocks"));
  EXPECT_THAT(r.err, HasSubstr("use --cell 16 or less"));
  r = run("dsc " + exr + " --cell 16");
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("blocks 4"));
}

TEST_F(SkyrenderCli, WeatherPrintsHeightRangesWithTo) {
  CliRun r = run("weather " + gfsFile().string() + " --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr(" m  top "));
  EXPECT_FALSE(std::regex_search(r.out, std::regex(R"(-?\d+-\d+ m)"))) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(base -?\d+ to \d+ m)"))) << r.out;
}

// ---- 2.8 interrupts ---------------------------------------------------------------------------

// Starts skyrender with `args`, its stdout to /dev/null and its stderr into `errFile`.
pid_t spawnSkyrender(const std::vector<std::string>& args, const fs::path& errFile) {
  std::vector<std::string> all = {std::getenv("SKY_SKYRENDER")};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  pid_t pid = -1;
  EXPECT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

TEST_F(SkyrenderCli, AnInterruptedTimeLapseKeepsWholeFramesAndSaysHowFarItGot) {
  for (const int signal : {SIGINT, SIGTERM}) {
    fs::remove_all(mDir / "out");
    const fs::path err = mDir / "stderr";
    const pid_t pid =
        spawnSkyrender({"render", "--width", "16", "--height", "9", "--time",
                        "2024-06-21T00:00+02:00/2024-06-21T08:19+02:00/1m", "--out", out()},
                       err);
    ASSERT_GT(pid, 0);
    // Wait for the first finished frame, then interrupt.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(mDir / "out" / "sky_0001.json") &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_TRUE(fs::exists(mDir / "out" / "sky_0001.json")) << "no frame within 2 minutes";
    ::kill(pid, signal);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of stopping";
    EXPECT_EQ(WEXITSTATUS(status), 128 + signal);
    const std::string text = readTextFile(err);
    std::smatch m;
    ASSERT_TRUE(std::regex_search(text, m, std::regex(R"(interrupted after (\d+) of 500 frames)")))
        << text;
    const int frames = std::stoi(m[1]);
    EXPECT_GE(frames, 1);
    EXPECT_LT(frames, 500);
    // Every frame it counts is whole, nothing more, and no temporary is left.
    size_t files = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(mDir / "out")) {
      EXPECT_EQ(e.path().filename().string().rfind(".tmp-", 0), std::string::npos) << e.path();
      ++files;
    }
    EXPECT_EQ(files, size_t(frames) * 3);
    char last[32];
    std::snprintf(last, sizeof last, "sky_%04d", frames);
    for (const char* ext : {".exr", ".png", ".json"})
      EXPECT_TRUE(fs::exists(mDir / "out" / (std::string(last) + ext))) << last << ext;
  }
}

// ---- 2.9 an unwritable cache ------------------------------------------------------------------

TEST_F(SkyrenderCli, AnUnwritableCacheWarnsOnceAndTheReportSaysSo) {
  CliRun r =
      run("render --width 16 --height 9 --time "
          "2024-06-21T12:00+02:00/2024-06-21T12:02+02:00/1m --out " +
              out(),
          "SKY_CACHE_DIR=/proc/nope");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(count(r.err, "warning: the cache folder /proc/nope cannot be written"), 1u) << r.err;
  for (const char* frame : {"sky_0001.json", "sky_0003.json"}) {
    const nlohmann::json report = readJson(mDir / "out" / frame);
    ASSERT_TRUE(report.contains("cache")) << frame;
    EXPECT_EQ(report["cache"]["writable"], false);
    EXPECT_TRUE(report["cache"].contains("not_written_because"));
    EXPECT_FALSE(report["high_cloud_textures"].contains("cache_file")) << frame;
    EXPECT_FALSE(report["volumetric_clouds"].contains("noise_cache_file")) << frame;
  }
  // A writable one is said to be.
  r = run("render --width 16 --height 9 --out " + out());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_THAT(r.err, Not(HasSubstr("warning")));
  EXPECT_EQ(readJson(mDir / "out" / "sky.json")["cache"]["writable"], true);
}

}  // namespace
}  // namespace sky
