#include "engine/io/png.h"

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <cmath>

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
  writePng8(path, 3, 2, rgba);
  const Image8 back = readPng(path);
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.channels, 4);
  EXPECT_EQ(back.pixels, expected);
  EXPECT_EQ(entries(), std::vector<std::string>{"preview.png"});
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
  writePng8(dir() / "ok.png", 2, 2, std::vector<float>(16, 0.5f));
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
  Error e = catchError([&] { writePng8(noDir, 2, 2, rgba); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_TRUE(mentions(e, noDir)) << e.what();
  EXPECT_TRUE(entries().empty());

  fs::create_directory(dir() / "taken.png");
  e = catchError([&] { writePng8(dir() / "taken.png", 2, 2, rgba); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_EQ(entries(), std::vector<std::string>{"taken.png"});
}

TEST_F(PngTest, WrongBufferSizeIsInternal) {
  const std::vector<float> rgba(15, 0.5f);
  EXPECT_EQ(catchError([&] { writePng8(dir() / "a.png", 2, 2, rgba); }).kind(),
            ErrorKind::Internal);
  EXPECT_EQ(catchError([&] { writePng8(dir() / "a.png", 0, 2, {}); }).kind(), ErrorKind::Internal);
  EXPECT_TRUE(entries().empty());
}

}  // namespace
}  // namespace sky
