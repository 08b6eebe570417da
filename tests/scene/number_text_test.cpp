#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "engine/scene/detail/key_suggest.h"
#include "engine/scene/detail/number_text.h"

namespace sky::detail {
namespace {

TEST(NumberText, ParsesDecimalScalars) {
  EXPECT_EQ(parseNumber("64"), 64.0);
  EXPECT_EQ(parseNumber("-12.5"), -12.5);
  EXPECT_EQ(parseNumber("+3"), 3.0);
  EXPECT_EQ(parseNumber("1e3"), 1000.0);
  EXPECT_EQ(parseNumber("2.5E-1"), 0.25);
  EXPECT_EQ(parseNumber(".5"), 0.5);
  EXPECT_EQ(parseNumber("0.1"), 0.1);
  EXPECT_EQ(parseNumber("1e-400"), 0.0);  // underflow is a tiny number, not an error
  for (const char* bad :
       {"", "abc", "1.2.3", "0x10", " 1", "1 ", "1,5", "+", "+-1", "--1", "1e", "true", "12px"})
    EXPECT_FALSE(parseNumber(bad).has_value()) << "'" << bad << "'";
}

TEST(NumberText, NonFiniteSpellingsAreNumbers) {
  // They are numbers (so the error is "out of range", not "not a number").
  for (const char* text : {".inf", "+.inf", ".Inf", ".INF", "inf", "infinity", "1e999"})
    EXPECT_EQ(parseNumber(text), std::numeric_limits<double>::infinity()) << text;
  EXPECT_EQ(parseNumber("-.inf"), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(parseNumber("-1e999"), -std::numeric_limits<double>::infinity());
  for (const char* text : {".nan", ".NaN", ".NAN", "nan", "NaN"}) {
    std::optional<double> v = parseNumber(text);
    ASSERT_TRUE(v.has_value()) << text;
    EXPECT_TRUE(std::isnan(*v)) << text;
  }
  EXPECT_EQ(parseFloat("1e39"), std::numeric_limits<float>::infinity());
}

TEST(NumberText, ShortestRoundTrip) {
  EXPECT_EQ(formatDouble(0.1), "0.1");
  EXPECT_EQ(formatDouble(47.37), "47.37");
  EXPECT_EQ(formatDouble(500.0), "500");
  EXPECT_EQ(formatDouble(-0.0), "-0");
  EXPECT_EQ(formatFloat(0.16f), "0.16");
  EXPECT_EQ(formatFloat(0.8f), "0.8");
  for (double v : {0.1, 1.0 / 3.0, 1e-300, 123456.789, -2.5e17, 0.30000000000000004})
    EXPECT_EQ(parseNumber(formatDouble(v)), v);
  for (float v : {0.1f, 1.0f / 3.0f, 0.16f, 1e-30f, 16777215.0f, 0.3f})
    EXPECT_EQ(parseFloat(formatFloat(v)), v);
}

TEST(KeySuggest, FindsTyposOnly) {
  EXPECT_EQ(editDistance("widht", "width"), 1u);
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  std::vector<std::string> output = {"width", "height", "name", "exposure_ev", "display", "view"};
  EXPECT_EQ(suggestKey("widht", output), "width");
  EXPECT_EQ(suggestKey("Height", output), "height");
  EXPECT_EQ(suggestKey("exposureEv", output), "exposure_ev");
  EXPECT_EQ(suggestKey("colour", output), "");
  EXPECT_EQ(suggestKey("x", output), "");
  std::vector<std::string> sky = {"sky_color", "fog_color", "sun_color", "glow_size",
                                  "haze_height"};
  EXPECT_EQ(suggestKey("sky_colour", sky), "sky_color");
  EXPECT_EQ(suggestKey("hazeHeight", sky), "haze_height");
}

}  // namespace
}  // namespace sky::detail
