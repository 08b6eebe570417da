#include "engine/color/ocio_output.h"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "engine/core/files.h"
#include "engine/core/paths.h"
#include "engine/io/png.h"
#include "tests/color/ocio_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::catchError;

const char* kAgx = "AgX";
const char* kAces = "ACES 1.0 - SDR Video";
const char* kUntoned = "Un-tone-mapped";

// A minimal valid OCIO config with a display of its own, to tell it apart from the shipped one.
const char* kTinyConfig = R"(ocio_profile_version: 2
roles:
  default: linear
  scene_linear: linear
  data: raw
file_rules:
  - !<Rule> {name: Default, colorspace: default}
displays:
  Tiny:
    - !<View> {name: Linear, colorspace: linear}
colorspaces:
  - !<ColorSpace> {name: linear, isdata: false}
  - !<ColorSpace> {name: raw, isdata: true}
)";

// IEC 61966-2-1 encoding, the reference for the un-tone-mapped view (clipped to [0, 1]).
float srgbEncode(float linear) {
  const float v = std::clamp(linear, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

std::vector<float> convert(const OcioOutput& out, std::vector<float> rgba, const char* view,
                           double ev = 0.0) {
  out.toDisplay(rgba, "sRGB", view, ev);
  return rgba;
}

class OcioOutputTest : public test::OcioEnvTest {};

TEST_F(OcioOutputTest, DefaultLoadsShippedConfig) {
  OcioOutput out = OcioOutput::load();
  EXPECT_EQ(out.configPath(), configDir() / "ocio" / "config.ocio");
}

TEST_F(OcioOutputTest, DisplaysAndViewsAreExactlyAsSpecified) {
  OcioOutput out = OcioOutput::load();
  EXPECT_EQ(out.displays(), std::vector<std::string>{"sRGB"});
  EXPECT_EQ(out.views("sRGB"), (std::vector<std::string>{kAgx, kAces, kUntoned, "Raw"}));
  EXPECT_TRUE(out.views("sRBG").empty());
  EXPECT_NO_THROW(out.checkDisplayView("sRGB", kAces));
  EXPECT_NO_THROW(out.checkDisplayView("sRGB", "Raw"));
}

TEST_F(OcioOutputTest, UnknownDisplayListsAvailableOnes) {
  OcioOutput out = OcioOutput::load();
  Error e = catchError([&] { out.checkDisplayView("sRBG", kAces); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_STREQ(e.what(), "output.display: unknown OCIO display 'sRBG' (available: sRGB)");
}

TEST_F(OcioOutputTest, UnknownViewListsViewsOfThatDisplay) {
  OcioOutput out = OcioOutput::load();
  Error e = catchError([&] { out.checkDisplayView("sRGB", "Filmic"); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_STREQ(e.what(),
               "output.view: unknown OCIO view 'Filmic' for display 'sRGB' (available: AgX, "
               "ACES 1.0 - SDR Video, Un-tone-mapped, Raw)");
}

TEST_F(OcioOutputTest, ToDisplayChecksThePairToo) {
  OcioOutput out = OcioOutput::load();
  std::vector<float> px{0.5f, 0.5f, 0.5f, 1.0f};
  Error e = catchError([&] { out.toDisplay(px, "sRGB", "Filmic", 0.0); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_EQ(px[0], 0.5f);  // untouched on error
}

TEST_F(OcioOutputTest, MissingConfigIsBadInputNamingFile) {
  const fs::path missing = dir() / "nope.ocio";
  Error e = catchError([&] { OcioOutput::load(missing); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
}

TEST_F(OcioOutputTest, UnparsableConfigIsOneLineBadInputWithOcioMessage) {
  const fs::path broken = dir() / "broken.ocio";
  writeFileAtomic(broken,
                  std::string_view("ocio_profile_version: 2\ncolorspaces: [\n  - {name: x\n"));
  Error e = catchError([&] { OcioOutput::load(broken); });
  const std::string msg = e.what();
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_NE(msg.find(broken.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("cannot load"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST_F(OcioOutputTest, ConfigWithoutSceneLinearRoleIsRejected) {
  std::string text = kTinyConfig;
  text.erase(text.find("  scene_linear: linear\n"), std::string("  scene_linear: linear\n").size());
  const fs::path path = dir() / "norole.ocio";
  writeFileAtomic(path, text);
  Error e = catchError([&] { OcioOutput::load(path); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_NE(std::string(e.what()).find("scene_linear"), std::string::npos) << e.what();
}

TEST_F(OcioOutputTest, OcioEnvironmentOverridesDefaultAndExplicitOverridesEnvironment) {
  const fs::path tiny = dir() / "tiny.ocio";
  writeFileAtomic(tiny, std::string_view(kTinyConfig));
  ::setenv("OCIO", tiny.c_str(), 1);

  OcioOutput fromEnv = OcioOutput::load();
  EXPECT_EQ(fromEnv.configPath(), tiny);
  EXPECT_EQ(fromEnv.displays(), std::vector<std::string>{"Tiny"});
  std::vector<float> px{0.25f, 0.5f, 2.0f, 1.0f};
  fromEnv.toDisplay(px, "Tiny", "Linear", 1.0);
  EXPECT_EQ(px, (std::vector<float>{0.5f, 1.0f, 4.0f, 1.0f}));

  const fs::path shipped = configDir() / "ocio" / "config.ocio";
  OcioOutput explicitOut = OcioOutput::load(shipped);
  EXPECT_EQ(explicitOut.configPath(), shipped);
  EXPECT_EQ(explicitOut.displays(), std::vector<std::string>{"sRGB"});
}

TEST_F(OcioOutputTest, UntonemappedViewIsSrgbEncodingClipped) {
  OcioOutput out = OcioOutput::load();
  const std::vector<float> in{0.18f,  0.18f,  0.18f,  1.0f,  // grey
                              0.0f,   0.0f,   0.0f,   1.0f,  // black
                              1.0f,   1.0f,   1.0f,   1.0f,  // white
                              1.0f,   0.0f,   0.0f,   1.0f,  // saturated primary
                              0.5f,   0.1f,   0.02f,  1.0f,  // saturated orange
                              0.002f, 0.01f,  0.7f,   1.0f,  // across the linear toe
                              100.0f, 100.0f, 100.0f, 1.0f, -0.1f, 0.5f, 0.5f, 1.0f};
  const std::vector<float> got = convert(out, in, kUntoned);
  for (size_t i = 0; i < in.size(); ++i) {
    if (i % 4 == 3) continue;
    EXPECT_NEAR(got[i], srgbEncode(in[i]), 2e-4f) << "value " << i << " input " << in[i];
  }
  EXPECT_NEAR(got[0], 0.461356f, 2e-4f);
}

TEST_F(OcioOutputTest, AcesViewMatchesMeasuredValues) {
  // Measured with OCIO 2.1.2 on this config. 1.0 -> 0.812 is the published ACES 1.0 sRGB value
  // (ACES Central, "Understanding the sRGB RRT/ODT"); 0.18 -> 0.356 follows from the RRT's
  // mid-grey at ~10% of peak luminance. Tolerance covers OCIO's fast pow/exp approximations.
  OcioOutput out = OcioOutput::load();
  const std::vector<float> in{0.18f, 0.18f, 0.18f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f,  1.0f,
                              1.0f,  1.0f,  1.0f,  0.0f, 0.0f, 1.0f, 0.5f, 0.1f, 0.02f, 1.0f};
  const std::vector<float> expected{0.355954f, 0.355954f, 0.355954f, 1.0f,      0.0f,
                                    0.0f,      0.0f,      1.0f,      0.811971f, 0.811971f,
                                    0.811971f, 1.0f,      0.803756f, 0.0f,      0.024502f,
                                    1.0f,      0.603653f, 0.239854f, 0.075292f, 1.0f};
  const std::vector<float> got = convert(out, in, kAces);
  for (size_t i = 0; i < in.size(); ++i) EXPECT_NEAR(got[i], expected[i], 5e-4f) << "value " << i;
}

TEST_F(OcioOutputTest, AcesViewStaysInDisplayRangeAndIsMonotonic) {
  OcioOutput out = OcioOutput::load();
  std::vector<float> ramp;
  for (float v = 1.0f / 1024.0f; v <= 1.0e4f; v *= 2.0f) ramp.insert(ramp.end(), {v, v, v, 1.0f});
  const std::vector<float> got = convert(out, ramp, kAces);
  // Strictly rising between the RRT's black toe (inputs below ~0.002 all reach display black)
  // and the point where the SDR tone scale reaches peak white (~16); flat outside.
  for (size_t i = 0; i + 4 < got.size(); i += 4) {
    if (ramp[i] >= 1.0f / 256.0f && ramp[i + 4] <= 16.0f)
      EXPECT_LT(got[i], got[i + 4]) << "input " << ramp[i];
    else
      EXPECT_LE(got[i], got[i + 4]) << "input " << ramp[i];
  }
  for (float v : got) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
  }
  const std::vector<float> bright = convert(out, {100.0f, 100.0f, 100.0f, 1.0f}, kAces);
  EXPECT_LE(bright[0], 1.0f);
  EXPECT_GT(bright[0], 0.99f);
}

TEST_F(OcioOutputTest, AgxViewIsThePublishedFormula) {
  // Display-linear values of scripts/ocio/make_agx.py --print R,G,B (AgX's formula in double,
  // the polynomial curve exact), encoded as the sRGB display encodes them. The tolerance covers
  // the curve's 4096-entry LUT and OCIO's fast log and pow.
  struct Case {
    float in[3];
    float displayLinear[3];
  };
  const Case cases[] = {
      {{0.18f, 0.18f, 0.18f}, {0.214519f, 0.214519f, 0.214519f}},  // middle grey
      {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}},
      {{1.0f, 1.0f, 1.0f}, {0.590159f, 0.590159f, 0.590159f}},
      {{16.0f, 16.0f, 16.0f}, {0.995108f, 0.995108f, 0.995108f}},
      {{1.0f, 0.0f, 0.0f}, {0.723267f, 0.105864f, 0.066756f}},
      {{0.5f, 0.1f, 0.02f}, {0.464477f, 0.146879f, 0.057093f}},
      {{0.02f, 0.05f, 0.6f}, {0.040821f, 0.136458f, 0.548421f}},
      {{1.0f, 0.66f, 0.31f}, {0.598848f, 0.483664f, 0.346991f}},  // a sunset-lit cloud
      {{0.001f, 0.001f, 0.001f}, {0.000106f, 0.000106f, 0.000106f}},
  };
  OcioOutput out = OcioOutput::load();
  for (const Case& c : cases) {
    const std::vector<float> got = convert(out, {c.in[0], c.in[1], c.in[2], 1.0f}, kAgx);
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(got[size_t(i)], srgbEncode(c.displayLinear[i]), 2e-3f)
          << "input " << c.in[0] << "," << c.in[1] << "," << c.in[2] << " channel " << i;
  }
}

TEST_F(OcioOutputTest, AgxViewStaysInDisplayRangeAndIsMonotonic) {
  OcioOutput out = OcioOutput::load();
  std::vector<float> ramp;
  for (float v = 1.0f / 4096.0f; v <= 16.0f; v *= 1.25f) ramp.insert(ramp.end(), {v, v, v, 1.0f});
  const std::vector<float> got = convert(out, ramp, kAgx);
  // Strictly rising over AgX's log range (2^-12.5 .. 2^4 times the middle grey's 0.18 / 0.18).
  for (size_t i = 0; i + 4 < got.size(); i += 4) EXPECT_LT(got[i], got[i + 4]) << "input " << ramp[i];
  for (float v : got) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
  }
}

TEST_F(OcioOutputTest, RawViewIsIdentity) {
  OcioOutput out = OcioOutput::load();
  const std::vector<float> in{0.18f, -0.5f, 100.0f, 1.0f, 0.0f, 1.0f, 1e-6f, 0.5f};
  EXPECT_EQ(convert(out, in, "Raw"), in);
}

TEST_F(OcioOutputTest, AlphaIsUntouched) {
  OcioOutput out = OcioOutput::load();
  const std::vector<float> in{0.5f, 0.2f, 0.1f, 0.25f, 3.0f, 2.0f,
                              1.0f, 2.0f, 0.1f, 0.1f,  0.1f, -1.0f};
  for (const char* view : {kAgx, kAces, kUntoned, "Raw"}) {
    const std::vector<float> got = convert(out, in, view, 2.5);
    for (size_t i = 3; i < in.size(); i += 4) EXPECT_EQ(got[i], in[i]) << view;
  }
}

TEST_F(OcioOutputTest, PlusOneEvEqualsDoublingTheInput) {
  OcioOutput out = OcioOutput::load();
  const std::vector<float> in{0.18f, 0.1f, 0.02f, 1.0f, 0.03f, 0.04f,
                              0.05f, 1.0f, 0.4f,  0.4f, 0.4f,  1.0f};
  std::vector<float> doubled = in, quartered = in;
  for (size_t i = 0; i < in.size(); ++i) {
    if (i % 4 == 3) continue;
    doubled[i] *= 2.0f;
    quartered[i] *= 0.25f;
  }
  for (const char* view : {kAgx, kAces, kUntoned, "Raw"}) {
    const std::vector<float> plusOne = convert(out, in, view, 1.0);
    const std::vector<float> reference = convert(out, doubled, view, 0.0);
    const std::vector<float> minusTwo = convert(out, in, view, -2.0);
    const std::vector<float> referenceQ = convert(out, quartered, view, 0.0);
    for (size_t i = 0; i < in.size(); ++i) {
      EXPECT_NEAR(plusOne[i], reference[i], 1e-5f) << view << " value " << i;
      EXPECT_NEAR(minusTwo[i], referenceQ[i], 1e-5f) << view << " value " << i;
    }
    // The exposure really changes the picture (guards against an ignored argument).
    EXPECT_GT(plusOne[0], convert(out, in, view, 0.0)[0]) << view;
  }
}

TEST_F(OcioOutputTest, ConcurrentCallsMatchSerialOnes) {
  OcioOutput out = OcioOutput::load();
  std::vector<float> base;
  for (int i = 0; i < 256; ++i) base.insert(base.end(), {i / 64.0f, i / 128.0f, i / 512.0f, 1.0f});
  std::vector<std::vector<float>> serial, parallel(8, base);
  for (int t = 0; t < 8; ++t)
    serial.push_back(convert(out, base, t % 2 ? kAces : kUntoned, t * 0.5));
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t)
    threads.emplace_back(
        [&, t] { out.toDisplay(parallel[size_t(t)], "sRGB", t % 2 ? kAces : kUntoned, t * 0.5); });
  for (std::thread& th : threads) th.join();
  EXPECT_EQ(parallel, serial);
}

TEST_F(OcioOutputTest, BadBufferAndExposureAreRejected) {
  OcioOutput out = OcioOutput::load();
  std::vector<float> three{0.1f, 0.2f, 0.3f};
  EXPECT_EQ(catchError([&] { out.toDisplay(three, "sRGB", "Raw", 0.0); }).kind(),
            ErrorKind::Internal);
  std::vector<float> px{0.1f, 0.2f, 0.3f, 1.0f};
  EXPECT_EQ(catchError([&] { out.toDisplay(px, "sRGB", "Raw", std::nan("")); }).kind(),
            ErrorKind::BadInput);
  std::vector<float> none;
  EXPECT_NO_THROW(out.toDisplay(none, "sRGB", kAces, 0.0));
}

TEST_F(OcioOutputTest, ADarkGradientUsesEveryCodeItSpans) {
  // A smooth scene-linear ramp from a dim twilight (0.002) to 0.03, 1024 x 8 px, through the
  // shipped ACES view into a dithered 8-bit PNG (the path of skyrender's PNG): its histogram
  // has no empty run between the darkest and the brightest code it uses. A view through a
  // coarse LUT or an 8-bit step before the curve would skip codes there, which the eye sees
  // as bands.
  const int w = 1024, h = 8;
  std::vector<float> rgba(size_t(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c)
        rgba[(size_t(y) * w + x) * 4 + c] =
            c < 3 ? 0.002f * std::pow(15.0f, (float(x) + 0.5f) / float(w)) : 1.0f;
  OcioOutput::load().toDisplay(rgba, "sRGB", kAces, 0.0);
  const std::filesystem::path png = dir() / "gradient.png";
  writePng8(png, w, h, rgba, PngQuantize::Dither);
  const Image8 back = readPng(png);
  std::vector<int> histogram(256, 0);
  for (size_t i = 0; i < back.pixels.size(); ++i)
    if (i % 4 != 3) ++histogram[back.pixels[i]];
  int lo = 0, hi = 255;
  while (lo < 255 && histogram[lo] == 0) ++lo;
  while (hi > 0 && histogram[hi] == 0) --hi;
  std::cout << "dark gradient: codes " << lo << " to " << hi << "\n";
  ASSERT_GT(hi - lo, 15) << "the ramp spans many codes";
  for (int code = lo; code <= hi; ++code) EXPECT_GT(histogram[code], 0) << "code " << code;
}

}  // namespace
}  // namespace sky
