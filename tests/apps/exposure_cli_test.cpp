// The physical EXR and the display's exposure (issue 15): the EXR holds physical values (a
// full-moon night's sky is ~10^5 times darker than noon's), the PNG is exposed by
// output.exposure and says so in the report and the EXR, and the README's 24 h time-lapse
// never dips to black between twilight and the moonlit night.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/core/files.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"
#include "tests/apps/cli_fixture.h"

namespace sky {
namespace {
namespace fs = std::filesystem;

fs::path example(const std::string& name) {
  return fs::path(std::getenv("SKY_DATA_DIR")) / "configs" / "examples" / name;
}

// Mean Rec.709 luminance of an EXR layer's RGB.
double meanLuminance(const LayeredImage& exr, const std::string& layer) {
  const ImageLayer* l = exr.find(layer);
  EXPECT_NE(l, nullptr) << layer;
  if (!l) return 0.0;
  const size_t c = l->channels.size();
  double sum = 0.0;
  for (size_t i = 0; i + 2 < l->pixels.size(); i += c)
    sum += 0.2126 * l->pixels[i] + 0.7152 * l->pixels[i + 1] + 0.0722 * l->pixels[i + 2];
  return sum / static_cast<double>(l->pixels.size() / c);
}

// Mean 8-bit value over the RGB channels of a PNG.
double meanDisplay(const fs::path& png) {
  const Image8 img = readPng(png);
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < img.pixels.size(); ++i)
    if (img.channels < 4 || i % 4 != 3) sum += img.pixels[i], ++n;
  return n ? sum / static_cast<double>(n) : 0.0;
}

TEST_F(SkyrenderCli, TheExrIsPhysicalFromNoonToAFullMoonNight) {
  // The clear sky of the default scene at noon and at midnight of the June 2024 full moon
  // (the moon 13 degrees up). Physically a full-moon night sky is 10^5-10^6 times darker than
  // the day's; the lifted night made it 4.7 (kozlov) and 6.5 (physical).
  for (const char* model : {"kozlov", "physical"}) {
    SCOPED_TRACE(model);
    const std::string common = std::string(" --width 32 --height 18 --set sky.model=") + model +
                               " --set weather.cover_low=0 --set high_clouds.cover=0";
    ASSERT_EQ(
        run("render --out " + out() + " --name noon --time 2024-06-21T13:30+02:00" + common).rc, 0);
    ASSERT_EQ(
        run("render --out " + out() + " --name night --time 2024-06-22T01:20+02:00" + common).rc,
        0);
    const double noon = meanLuminance(readExr(mDir / "out" / "noon.exr"), "sky");
    const double night = meanLuminance(readExr(mDir / "out" / "night.exr"), "sky");
    std::cout << model << ": sky noon " << noon << ", full-moon night " << night << ", ratio "
              << noon / night << "\n";
    EXPECT_GE(noon / night, 1e4);
    // The night is still exposed to be seen: the report and the EXR say by how much.
    const nlohmann::json report = nlohmann::json::parse(readTextFile(mDir / "out" / "night.json"));
    EXPECT_EQ(report["exposure"]["mode"], "auto");
    EXPECT_GT(report["exposure"]["ev"].get<double>(), 10.0);
    const LayeredImage exr = readExr(mDir / "out" / "night.exr");
    ASSERT_TRUE(exr.attributes.count("skylayers:exposure_ev"));
    EXPECT_NEAR(std::stod(exr.attributes.at("skylayers:exposure_ev")),
                report["exposure"]["ev"].get<double>(), 1e-3);
  }
}

TEST_F(SkyrenderCli, ExposureModesChangeThePngNotTheExr) {
  // A night frame: fixed leaves it at exposure_ev (dark), auto lifts it by the night lift,
  // histogram by what it metres; the EXR is the same physical image each time.
  const std::string night = " --width 32 --height 18 --time 2024-06-22T01:20+02:00";
  std::vector<double> display, sky;
  for (const char* mode : {"fixed", "auto", "histogram"}) {
    ASSERT_EQ(
        run("render --out " + out() + " --name " + mode + night + " --set output.exposure=" + mode)
            .rc,
        0);
    display.push_back(meanDisplay(mDir / "out" / (std::string(mode) + ".png")));
    sky.push_back(meanLuminance(readExr(mDir / "out" / (std::string(mode) + ".exr")), "sky"));
    const nlohmann::json report =
        nlohmann::json::parse(readTextFile(mDir / "out" / (std::string(mode) + ".json")));
    EXPECT_EQ(report["exposure"]["mode"], mode);
    if (std::string(mode) == "histogram") {
      EXPECT_GT(report["exposure"]["metered_luminance"].get<double>(), 0.0);
    }
  }
  std::cout << "night display: fixed " << display[0] << ", auto " << display[1] << ", histogram "
            << display[2] << "\n";
  EXPECT_LT(display[0], 2.0) << "unexposed, the physical night is black";
  EXPECT_GT(display[1], 8.0);
  EXPECT_GT(display[2], 4.0);
  EXPECT_EQ(sky[0], sky[1]);
  EXPECT_EQ(sky[1], sky[2]);
}

TEST_F(SkyrenderCli, AHistogramExposureAdaptsOverASequence) {
  // Dusk in 15-minute frames, the light falling fast. At once (exposure_adaptation_s 0) each
  // frame gets the exposure it metres; with a 600 s time constant each frame's exposure lies
  // between its own target and the frame before's, exp(-900 / 600) = 22 % of the way back.
  const std::string dusk = " --width 16 --height 9 --time 2024-06-21T21:30+02:00/"
                           "2024-06-21T22:00+02:00/15m --set output.exposure=histogram";
  for (double tau : {0.0, 600.0}) {
    SCOPED_TRACE("adaptation " + std::to_string(tau));
    fs::remove_all(mDir / "out");
    fs::create_directories(mDir / "out");
    ASSERT_EQ(run("render --out " + out() + dusk +
                  " --set output.exposure_adaptation_s=" + std::to_string(tau))
                  .rc,
              0);
    double lastEv = 0.0;
    for (int i = 1; i <= 3; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "sky_%04d.json", i);
      const nlohmann::json e = nlohmann::json::parse(readTextFile(mDir / "out" / name))["exposure"];
      const double ev = e["ev"].get<double>(), target = e["target_ev"].get<double>();
      if (i == 1 || tau == 0.0) {
        EXPECT_DOUBLE_EQ(ev, target) << "frame " << i;
      } else {
        EXPECT_GT(target, lastEv + 1.0) << "frame " << i << ": the light falls";
        EXPECT_NEAR(ev, target + (lastEv - target) * std::exp(-900.0 / tau), 1e-6)
            << "frame " << i;
      }
      lastEv = ev;
    }
  }
}

