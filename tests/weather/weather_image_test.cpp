// The weather map's image source: an RGBA PNG (codes / 255) or EXR (as is) mapped over the
// region, row 0 north; and each bad file as a one-line BadInput error naming weather.image
// and the file as the scene wrote it.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "engine/core/error.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"
#include "engine/weather/weather_map.h"
#include "error_capture.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::catchError;
using ::testing::HasSubstr;

class WeatherImage : public ::testing::Test {
protected:
  void SetUp() override {
    mDir = fs::temp_directory_path() /
           ("sky-weather-image-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(mDir);
    fs::create_directories(mDir);
  }
  void TearDown() override { fs::remove_all(mDir); }

  Scene scene(const std::string& image) const {
    Scene s;
    s.weather.source = WeatherMapSource::Image;
    s.weather.image = image;
    s.weather.region = WeatherRegion{{40.0, 44.0}, {-2.0, 4.0}};
    s.baseDir = mDir;
    return s;
  }
  void writeExrLayer(const std::string& name, int w, int h, std::vector<std::string> channels,
                     std::vector<float> pixels) const {
    LayeredImage exr;
    exr.width = w;
    exr.height = h;
    exr.layers.push_back({"", std::move(channels), std::move(pixels)});
    writeExr(mDir / name, exr);
  }
  // The error makeWeatherMap throws for `image`: BadInput, one line, naming the key and file.
  std::string errorFor(const std::string& image) const {
    const Error e = catchError([&] { makeWeatherMap(weatherInputs(scene(image))); });
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_THAT(what, HasSubstr("weather.image: " + image + ": "));
    return what;
  }

  fs::path mDir;
};

TEST_F(WeatherImage, PngCodesMapOverTheRegionRowZeroNorth) {
  // 4 x 2: the top row clear with type 0, the bottom row cloudy with type 1.
  std::vector<float> rgba;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const float v = y == 0 ? 0.0f : float(x + 1) * 51.0f / 255.0f;
      rgba.insert(rgba.end(), {v, 1.0f - v, float(y), 1.0f});
    }
  writePng8(mDir / "map.png", 4, 2, rgba, PngQuantize::Nearest);
  const WeatherMap map = makeWeatherMap(weatherInputs(scene("map.png")));
  ASSERT_EQ(map.width, 4u);
  ASSERT_EQ(map.height, 2u);
  EXPECT_EQ(map.region, scene("map.png").weather.region);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const float v = y == 0 ? 0.0f : float(x + 1) * 51.0f / 255.0f;
      EXPECT_NEAR(map.at(uint32_t(x), uint32_t(y)).x, v, 1e-6);
      EXPECT_NEAR(map.at(uint32_t(x), uint32_t(y)).y, 1.0f - v, 1e-6);
      EXPECT_EQ(map.at(uint32_t(x), uint32_t(y)).z, float(y));
      EXPECT_EQ(map.at(uint32_t(x), uint32_t(y)).w, 1.0f);
    }
  // The north half of the region is row 0: clear.
  EXPECT_EQ(map.sample(43.5, 0.0).x, 0.0f);
  EXPECT_GT(map.sample(40.5, 0.0).x, 0.3f);
  EXPECT_NEAR(map.maxCover().x, 4.0f * 51.0f / 255.0f, 1e-6);
  EXPECT_NEAR(map.maxCover().y, 1.0f, 1e-6);
}

TEST_F(WeatherImage, ExrValuesAsTheyAreWithDensityAboveOne) {
  writeExrLayer("map.exr", 2, 1, {"R", "G", "B", "A"},
                {0.25f, 0.5f, 0.5f, 2.0f,  //
                 0.0f, 1.0f, 1.0f, 0.5f});
  const WeatherMap map = makeWeatherMap(weatherInputs(scene("map.exr")));
  ASSERT_EQ(map.width, 2u);
  ASSERT_EQ(map.height, 1u);
  EXPECT_EQ(map.at(0, 0), glm::vec4(0.25f, 0.5f, 0.5f, 2.0f));
  EXPECT_EQ(map.at(1, 0), glm::vec4(0.0f, 1.0f, 1.0f, 0.5f));
}

TEST_F(WeatherImage, MissingFileIsBadInput) {
  EXPECT_THAT(errorFor("nothing.png"), HasSubstr("file not found"));
  Scene s = scene("");
  const Error e = catchError([&] { makeWeatherMap(weatherInputs(s)); });
  EXPECT_THAT(std::string(e.what()), HasSubstr("weather.image: is required"));
}

TEST_F(WeatherImage, UnreadableFileIsBadInput) {
  std::ofstream(mDir / "broken.png") << "not a png at all";
  std::ofstream(mDir / "broken.exr") << "not an exr";
  std::ofstream(mDir / "map.tif") << "tiff";
  errorFor("broken.png");
  errorFor("broken.exr");
  EXPECT_THAT(errorFor("map.tif"), HasSubstr("PNG or EXR"));
}

TEST_F(WeatherImage, WrongChannelCountIsBadInput) {
  writeExrLayer("rgb.exr", 2, 2, {"R", "G", "B"}, std::vector<float>(12, 0.5f));
  EXPECT_THAT(errorFor("rgb.exr"), HasSubstr("must be RGBA (4 channels"));
  EXPECT_THAT(errorFor("rgb.exr"), HasSubstr("has 3"));
}

TEST_F(WeatherImage, CoverOrTypeOutsideZeroOneIsBadInput) {
  writeExrLayer("high.exr", 2, 1, {"R", "G", "B", "A"},
                {0.5f, 0.5f, 0.5f, 1.0f,  //
                 1.5f, 0.5f, 0.5f, 1.0f});
  EXPECT_THAT(errorFor("high.exr"), HasSubstr("R (low cover) value 1.5 at pixel (1, 0)"));
  writeExrLayer("negative.exr", 1, 2, {"R", "G", "B", "A"},
                {0.5f, 0.5f, 0.5f, 1.0f,  //
                 0.5f, -0.25f, 0.5f, 1.0f});
  EXPECT_THAT(errorFor("negative.exr"), HasSubstr("G (mid cover) value -0.25 at pixel (0, 1)"));
  writeExrLayer("type.exr", 1, 1, {"R", "G", "B", "A"}, {0.5f, 0.5f, 2.0f, 1.0f});
  EXPECT_THAT(errorFor("type.exr"), HasSubstr("B (cloud type)"));
  writeExrLayer("density.exr", 1, 1, {"R", "G", "B", "A"}, {0.5f, 0.5f, 0.5f, -1.0f});
  EXPECT_THAT(errorFor("density.exr"), HasSubstr("A (density scale)"));
}

}  // namespace
}  // namespace sky
