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

// How display values become 8-bit codes: rounded to the nearest, or with triangular dither of
// one code's amplitude added first (Lipshitz, Wannamaker & Vanderkooy 1992: it makes the
// rounding error independent of the signal, so a smooth gradient shows no bands or contour
// rings, only a fine noise). The dither is a hash of the pixel and the channel, so the same
// image always gives the same file. Alpha is never dithered.
enum class PngQuantize { Nearest, Dither };

// Interleaved RGBA display values (already through the view transform) as 8-bit codes: each
// value clamped to [0, 1] and quantised as `quantize` says (NaN -> 0).
std::vector<uint8_t> quantize8(int width, int height, std::span<const float> displayRgba,
                               PngQuantize quantize);

// Writes interleaved RGBA display values as quantize8 makes them codes. Atomic; an
// unwritable path is a BadInput error naming it.
void writePng8(const std::filesystem::path& path, int width, int height,
               std::span<const float> displayRgba, PngQuantize quantize);

// Writes interleaved RGBA 8-bit codes as they are (a display image already quantised: the GPU
// display path's, a contact sheet). Atomic; errors as writePng8's.
void writePngCodes(const std::filesystem::path& path, int width, int height,
                   std::span<const uint8_t> rgba);

// Reads an 8-bit (16-bit is reduced to 8) PNG with the channels it has; a missing or corrupt
// file is a BadInput error naming the file.
Image8 readPng(const std::filesystem::path& path);

}  // namespace sky