TEST_F(SkyrenderCli, TheTimelapseNeverDipsToBlackBetweenTwilightAndMoonlight) {
  // The README's 24 h time-lapse (configs/examples/timelapse_24h.yaml: histogram exposure
  // adapting over 10 minutes) at 32x18: no frame's mean display value falls below 85 % of
  // both its neighbours', and none is black. The old lifted night fell to about 1/255 at
  // sun -10..-12 degrees between 21 before and 29 after. With output.exposure auto (the
  // lighting model's night lift) the twilight sagged to 60 % until the lift followed the
  // moonlight too (TheNightHasNoTwilightHole); now the same 85 % holds.
  for (const auto& [mode, share] : {std::pair<std::string, double>{"histogram", 0.85},
                                    std::pair<std::string, double>{"auto", 0.85}}) {
    SCOPED_TRACE(mode);
    fs::remove_all(mDir / "out");
    fs::create_directories(mDir / "out");
    CliRun r = run("render " + example("timelapse_24h.yaml").string() + " --out " + out() +
                   " --width 32 --height 18 --set output.exposure=" + mode);
    ASSERT_EQ(r.rc, 0) << r.err;
    std::vector<double> means;
    for (int i = 1; i <= 97; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "timelapse_%04d.png", i);
      means.push_back(meanDisplay(mDir / "out" / name));
    }
    double worst = 1e9;
    size_t worstAt = 0;
    for (size_t i = 1; i + 1 < means.size(); ++i) {
      const double kept = means[i] / std::max(means[i - 1], means[i + 1]);
      if (kept < worst) worst = kept, worstAt = i;
      EXPECT_GT(means[i], 2.0) << "frame " << i + 1 << " is black";
    }
    std::cout << mode << ": darkest frame " << *std::min_element(means.begin(), means.end())
              << "; least share of its brighter neighbour " << worst << " at frame " << worstAt + 1
              << "\n";
    for (size_t i = 1; i + 1 < means.size(); ++i)
      EXPECT_FALSE(means[i] < share * means[i - 1] && means[i] < share * means[i + 1])
          << "frame " << i + 1 << " (" << means[i] << ") dips below " << share << " of both "
          << means[i - 1] << " and " << means[i + 1];
  }
}

