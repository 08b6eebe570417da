// The display's night look (engine/color/night_look.h): cones alone in daylight, rods alone
// in the dark, and in between dim colours lose their saturation and shift toward blue.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/color/night_look.h"

namespace sky {
namespace {

double saturation(const std::vector<float>& p) {
  const double hi = std::max({p[0], p[1], p[2]}), lo = std::min({p[0], p[1], p[2]});
  return hi > 0.0 ? (hi - lo) / hi : 0.0;
}

TEST(NightLook, PhotopicShareRunsFromRodsToCones) {
  EXPECT_EQ(photopicShare(0.001), 0.0);
  EXPECT_EQ(photopicShare(0.01), 0.0);
  EXPECT_EQ(photopicShare(3.0), 1.0);
  EXPECT_EQ(photopicShare(1e4), 1.0);
  double last = 0.0;
  for (double l = 0.012; l < 3.0; l *= 1.3) {
    const double s = photopicShare(l);
    EXPECT_GE(s, last) << l;
    last = s;
  }
  EXPECT_GT(photopicShare(0.2), 0.3);
  EXPECT_LT(photopicShare(0.2), 0.7);
}

TEST(NightLook, DaylightIsUntouchedAndTheDarkTurnsBlueGrey) {
  // Renderer units: 1 = 10^4 cd/m^2. A daylit orange (1000 cd/m^2), a moonlit one
  // (0.001 cd/m^2) and a mesopic one (0.2 cd/m^2).
  const std::vector<float> day = {0.12f, 0.08f, 0.02f, 1.0f};
  std::vector<float> px = day;
  applyNightLook(px);
  EXPECT_EQ(px, day);

  std::vector<float> night = {1.2e-7f, 0.8e-7f, 0.2e-7f, 0.5f};
  const double before = saturation(night);
  applyNightLook(night);
  EXPECT_EQ(night[3], 0.5f) << "alpha is left alone";
  EXPECT_GT(night[2], night[0]) << "the rods' grey is blue, not orange";
  EXPECT_LT(saturation(night), before);

  std::vector<float> mesopic = {2.4e-5f, 1.6e-5f, 0.4e-5f, 1.0f};
  const double mesopicBefore = saturation(mesopic);
  applyNightLook(mesopic);
  EXPECT_LT(saturation(mesopic), mesopicBefore);
  EXPECT_GT(mesopic[0], mesopic[2]) << "half cones: still orange, less so";

  // White keeps its luminance in the dark.
  std::vector<float> white = {1e-7f, 1e-7f, 1e-7f, 1.0f};
  applyNightLook(white);
  const double y = 0.2126 * white[0] + 0.7152 * white[1] + 0.0722 * white[2];
  EXPECT_NEAR(y, 1e-7, 2e-9);
}

}  // namespace
}  // namespace sky
