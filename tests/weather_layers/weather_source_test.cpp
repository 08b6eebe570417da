// engine/weather/weather_source.h: how the map changes with the frame's time: weather.time,
// steps spread over several files (a file-name pattern), the scene's wind carrying a
// procedural map, and the cache that builds nothing when nothing changed.
#include <eccodes.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/weather/cloud_layers_from_fields.h"
#include "engine/weather/geo.h"
#include "engine/weather/weather_source.h"
#include "../weather_files/grib_writer.h"
#include "error_capture.h"
#include "gfs_fixture.h"

namespace sky {
namespace {
namespace fs = std::filesystem;

struct FileCloser {
  void operator()(FILE* f) const { std::fclose(f); }
};
struct HandleDeleter {
  void operator()(codes_handle* h) const { codes_handle_delete(h); }
};

// A scratch folder for this test process.
fs::path scratch() {
  static const fs::path dir = [] {
    fs::path d = fs::path(testing::TempDir()) / ("sky_weather_source_" + std::to_string(getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// Copies the GFS fixture's instantaneous fields to `to` with their forecast time `hours`
// later and, when `dry`, the relative humidity set to 0 everywhere (clear sky): a second step
// of a forecast.
void writeShiftedCopy(const fs::path& to, long hours, bool dry) {
  std::unique_ptr<FILE, FileCloser> in(
      std::fopen((test::weatherDataDir() / "gfs_2p5deg_r_gh_t_tcc_uv500.grib2").c_str(), "rb"));
  std::unique_ptr<FILE, FileCloser> out(std::fopen(to.c_str(), "wb"));
  ASSERT_TRUE(in && out);
  int err = 0;
  while (codes_handle* raw = codes_handle_new_from_file(nullptr, in.get(), PRODUCT_GRIB, &err)) {
    std::unique_ptr<codes_handle, HandleDeleter> h(raw);
    // Only instantaneous fields: the time-averaged tcc would need its interval's end moved.
    long start = 0, end = 0;
    ASSERT_EQ(codes_get_long(h.get(), "startStep", &start), 0);
    ASSERT_EQ(codes_get_long(h.get(), "endStep", &end), 0);
    char name[64] = {};
    size_t len = sizeof name;
    ASSERT_EQ(codes_get_string(h.get(), "shortName", name, &len), 0);
    // Nor the wind: GFS packs u and v into one multi-field message.
    if (start != end || std::string(name) == "u" || std::string(name) == "v") continue;
    ASSERT_EQ(codes_set_long(h.get(), "forecastTime", end + hours), 0);
    if (dry && std::string(name) == "r") {
      size_t n = 0;
      ASSERT_EQ(codes_get_size(h.get(), "values", &n), 0);
      const std::vector<double> zeros(n, 0.0);
      ASSERT_EQ(codes_set_double_array(h.get(), "values", zeros.data(), n), 0);
    }
    const void* bytes = nullptr;
    size_t size = 0;
    ASSERT_EQ(codes_get_message(h.get(), &bytes, &size), 0);
    ASSERT_EQ(std::fwrite(bytes, 1, size, out.get()), size);
  }
}

double meanLow(const WeatherMap& map) {
  double sum = 0.0;
  for (const glm::vec4& t : map.texels) sum += t.r;
  return sum / double(map.texels.size());
}

IsoTime instant(const char* text) {
  return *IsoTime::parse(text);
}

TEST(WeatherSource, WeatherTimeShowsTheForecastAtAnotherInstantAndMovesOnWithTheFrames) {
  Scene scene = test::gfsScene(test::kAtlanticRegion, WeatherCover::Rh);
  scene.weather.resolution = 64;
  // The sun of a winter evening over a forecast valid at another time.
  scene.time.start = instant("2023-12-21T16:00:00Z");
  WeatherSource source;
  const WeatherMap& atScene = source.map(weatherInputs(scene), scene.time.start);
  const double valid = source.fields()->steps[0].validTimeUnix;
  // With one step and no advection the map is the same at any time.
  EXPECT_EQ(weatherTimeUnix(weatherInputs(scene), scene.time.start), double(scene.time.start.unixSeconds));

  scene.weather.time = IsoTime{int64_t(valid) + 3 * 3600, 0.0, 0};
  scene.weather.advection = WeatherAdvection::Data;
  const double shown = weatherTimeUnix(weatherInputs(scene), scene.time.start.plusSeconds(1800.0));
  EXPECT_EQ(shown, valid + 3.5 * 3600.0) << "weather.time plus the frame's time since the start";
  const WeatherMap& moved = source.map(weatherInputs(scene), scene.time.start.plusSeconds(1800.0));
  const WeatherMap expected =
      weatherMapFromFields(*source.fields(), shown, scene.weather, *scene.weather.region);
  ASSERT_EQ(moved.texels.size(), expected.texels.size());
  for (size_t i = 0; i < moved.texels.size(); ++i)
    ASSERT_EQ(moved.texels[i], expected.texels[i]) << "texel " << i;
  (void)atScene;
  // A weather.time that is not an instant never gets here: the scene reader refuses it
  // (SceneErrors.CloudAndWeatherRules).
}

TEST(WeatherSource, APatternReadsOneStepPerFileAndInterpolatesBetweenThem) {
  const fs::path dir = scratch() / "steps";
  fs::create_directories(dir);
  fs::copy_file((test::weatherDataDir() / "gfs_2p5deg_r_gh_t_tcc_uv500.grib2"),
                dir / "gfs.f000.grib2", fs::copy_options::overwrite_existing);
  writeShiftedCopy(dir / "gfs.f006.grib2", 6, true);
  std::ofstream(dir / "notes.txt") << "not a forecast";  // the pattern must not pick it up

  Scene scene = test::gfsScene(test::kAtlanticRegion, WeatherCover::Rh);
  scene.weather.resolution = 64;
  scene.baseDir = dir;
  scene.weather.file = "gfs.f0*.grib2";
  WeatherSource source;
  ASSERT_NO_THROW(source.map(weatherInputs(scene), scene.time.start));
  ASSERT_EQ(source.fields()->steps.size(), 2u);
  const double t0 = source.fields()->steps[0].validTimeUnix;
  EXPECT_EQ(source.fields()->steps[1].validTimeUnix - t0, 6 * 3600.0);

  const auto at = [&](double seconds) {
    return meanLow(source.map(weatherInputs(scene), IsoTime{int64_t(t0 + seconds), 0.0, 0}));
  };
  const double wet = at(0.0), half = at(3 * 3600.0), dry = at(6 * 3600.0);
  std::printf("mean low cover at +0 h %.4f, +3 h %.4f, +6 h %.4f\n", wet, half, dry);
  EXPECT_GT(wet, 0.05);
  EXPECT_EQ(dry, 0.0) << "the dry step has no clouds";
  // Halfway between the files' steps; the bicubic resampling's clamp to [0, 1] is not quite
  // linear, hence the tolerance.
  EXPECT_NEAR(half, 0.5 * wet, 1e-3);

  // A pattern that matches nothing, and files on different grids, are one-line errors.
  scene.weather.file = "ecmwf*.grib2";
  Error e = test::catchError([&] { WeatherSource().map(weatherInputs(scene), scene.time.start); });
  EXPECT_NE(std::string(e.what()).find("weather.file: ecmwf*.grib2: no file matches"),
            std::string::npos)
      << e.what();
  // The NetCDF twin of the fixture: the same grid and valid time.
  fs::copy_file(test::weatherDataDir() / "gfs_trop_r_t_gh_era5style.nc", dir / "gfs.f000.nc");
  scene.weather.file = "gfs.f0*";
  e = test::catchError([&] { WeatherSource().map(weatherInputs(scene), scene.time.start); });
  EXPECT_NE(std::string(e.what()).find("repeats a valid time another matching file has"),
            std::string::npos)
      << e.what();
  fs::remove(dir / "gfs.f000.nc");
  // One humidity field on a 5-degree grid.
  test::GribWriter("regular_ll_pl_grib2")
      .set("Ni", 8L)
      .set("Nj", 8L)
      .set("latitudeOfFirstGridPointInDegrees", 70.0)
      .set("latitudeOfLastGridPointInDegrees", 35.0)
      .set("longitudeOfFirstGridPointInDegrees", 330.0)
      .set("longitudeOfLastGridPointInDegrees", 365.0)
      .set("iDirectionIncrementInDegrees", 5.0)
      .set("jDirectionIncrementInDegrees", 5.0)
      .set("numberOfDataPoints", 64L)
      .set("dataDate", 20110116L)
      .set("typeOfLevel", "isobaricInhPa")
      .set("shortName", "r")
      .set("level", 850L)
      .values(std::vector<double>(64, 90.0))
      .appendTo(dir / "gfs.f024.grib2");
  e = test::catchError([&] { WeatherSource().map(weatherInputs(scene), scene.time.start); });
  EXPECT_NE(
      std::string(e.what()).find("weather.file: gfs.f024.grib2 is on a different grid (8 x 8)"),
      std::string::npos)
      << e.what();
}

TEST(WeatherSource, TheSceneWindCarriesAProceduralMapFromTheFirstFrame) {
  Scene scene;
  scene.weather.coverLow = 0.4;
  scene.weather.resolution = 128;
  scene.weather.region = {{-5.0, 5.0}, {0.0, 10.0}};
  scene.clouds.windSpeedMs = 20.0;
  scene.clouds.windFrom = 270.0;  // a west wind blows toward the east
  WeatherSource source;
  const WeatherMap first = source.map(weatherInputs(scene), scene.time.start);
  const WeatherMap still = source.map(weatherInputs(scene), scene.time.start.plusSeconds(3 * 3600.0));
  EXPECT_EQ(first.texels, still.texels) << "advection none holds the map";

  scene.weather.advection = WeatherAdvection::Wind;
  const WeatherMap start = source.map(weatherInputs(scene), scene.time.start);
  EXPECT_EQ(start.texels, first.texels) << "the first frame shows the map as made";
  const uint64_t built = source.revision();
  const WeatherMap later = source.map(weatherInputs(scene), scene.time.start.plusSeconds(3 * 3600.0));
  EXPECT_EQ(source.revision(), built + 1);
  source.map(weatherInputs(scene), scene.time.start.plusSeconds(3 * 3600.0));
  EXPECT_EQ(source.revision(), built + 1) << "the same frame again builds nothing";
  // 20 m/s for 3 h is 216 km, 1.94 degrees of longitude at the equator, 24.9 texels: texel x
  // now holds what lay 24.9 / cos(latitude) texels west (compare texels away from the west
  // edge).
  const double kDeg = 3.14159265358979 / 180.0;
  double err = 0.0;
  int n = 0;
  for (uint32_t y = 0; y < later.height; ++y)
    for (uint32_t x = 40; x < later.width; ++x) {
      const double lat = 5.0 - (y + 0.5) * 10.0 / later.height;
      const double shift =
          20.0 * 3 * 3600.0 / (kEarthRadiusM * kDeg * std::cos(lat * kDeg)) * (later.width / 10.0);
      const double src = x + 0.5 - shift;
      const auto x0 = uint32_t(std::floor(src - 0.5));
      const double f = src - 0.5 - x0;
      const double expected = (1.0 - f) * first.at(x0, y).r + f * first.at(x0 + 1, y).r;
      err = std::max(err, std::fabs(later.at(x, y).r - expected));
      ++n;
    }
  EXPECT_LT(err, 1e-4) << "over " << n << " texels";

  scene.weather.advection = WeatherAdvection::Data;
  const Error e = test::catchError([&] { source.map(weatherInputs(scene), scene.time.start); });
  EXPECT_NE(std::string(e.what()).find("weather.advection: data needs source file"),
            std::string::npos)
      << e.what();
}

TEST(WeatherSource, TheAutomatonEvolvesTheCoverBetweenWindowEndsOnly) {
  Scene scene;
  scene.weather.coverLow = 0.5;
  scene.weather.resolution = 64;
  scene.weather.region = {{45.0, 46.0}, {5.0, 6.5}};
  scene.time.start = instant("2024-06-21T12:00:00Z");  // a whole hour: a window starts here
  scene.weather.automaton.windowH = 1.0;
  WeatherSource still;
  const WeatherMap plain = still.map(weatherInputs(scene), scene.time.start);

  scene.weather.evolution = WeatherEvolution::Ca;
  WeatherSource source;
  EXPECT_EQ(source.map(weatherInputs(scene), scene.time.start).texels, plain.texels)
      << "at the window's start the map is the data's";
  const IsoTime halfway = scene.time.start.plusSeconds(1800.0);
  const WeatherMap evolved = source.map(weatherInputs(scene), halfway);
  EXPECT_GT(source.automatonStats().stepsRun, 0);
  double change = 0.0;
  for (size_t i = 0; i < plain.texels.size(); ++i) {
    ASSERT_GE(evolved.texels[i].r, 0.0f);
    ASSERT_LE(evolved.texels[i].r, 1.0f);
    EXPECT_EQ(evolved.texels[i].b, plain.texels[i].b) << "the type stays";
    change += std::fabs(evolved.texels[i].r - plain.texels[i].r);
  }
  change /= double(plain.texels.size());
  std::printf("mean |cover change| halfway through the window: %.3f\n", change);
  EXPECT_GT(change, 0.02) << "the automaton really moves the clouds";
  EXPECT_EQ(WeatherSource().map(weatherInputs(scene), halfway).texels, evolved.texels)
      << "the same seed and time give the same clouds, whatever came before";
  EXPECT_EQ(source.map(weatherInputs(scene), scene.time.start.plusSeconds(3600.0)).texels, plain.texels)
      << "at the window's end the map is the data's again";
}

}  // namespace
}  // namespace sky
