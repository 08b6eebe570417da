#include "engine/io/png.h"

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <utility>

#include "engine/core/files.h"
#include "tests/io/io_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::catchError;
using test::mentions;

class PngTest : public test::ScratchDirTest {};

TEST_F(PngTest, RoundTripClampsAndRoundsToNearest) {
  // 3x2 RGBA: row 0 = top.
  const std::vector<float> rgba{0.0f,           0.5f,           1.0f,
                                1.0f,  // 0, 127.5 -> 128, 255
                                -0.5f,          1.5f,           0.2f,
                                1.0f,  // clamped; 0.2 * 255 = 51
                                std::nanf(""),  0.25f,          0.75f,
                                0.0f,  // NaN -> 0; 63.75 -> 64; 191.25 -> 191
                                10.4f / 255.0f, 10.6f / 255.0f, 254.49f / 255.0f,
                                0.5f,           1.0f / 255.0f,  0.002f,
                                0.998f,         1.0f,           0.0f,
                                0.0f,           0.0f,           1.0f};
  const std::vector<uint8_t> expected{0,  128, 255, 255, 0, 255, 51,  255, 0, 64, 191, 0,
                                      10, 11,  254, 128, 1, 1,   254, 255, 0, 0,  0,   255};
  const fs::path path = dir() / "preview.png";
  writePng8(path, 3, 2, rgba, PngQuantize::Nearest);
  const Image8 back = readPng(path);
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.channels, 4);
  EXPECT_EQ(back.pixels, expected);
  EXPECT_EQ(entries(), std::vector<std::string>{"preview.png"});
}

TEST_F(PngTest, DitherKeepsADarkGradientFreeOfBands) {
  // A dark ramp over ten 8-bit codes (5 to 15), 256 x 32 px, alpha 0.5. Rounded to the
  // nearest code it is a staircase: each block of 4 x 32 px sits up to half a code off the
  // ramp, the same way down every column (bands). Dithered, the block means follow the ramp
  // and the steps dissolve into noise of at most one code.
  const int w = 256, h = 32;
  std::vector<float> rgba(size_t(w) * h * 4);
  auto ramp = [&](int x) { return (5.0f + 10.0f * (float(x) + 0.5f) / float(w)) / 255.0f; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) rgba[(size_t(y) * w + x) * 4 + c] = c < 3 ? ramp(x) : 0.5f;
  // The largest distance (in codes) of a 4-column block's mean from the ramp's, and the
  // largest distance of any code from its pixel's value.
  auto errors = [&](PngQuantize q) {
    const fs::path path = dir() / "ramp.png";
    writePng8(path, w, h, rgba, q);
    const Image8 back = readPng(path);
    double worstBlock = 0.0, worstPixel = 0.0;
    for (int c = 0; c < 3; ++c)
      for (int bx = 0; bx < w; bx += 4) {
        double sum = 0.0, want = 0.0;
        for (int y = 0; y < h; ++y)
          for (int x = bx; x < bx + 4; ++x) {
            const double code = back.pixels[(size_t(y) * w + x) * 4 + c];
            sum += code;
            want += 255.0 * ramp(x);
            worstPixel = std::max(worstPixel, std::abs(code - 255.0 * ramp(x)));
            EXPECT_EQ(back.pixels[(size_t(y) * w + x) * 4 + 3], 128) << "alpha is not dithered";
          }
        worstBlock = std::max(worstBlock, std::abs(sum - want) / (4.0 * h));
      }
    return std::pair{worstBlock, worstPixel};
  };
  const auto [nearestBlock, nearestPixel] = errors(PngQuantize::Nearest);
  const auto [ditherBlock, ditherPixel] = errors(PngQuantize::Dither);
  std::cout << "block error (codes): nearest " << nearestBlock << ", dithered " << ditherBlock
            << "\n";
  EXPECT_GT(nearestBlock, 0.35) << "the staircase";
  EXPECT_LT(ditherBlock, 0.2) << "dithered, the blocks follow the ramp";
  EXPECT_LE(nearestPixel, 0.5 + 1e-3);
  EXPECT_LT(ditherPixel, 1.5) << "the dither is a single code's";
  // The same image gives the same file.
  writePng8(dir() / "a.png", w, h, rgba, PngQuantize::Dither);
  writePng8(dir() / "b.png", w, h, rgba, PngQuantize::Dither);
  EXPECT_EQ(readBinaryFile(dir() / "a.png"), readBinaryFile(dir() / "b.png"));
}

TEST_F(PngTest, ReadsFilesWithFewerChannels) {
  const fs::path path = dir() / "grey.png";
  const uint8_t grey[4] = {0, 64, 128, 255};
  ASSERT_TRUE(stbi_write_png(path.c_str(), 2, 2, 1, grey, 2));
  const Image8 back = readPng(path);
  EXPECT_EQ(back.channels, 1);
  EXPECT_EQ(back.pixels, (std::vector<uint8_t>{0, 64, 128, 255}));
}

TEST_F(PngTest, CorruptAndMissingFilesAreBadInputNamingThem) {
  const fs::path corrupt = dir() / "corrupt.png";
  writePng8(dir() / "ok.png", 2, 2, std::vector<float>(16, 0.5f), PngQuantize::Nearest);
  std::vector<uint8_t> bytes = readBinaryFile(dir() / "ok.png");
  writeFileAtomic(corrupt, std::string_view(reinterpret_cast<const char*>(bytes.data()), 20));
  Error e = catchError([&] { readPng(corrupt); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_TRUE(mentions(e, corrupt)) << e.what();

  const fs::path missing = dir() / "missing.png";
  e = catchError([&] { readPng(missing); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_TRUE(mentions(e, missing)) << e.what();
}

TEST_F(PngTest, FailedWritesLeaveNoFiles) {
  const std::vector<float> rgba(16, 0.5f);
  const fs::path noDir = dir() / "no-such-dir" / "a.png";
  Error e = catchError([&] { writePng8(noDir, 2, 2, rgba, PngQuantize::Nearest); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_TRUE(mentions(e, noDir)) << e.what();
  EXPECT_TRUE(entries().empty());

  fs::create_directory(dir() / "taken.png");
  e = catchError([&] { writePng8(dir() / "taken.png", 2, 2, rgba, PngQuantize::Nearest); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_EQ(entries(), std::vector<std::string>{"taken.png"});
}

TEST_F(PngTest, WrongBufferSizeIsInternal) {
  const std::vector<float> rgba(15, 0.5f);
  EXPECT_EQ(
      catchError([&] { writePng8(dir() / "a.png", 2, 2, rgba, PngQuantize::Nearest); }).kind(),
            ErrorKind::Internal);
  EXPECT_EQ(catchError([&] { writePng8(dir() / "a.png", 0, 2, {}, PngQuantize::Nearest); }).kind(),
            ErrorKind::Internal);
  EXPECT_TRUE(entries().empty());
}

}  // namespace
}  // namespace sky
