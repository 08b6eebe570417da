// libFuzzer entry for the image readers of engine/io (readExr, readPng), as `skyrender dsc`,
// weather maps and the high-cloud images use them: any input must end in an image or a
// sky::Error, never a crash, a leak, a hang or another exception. Both readers take a path,
// so the bytes go through a file of this process's own.
//
// The first byte picks the reader, so the seed folders (plain image files) work as they are:
// 0x76 (the first byte of EXR's magic) reads the whole input as EXR, 0x89 (PNG's) as PNG;
// any other first byte is dropped and picks EXR when odd, PNG when even.
//
// Findings in OpenEXR 3.1 (Debian 12): it allocates what a header declares before it reads
// anything behind it (an attribute's size, and for string attributes it also fills it), so
// a file of 24 bytes cost 1.4 GB and seconds before the read failed. readExr now walks the
// header first and refuses an attribute larger than the bytes left (issue 31), and caps the
// data window (a compressor's line buffer). Where OpenEXR's reading of a value (a channel
// list) does not end where its declared size says, the two walks part and OpenEXR may still
// allocate from garbage, so long runs use -fork=1 (libFuzzer then records out-of-memory
// inputs and goes on).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/error.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"

namespace {

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "image_fuzz: %s\n", what.c_str());
  std::abort();
}

void write(const std::filesystem::path& file, const uint8_t* data, size_t size) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
}

// What callers rely on after a successful read (readAny in passes/high_cloud_textures
// indexes pixels by width * height * channels).
void checkExr(const sky::LayeredImage& image) {
  if (image.width <= 0 || image.height <= 0) finding("EXR read with an empty size");
  if (image.layers.empty()) finding("EXR read with no layers");
  const size_t pixels = size_t(image.width) * size_t(image.height);
  for (const sky::ImageLayer& layer : image.layers) {
    if (layer.channels.empty()) finding("EXR layer '" + layer.name + "' has no channels");
    if (layer.pixels.size() != pixels * layer.channels.size())
      finding("EXR layer '" + layer.name + "' has " + std::to_string(layer.pixels.size()) +
              " values for " + std::to_string(pixels) + " pixels");
  }
}

void checkPng(const sky::Image8& image) {
  if (image.width <= 0 || image.height <= 0) finding("PNG read with an empty size");
  if (image.channels < 1 || image.channels > 4)
    finding("PNG read with " + std::to_string(image.channels) + " channels");
  if (image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
    finding("PNG pixel count does not match its size");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string stem =
      (std::filesystem::temp_directory_path() / ("sky_image_fuzz_" + std::to_string(::getpid())))
          .string();
  static const std::filesystem::path exrFile = stem + ".exr", pngFile = stem + ".png";
  if (size == 0) return 0;
  bool exr = data[0] == 0x76;
  if (data[0] != 0x76 && data[0] != 0x89) {
    exr = data[0] & 1;
    ++data;
    --size;
  }
  try {
    if (exr) {
      write(exrFile, data, size);
      checkExr(sky::readExr(exrFile));
    } else {
      write(pngFile, data, size);
      checkPng(sky::readPng(pngFile));
    }
  } catch (const sky::Error&) {
    // Bad input is expected; anything else escapes and libFuzzer reports it.
  }
  return 0;
}
