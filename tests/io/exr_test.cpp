#include "engine/io/exr.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>

#include "engine/core/files.h"
#include "tests/io/io_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::catchError;
using test::mentions;

constexpr int kW = 7, kH = 5;

// Distinct value per layer, pixel and channel, spread over many magnitudes so a swapped
// row, channel or layer shows up.
float pattern(int layer, int x, int y, int c) {
  return (1.0f + float(layer)) * (0.01f * float(x + 1) + float(y) * 1.5f) *
         std::pow(4.0f, float(c - 1));
}

ImageLayer makeLayer(int index, std::string name, std::vector<std::string> channels) {
  ImageLayer layer{std::move(name), std::move(channels), {}};
  const int n = int(layer.channels.size());
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < n; ++c) layer.pixels.push_back(pattern(index, x, y, c));
  return layer;
}

LayeredImage makeImage() {
  LayeredImage image;
  image.width = kW;
  image.height = kH;
  image.layers.push_back(makeLayer(0, "", {"R", "G", "B", "A"}));
  image.layers.push_back(makeLayer(1, "sky", {"R", "G", "B"}));
  image.layers.push_back(makeLayer(2, "depth", {"Z"}));
  image.attributes["skylayers:scene"] = "clear_noon.yaml";
  return image;
}

void expectHalfClose(const ImageLayer& got, const ImageLayer& want) {
  ASSERT_EQ(got.channels, want.channels) << "layer '" << want.name << "'";
  ASSERT_EQ(got.pixels.size(), want.pixels.size());
  for (size_t i = 0; i < want.pixels.size(); ++i)
    // half keeps 11 significant bits: relative error <= 2^-11.
    EXPECT_NEAR(got.pixels[i], want.pixels[i], std::abs(want.pixels[i]) * 4.9e-4f + 1e-7f)
        << "layer '" << want.name << "' value " << i;
}

class ExrTest : public test::ScratchDirTest {};

TEST_F(ExrTest, RoundTripMainAndNamedLayers) {
  const LayeredImage image = makeImage();
  const fs::path path = dir() / "frame.exr";
  writeExr(path, image);
  const LayeredImage back = readExr(path);
  EXPECT_EQ(back.width, kW);
  EXPECT_EQ(back.height, kH);
  ASSERT_EQ(back.layers.size(), 3u);
  for (const ImageLayer& want : image.layers) {
    const ImageLayer* got = back.find(want.name);
    ASSERT_NE(got, nullptr) << want.name;
    expectHalfClose(*got, want);
  }
  EXPECT_EQ(back.layers[0].name, "");  // main layer first
  EXPECT_EQ(back.find("clouds"), nullptr);
  EXPECT_EQ(back.attributes.at("skylayers:scene"), "clear_noon.yaml");
  EXPECT_EQ(entries(), std::vector<std::string>{"frame.exr"});
}

TEST_F(ExrTest, FileHoldsExactChannelNamesAsHalfZipSinglePart) {
  const fs::path path = dir() / "frame.exr";
  writeExr(path, makeImage());

  Imf::MultiPartInputFile parts(path.c_str());
  EXPECT_EQ(parts.parts(), 1);
  Imf::InputFile file(path.c_str());
  EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION);
  std::set<std::string> names;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    names.insert(it.name());
    EXPECT_EQ(it.channel().type, Imf::HALF) << it.name();
  }
  EXPECT_EQ(names,
            (std::set<std::string>{"R", "G", "B", "A", "sky.R", "sky.G", "sky.B", "depth.Z"}));

  // Row 0 of the image is the first scanline of the file (top of the picture).
  const Imath::Box2i dw = file.header().dataWindow();
  EXPECT_EQ(dw.min, Imath::V2i(0, 0));
  EXPECT_EQ(dw.max, Imath::V2i(kW - 1, kH - 1));
  std::vector<float> red(size_t(kW * kH));
  Imf::FrameBuffer frame;
  frame.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(red.data()), sizeof(float),
                               sizeof(float) * kW));
  file.setFrameBuffer(frame);
  file.readPixels(0, kH - 1);
  EXPECT_NEAR(red[0], pattern(0, 0, 0, 0), 1e-4f);
  EXPECT_NEAR(red[size_t(kW * (kH - 1) + 3)], pattern(0, 3, kH - 1, 0), 1e-2f);
}

TEST_F(ExrTest, ValuesBeyondHalfRangeClampButNanSurvives) {
  LayeredImage image;
  image.width = 2;
  image.height = 1;
  image.layers.push_back({"", {"R", "G"}, {1.0e6f, -1.0e6f, std::nanf(""), 65504.0f}});
  const fs::path path = dir() / "range.exr";
  writeExr(path, image);
  const LayeredImage back = readExr(path);
  ASSERT_EQ(back.layers.size(), 1u);
  EXPECT_EQ(back.layers[0].pixels[0], 65504.0f);
  EXPECT_EQ(back.layers[0].pixels[1], -65504.0f);
  EXPECT_TRUE(std::isnan(back.layers[0].pixels[2]));
  EXPECT_EQ(back.layers[0].pixels[3], 65504.0f);
}