// Issue 30, goal 7: the README's time-lapse (the default scene, output.exposure auto) had a
// hole between dusk and dawn: the darkest frame 0.16 of the night's median at 160x90 (sun
// -11.4, the full moon 6 degrees up), because the night lift followed the sun alone and
// reached its full 16.2 stops only at -18 while the moon held the sky's light from -12 on.
// A moonless night faded to black instead (mean display 0.26 of a code), 4.8 times darker
// every half hour through nautical twilight. Here, at 48x27 every 30 minutes from 21:00 to
// 06:00 (clear sky, which keeps it to a few seconds; with the default cumulus the same
// numbers are 0.69 and 1.64 for the full moon, 0.71 and 1.68 without moon):
// - no frame with the sun below -6 degrees under 0.35 of those frames' median display value
//   (measured 0.97 with the full moon, 0.85 without; before 0.22 and 0.63);
// - no two consecutive frames more than 2x apart, a stop in half an hour, from dusk to dawn
//   (measured 1.32 and 1.41; before 2.84 and 4.05);
// - the moonless night darker than the moonlit one, but seen: its median between 0.25 and
//   0.9 of the moonlit night's (measured 0.69; before 0.026).
TEST_F(SkyrenderCli, TheNightHasNoTwilightHole) {
  struct Night {
    const char* name;
    const char* time;
    double median = 0.0;
  };
  Night nights[] = {{"full moon", "2024-06-21T21:00+02:00/2024-06-22T06:00+02:00/30m"},
                    {"new moon", "2024-07-05T21:00+02:00/2024-07-06T06:00+02:00/30m"}};
  for (Night& night : nights) {
    SCOPED_TRACE(night.name);
    fs::remove_all(mDir / "out");
    fs::create_directories(mDir / "out");
    CliRun r = run("render --out " + out() + " --width 48 --height 27 --time " + night.time +
                   " --set weather.cover_low=0");
    ASSERT_EQ(r.rc, 0) << r.err;
    std::vector<double> means, dark;
    std::string table;
    for (int i = 1; i <= 19; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "sky_%04d", i);
      const fs::path frame = mDir / "out" / name;
      const double mean = meanDisplay(fs::path(frame).replace_extension(".png"));
      const nlohmann::json report =
          nlohmann::json::parse(readTextFile(fs::path(frame).replace_extension(".json")));
      const double sun = report["sun"]["elevation_deg"].get<double>();
      means.push_back(mean);
      if (sun < -6.0) dark.push_back(mean);
      table += " " + std::to_string(static_cast<int>(std::lround(mean)));
    }
    ASSERT_GE(dark.size(), 10u);
    std::vector<double> sorted = dark;
    std::sort(sorted.begin(), sorted.end());
    night.median = sorted[sorted.size() / 2];
    double steepest = 1.0;
    for (size_t i = 1; i < means.size(); ++i)
      steepest = std::max(steepest, std::max(means[i], means[i - 1]) /
                                        std::max(std::min(means[i], means[i - 1]), 1e-3));
    std::cout << night.name << ": mean display (codes)" << table << "; night median "
              << night.median << ", darkest " << sorted.front() / night.median
              << " of it; steepest half hour x" << steepest << "\n";
    EXPECT_GE(sorted.front(), 0.35 * night.median) << "a hole in the night";
    EXPECT_LE(steepest, 2.0) << "a jump between frames half an hour apart";
  }
  EXPECT_GT(nights[1].median, 0.25 * nights[0].median) << "the moonless night is black";
  EXPECT_LT(nights[1].median, 0.9 * nights[0].median) << "moonlight should show";
}

}  // namespace
}  // namespace sky
