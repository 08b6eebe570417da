// The CI counterpart of tests/fuzz/image_fuzz.cpp: deterministic mutations (bit flips,
// truncations, zeroed and overwritten ranges, half of them in the header) of one small EXR
// and one small PNG from tests/data through readExr and readPng. Each must give an image
// whose pixel count matches its size, or a BadInput sky::Error with a one-line message that
// names the file; a crash or any other exception fails the test.
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"
#include "byte_mutation.h"
#include "io_test_util.h"

namespace sky {
namespace {

namespace fs = std::filesystem;

fs::path testData() {
  const char* v = std::getenv("SKY_TEST_DATA");  // set by tests/support's main()
  return v && *v ? fs::path(v) : fs::path("tests/data");
}

class ImageFuzz : public test::ScratchDirTest {
protected:
  void expectBadInput(const Error& e, const fs::path& file, int i) {
    ++errors;
    EXPECT_EQ(e.kind(), ErrorKind::BadInput) << i << ": " << e.what();
    EXPECT_TRUE(test::mentions(e, file)) << i << ": " << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << i << ": " << e.what();
  }
  int errors = 0, reads = 0;
};

TEST_F(ImageFuzz, MutatedExrEndsInAnImageOrABadInputError) {
  const std::string base = readTextFile(testData() / "high_clouds" / "coefficients_32.exr");
  ASSERT_GT(base.size(), 100u);
  ASSERT_EQ(base.substr(0, 4), std::string("\x76\x2f\x31\x01", 4));
  // The header and the chunk offset table take this file's first 352 bytes.
  const size_t header = 352;
  const fs::path file = dir() / "fuzz.exr";
  writeFileAtomic(file, base);
  ASSERT_NO_THROW(readExr(file));

  std::mt19937 rng(20240621);
  for (int i = 0; i < 300; ++i) {
    writeFileAtomic(file, test::mutateBytes(base, rng, (i / 3) % 4, {header, 16, 0}));
    try {
      const LayeredImage image = readExr(file);
      ++reads;
      ASSERT_GT(image.width, 0) << i;
      ASSERT_GT(image.height, 0) << i;
      ASSERT_FALSE(image.layers.empty()) << i;
      for (const ImageLayer& layer : image.layers) {
        ASSERT_FALSE(layer.channels.empty()) << i;
        ASSERT_EQ(layer.pixels.size(),
                  size_t(image.width) * size_t(image.height) * layer.channels.size())
            << i;
      }
    } catch (const Error& e) {
      expectBadInput(e, file, i);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "mutation " << i << ": not a sky::Error: " << e.what();
    }
  }
  // Both outcomes occur: the mutations neither all break the file nor all miss. (27 of 300
  // read: an attribute whose declared size runs past the file is refused before OpenEXR,
  // which ignored the size of fixed-size types, reads it.)
  EXPECT_GT(errors, 30);
  EXPECT_GT(reads, 20);
  RecordProperty("reads", reads);
}

TEST_F(ImageFuzz, MutatedPngEndsInAnImageOrABadInputError) {
  const std::string base = readTextFile(testData() / "high_clouds" / "rgb_64.png");
  ASSERT_GT(base.size(), 100u);
  ASSERT_EQ(base.substr(1, 3), "PNG");
  const fs::path file = dir() / "fuzz.png";
  writeFileAtomic(file, base);
  ASSERT_NO_THROW(readPng(file));

  std::mt19937 rng(20240621);
  for (int i = 0; i < 300; ++i) {
    // The signature, IHDR (size, depth, colour type) and the start of the first IDAT.
    writeFileAtomic(file, test::mutateBytes(base, rng, (i / 3) % 4, {64, 16, 0}));
    try {
      const Image8 image = readPng(file);
      ++reads;
      ASSERT_GT(image.width, 0) << i;
      ASSERT_GT(image.height, 0) << i;
      ASSERT_GE(image.channels, 1) << i;
      ASSERT_LE(image.channels, 4) << i;
      ASSERT_EQ(image.pixels.size(),
                size_t(image.width) * size_t(image.height) * size_t(image.channels))
          << i;
    } catch (const Error& e) {
      expectBadInput(e, file, i);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "mutation " << i << ": not a sky::Error: " << e.what();
    }
  }
  // Most edits break the zlib stream or a chunk length; a few (in pixels, in ignored CRCs
  // and ancillary chunks) still read.
  EXPECT_GT(errors, 100);
  EXPECT_GT(reads, 5);
  RecordProperty("reads", reads);
}

}  // namespace
}  // namespace sky