TEST_F(ExrTest, FullFloatLayersKeepDistancesPastHalfRange) {
  // clouds.depth: horizon clouds lie 30-200 km away, past half's 65504.
  LayeredImage image;
  image.width = 2;
  image.height = 1;
  image.layers.push_back({"", {"R"}, {0.5f, 1.0f}});
  image.layers.push_back({"clouds", {"A", "depth"}, {0.25f, 187654.3f, 1.0f, 1.0e-3f}, true});
  const fs::path path = dir() / "float.exr";
  writeExr(path, image);
  Imf::InputFile file(path.c_str());
  EXPECT_EQ(file.header().channels().findChannel("clouds.depth")->type, Imf::FLOAT);
  EXPECT_EQ(file.header().channels().findChannel("R")->type, Imf::HALF);
  const LayeredImage back = readExr(path);
  const ImageLayer* clouds = back.find("clouds");
  ASSERT_NE(clouds, nullptr);
  EXPECT_EQ(clouds->pixels, (std::vector<float>{0.25f, 187654.3f, 1.0f, 1.0e-3f}));
}

TEST_F(ExrTest, ReadsRgbaFileFromOtherToolsWithOffsetDataWindow) {
  // The way other tools write: RgbaOutputFile, PIZ, a data window that does not start at 0.
  const fs::path path = dir() / "other.exr";
  const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(31, 31));
  const Imath::Box2i data(Imath::V2i(10, 20), Imath::V2i(13, 22));
  std::vector<Imf::Rgba> px;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      px.emplace_back(half(float(x)), half(float(y)), half(0.5f), half(1.0f));
  {
    Imf::RgbaOutputFile out(path.c_str(), display, data, Imf::WRITE_RGBA, 1.0f, Imath::V2f(0, 0),
                            1.0f, Imf::INCREASING_Y, Imf::PIZ_COMPRESSION);
    out.setFrameBuffer(px.data() - 10 - 20 * 4, 1, 4);
    out.writePixels(3);
  }
  const LayeredImage back = readExr(path);
  EXPECT_EQ(back.width, 4);
  EXPECT_EQ(back.height, 3);
  ASSERT_EQ(back.layers.size(), 1u);
  EXPECT_EQ(back.layers[0].name, "");
  EXPECT_EQ(back.layers[0].channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  const std::vector<float>& p = back.layers[0].pixels;
  // Pixel (x=3, y=2): R = 3, G = 2.
  EXPECT_EQ(p[(2 * 4 + 3) * 4 + 0], 3.0f);
  EXPECT_EQ(p[(2 * 4 + 3) * 4 + 1], 2.0f);
  EXPECT_EQ(p[(2 * 4 + 3) * 4 + 2], 0.5f);
  EXPECT_EQ(p[(2 * 4 + 3) * 4 + 3], 1.0f);
}

