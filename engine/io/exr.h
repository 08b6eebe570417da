#pragma once
// Scene-linear image files: single-part, multi-layer OpenEXR (HALF channels unless a layer
// asks for FLOAT, ZIP).
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace sky {

// One named group of channels. Layer "" is the main image (channels "R","G","B","A");
// layer "sky" with channels {"R","G","B"} is stored as "sky.R", "sky.G", "sky.B".
// Pixels are interleaved, channel-major within a pixel (pixel i, channel c at
// pixels[i * channels.size() + c]), row 0 = top.
struct ImageLayer {
  std::string name;
  std::vector<std::string> channels;
  std::vector<float> pixels;
  // Stored as 32-bit FLOAT instead of HALF: for values past half's range (65504), such as
  // distances in metres.
  bool fullFloat = false;
  // Stored as 32-bit UINT: classes and labels, whole numbers 0 .. 2^32 - 1 (readExr gives
  // them back as floats, exact up to 2^24).
  bool integer = false;
};

struct LayeredImage {
  int width = 0;
  int height = 0;
  std::vector<ImageLayer> layers;
  // String attributes stored in the header, e.g. {"skylayers:scene", "clear_noon.yaml"}.
  std::map<std::string, std::string> attributes;

  // Pointer into `layers` (valid until layers changes), or nullptr when absent.
  const ImageLayer* find(std::string_view name) const;
};

// Writes HALF float, ZIP compressed, atomically (a failure leaves no file behind).
// A malformed image (pixel count, duplicate or empty names) is an internal error; an
// unwritable path is a BadInput error naming it.
void writeExr(const std::filesystem::path& path, const LayeredImage& image);

// Reads any flat EXR (scanline or tiled; first part of multi-part files) into layers
// grouped by the text before the last '.' of each channel name. Layers come back with the
// main layer "" first, then by name; within a layer R, G, B, A come first, then the other
// channels by name. A missing or corrupt file is a BadInput error naming the file.
LayeredImage readExr(const std::filesystem::path& path);

}  // namespace sky
