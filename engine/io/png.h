#pragma once
// 8-bit display-referred images (previews, golden references).
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace sky {

struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 0;             // as stored in the file: 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA
  std::vector<uint8_t> pixels;  // interleaved, row 0 = top
};

// Writes interleaved RGBA display values (already through the view transform): each value
// is clamped to [0, 1] and rounded to the nearest 8-bit code (NaN -> 0). Atomic; an
// unwritable path is a BadInput error naming it.
void writePng8(const std::filesystem::path& path, int width, int height,
               std::span<const float> displayRgba);

// Reads an 8-bit (16-bit is reduced to 8) PNG with the channels it has; a missing or corrupt
// file is a BadInput error naming the file.
Image8 readPng(const std::filesystem::path& path);

}  // namespace sky