// A header may claim any data window (tests/fuzz image_fuzz took all memory with a 100-byte
// file): past 32768 a side, or 2^28 values, the file is refused before anything is allocated
// for its pixels.
TEST_F(ExrTest, AHugeDataWindowIsRefusedBeforeItsPixels) {
  LayeredImage image;
  image.width = 4;
  image.height = 4;
  image.layers.push_back({"", {"R"}, std::vector<float>(16, 0.5f)});
  const fs::path good = dir() / "small.exr";
  writeExr(good, image);
  std::string bytes = readTextFile(good);
  const std::string key("dataWindow\0box2i\0", 17);
  const size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  std::string patched = bytes;
  const int32_t box[4] = {0, 0, 99999, 3};  // little-endian, as EXR stores it
  patched.replace(at + key.size() + 4, 16, reinterpret_cast<const char*>(box), 16);
  const fs::path big = dir() / "big.exr";
  writeFileAtomic(big, patched);
  Error e = catchError([&] { readExr(big); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
  EXPECT_TRUE(mentions(e, big)) << e.what();
  EXPECT_NE(std::string(e.what()).find("exceeds the maximum width of 32768"), std::string::npos)
      << e.what();
}

TEST_F(ExrTest, AnAttributeLongerThanTheFileIsRefusedBeforeOpenExrAllocatesIt) {
  // The fuzz finding: 24 bytes whose one attribute claims 2 GB (OpenEXR 3.1 allocated and
  // filled 1.4 GB of it before failing). A multi-part file's second header too.
  const std::string magic("\x76\x2f\x31\x01", 4);
  const std::string huge("\xff\xff\xff\x7f", 4);
  struct Case {
    const char* name;
    std::string bytes;
  };
  const Case cases[] = {
      {"single.exr", magic + std::string("\x02\0\0\0", 4) + std::string("a\0string\0", 9) + huge},
      {"multi.exr", magic + std::string("\x02\x10\0\0", 4) +
                        std::string("a\0int\0\x04\0\0\0\x01\0\0\0\0", 15) +
                        std::string("bb\0string\0", 10) + huge + "x"},
  };
  for (const Case& c : cases) {
    const fs::path file = dir() / c.name;
    writeFileAtomic(file, c.bytes);
    Error e = catchError([&] { readExr(file); });
    EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
    EXPECT_TRUE(mentions(e, file)) << e.what();
    EXPECT_NE(std::string(e.what()).find("declares 2147483647 bytes, more than the"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(ExrTest, TruncatedFileIsBadInputNamingIt) {
  LayeredImage image;
  image.width = 64;
  image.height = 64;
  ImageLayer layer{"", {"R", "G", "B"}, {}};
  uint32_t state = 12345;  // fixed LCG noise so ZIP cannot shrink the data much
  for (int i = 0; i < 64 * 64 * 3; ++i) {
    state = state * 1664525u + 1013904223u;
    layer.pixels.push_back(float(state >> 8) / float(1 << 24));
  }
  image.layers.push_back(layer);
  const fs::path good = dir() / "good.exr";
  writeExr(good, image);
  const std::vector<uint8_t> bytes = readBinaryFile(good);

  for (size_t keep : {bytes.size() / 2, size_t(40), size_t(3)}) {
    const fs::path cut = dir() / ("cut" + std::to_string(keep) + ".exr");
    writeFileAtomic(cut, std::string_view(reinterpret_cast<const char*>(bytes.data()), keep));
    Error e = catchError([&] { readExr(cut); });
    EXPECT_EQ(e.kind(), ErrorKind::BadInput) << keep;
    EXPECT_TRUE(mentions(e, cut)) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST_F(ExrTest, GarbageAndMissingFilesAreBadInput) {
  const fs::path garbage = dir() / "garbage.exr";
  writeFileAtomic(garbage, std::string_view("this is not an OpenEXR file at all"));
  Error e = catchError([&] { readExr(garbage); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_TRUE(mentions(e, garbage)) << e.what();

  const fs::path missing = dir() / "missing.exr";
  e = catchError([&] { readExr(missing); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_TRUE(mentions(e, missing)) << e.what();
}

TEST_F(ExrTest, FailedWritesLeaveNoFiles) {
  const LayeredImage image = makeImage();
  // Target inside a folder that does not exist.
  const fs::path noDir = dir() / "no-such-dir" / "frame.exr";
  Error e = catchError([&] { writeExr(noDir, image); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_TRUE(mentions(e, noDir)) << e.what();
  EXPECT_TRUE(entries().empty());

  // Target that is a folder: the temporary is written, then cannot replace the folder.
  fs::create_directory(dir() / "taken.exr");
  e = catchError([&] { writeExr(dir() / "taken.exr", image); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_TRUE(mentions(e, dir() / "taken.exr")) << e.what();
  EXPECT_EQ(entries(), std::vector<std::string>{"taken.exr"});
  EXPECT_TRUE(fs::is_directory(dir() / "taken.exr"));
}

TEST_F(ExrTest, OverwriteReplacesWholeFileAndBadImageKeepsOldOne) {
  const fs::path path = dir() / "frame.exr";
  writeExr(path, makeImage());
  LayeredImage small;
  small.width = 1;
  small.height = 1;
  small.layers.push_back({"", {"Y"}, {0.25f}});
  writeExr(path, small);
  LayeredImage back = readExr(path);
  ASSERT_EQ(back.layers.size(), 1u);
  EXPECT_EQ(back.layers[0].channels, std::vector<std::string>{"Y"});
  EXPECT_EQ(back.layers[0].pixels, std::vector<float>{0.25f});

  LayeredImage bad = small;
  bad.layers[0].pixels.push_back(1.0f);  // one value too many
  EXPECT_EQ(catchError([&] { writeExr(path, bad); }).kind(), ErrorKind::Internal);
  EXPECT_EQ(readExr(path).layers[0].pixels, std::vector<float>{0.25f});
  EXPECT_EQ(entries(), std::vector<std::string>{"frame.exr"});
}

TEST_F(ExrTest, MalformedImagesAreInternalErrors) {
  const fs::path path = dir() / "x.exr";
  LayeredImage dup = makeImage();
  dup.layers.push_back(makeLayer(3, "sky", {"R"}));
  EXPECT_EQ(catchError([&] { writeExr(path, dup); }).kind(), ErrorKind::Internal);
  LayeredImage dotted = makeImage();
  dotted.layers[2].channels[0] = "a.b";
  EXPECT_EQ(catchError([&] { writeExr(path, dotted); }).kind(), ErrorKind::Internal);
  LayeredImage empty;
  EXPECT_EQ(catchError([&] { writeExr(path, empty); }).kind(), ErrorKind::Internal);
  EXPECT_TRUE(entries().empty());
}

}  // namespace
}  // namespace sky
