#include "engine/io/exr.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <string>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace sky {
namespace fs = std::filesystem;

namespace {

// Above this many floats a header is more likely corrupt than real (8 GiB of pixels).
constexpr size_t kMaxReadValues = size_t(1) << 31;
constexpr float kHalfMax = 65504.0f;

std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

std::string fullName(const std::string& layer, const std::string& channel) {
  return layer.empty() ? channel : layer + "." + channel;
}

// Order inside a layer: the colour channels in their usual order, then the rest by name.
int channelRank(const std::string& c) {
  static const char* kOrder[] = {"R", "G", "B", "A"};
  for (int i = 0; i < 4; ++i)
    if (c == kOrder[i]) return i;
  return 4;
}

// Float -> half with finite overflow clamped to the largest half: an infinity in a
// scene-linear file poisons every filter downstream, while NaN stays NaN so bugs remain
// visible.
half toHalf(float v) {
  if (std::isfinite(v)) v = std::clamp(v, -kHalfMax, kHalfMax);
  return half(v);
}

void checkImage(const LayeredImage& image) {
  if (image.width <= 0 || image.height <= 0)
    internalError("writeExr: image size " + std::to_string(image.width) + "x" +
                  std::to_string(image.height) + " is empty");
  const size_t pixels = size_t(image.width) * size_t(image.height);
  std::set<std::string> names;
  if (image.layers.empty()) internalError("writeExr: image has no layers");
  for (const ImageLayer& layer : image.layers) {
    if (layer.channels.empty())
      internalError("writeExr: layer '" + layer.name + "' has no channels");
    if (layer.pixels.size() != pixels * layer.channels.size())
      internalError("writeExr: layer '" + layer.name + "' has " +
                    std::to_string(layer.pixels.size()) + " values, expected " +
                    std::to_string(pixels * layer.channels.size()));
    for (const std::string& c : layer.channels) {
      if (c.empty() || c.find('.') != std::string::npos)
        internalError("writeExr: layer '" + layer.name + "' has invalid channel name '" + c + "'");
      if (!names.insert(fullName(layer.name, c)).second)
        internalError("writeExr: duplicate channel '" + fullName(layer.name, c) + "'");
    }
  }
}

}  // namespace

const ImageLayer* LayeredImage::find(std::string_view name) const {
  for (const ImageLayer& layer : layers)
    if (layer.name == name) return &layer;
  return nullptr;
}

void writeExr(const fs::path& path, const LayeredImage& image) {
  checkImage(image);

  // Converted per layer to HALF up front; the frame buffer then points at exactly what is
  // stored, so OpenEXR does no conversion of its own.
  std::vector<std::vector<half>> halves;
  halves.reserve(image.layers.size());
  std::vector<std::vector<uint32_t>> integers;
  integers.reserve(image.layers.size());
  Imf::Header header(image.width, image.height);
  Imf::FrameBuffer frame;
  try {
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& [key, value] : image.attributes)
      header.insert(key, Imf::StringAttribute(value));
    for (const ImageLayer& layer : image.layers) {
      const size_t n = layer.channels.size();
      if (layer.fullFloat) {
        for (size_t c = 0; c < n; ++c) {
          const std::string name = fullName(layer.name, layer.channels[c]);
          header.channels().insert(name, Imf::Channel(Imf::FLOAT));
          frame.insert(
              name,
              Imf::Slice(Imf::FLOAT,
                         const_cast<char*>(reinterpret_cast<const char*>(layer.pixels.data() + c)),
                         n * sizeof(float), size_t(image.width) * n * sizeof(float)));
        }
        continue;
      }
      if (layer.integer) {
        std::vector<uint32_t>& data = integers.emplace_back(layer.pixels.size());
        std::transform(layer.pixels.begin(), layer.pixels.end(), data.begin(), [](float v) {
          return v > 0.0f ? static_cast<uint32_t>(std::min(std::round(v), 4294967040.0f)) : 0u;
        });
        for (size_t c = 0; c < n; ++c) {
          const std::string name = fullName(layer.name, layer.channels[c]);
          header.channels().insert(name, Imf::Channel(Imf::UINT));
          frame.insert(name,
                       Imf::Slice(Imf::UINT, reinterpret_cast<char*>(data.data() + c),
                                  n * sizeof(uint32_t), size_t(image.width) * n * sizeof(uint32_t)));
        }
        continue;
      }
      std::vector<half>& data = halves.emplace_back(layer.pixels.size());
      std::transform(layer.pixels.begin(), layer.pixels.end(), data.begin(), toHalf);
      for (size_t c = 0; c < n; ++c) {
        const std::string name = fullName(layer.name, layer.channels[c]);
        header.channels().insert(name, Imf::Channel(Imf::HALF));
        frame.insert(name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(data.data() + c),
                                      n * sizeof(half), size_t(image.width) * n * sizeof(half)));
      }
    }
  } catch (const std::exception& e) {
    // Header problems are ours: an attribute name that clashes with a standard one.
    internalError("writeExr: " + path.string() + ": " + oneLine(e.what()));
  }

  // Checked up front: OpenEXR's own message would name the temporary file, not `path`.
  const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::is_directory(parent, ec))
    inputError(path.string() + ": cannot write EXR: folder " + parent.string() + " does not exist");

  writeFileAtomic(path, [&](const fs::path& tmp) {
    try {
      Imf::OutputFile file(tmp.c_str(), header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      inputError(path.string() + ": cannot write EXR: " + oneLine(e.what()));
    }
  });
}

namespace {
// The largest EXR read: a side of 32768 and 2^28 values (1 GiB of floats), far past any
// render, map or texture skylayers makes or reads (output sizes stop at 16384).
constexpr int64_t kMaxExrSide = 32768;
constexpr int64_t kMaxExrValues = int64_t(1) << 28;

// OpenEXR 3.1 allocates (and for strings fills) the size an attribute's header declares
// before it reads the value, so a 24-byte file claiming a 1.4 GB attribute took 1.4 GB and
// 5 s before failing (tests/fuzz image_fuzz, issue 31). Walks the header(s) the way the
// format lays them out (name, type, int32 size, value; an empty name ends a header; a
// multi-part file lists headers until an empty one) and refuses a size past the end of the
// file. Stops at anything it cannot follow and leaves that to OpenEXR.
void refuseOversizedAttributes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const uintmax_t fileSize = fs::file_size(path, ec);
  char head[8];
  if (ec || !in.read(head, 8)) return;
  const bool multiPart = static_cast<unsigned char>(head[5]) & 0x10;  // version flags, bit 12
  // A NUL-terminated string of at most 255 characters (long names); nullopt at the end of
  // the file or past that length.
  const auto text = [&]() -> std::optional<std::string> {
    std::string s;
    for (char c; in.get(c);) {
      if (c == 0) return s;
      if (s.size() == 255) return std::nullopt;
      s += c;
    }
    return std::nullopt;
  };
  for (int headers = 0; headers < 1024; ++headers) {
    for (;;) {
      const std::optional<std::string> name = text();
      if (!name) return;
      if (name->empty()) break;  // the end of this header (for a multi-part file's list: of all)
      if (!text()) return;       // the type
      unsigned char b[4];
      if (!in.read(reinterpret_cast<char*>(b), 4)) return;
      const int32_t size = int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 |
                                   uint32_t(b[3]) << 24);
      const std::streamoff at = in.tellg();
      if (at < 0) return;
      if (size < 0 || uintmax_t(size) > fileSize - uintmax_t(at))
        inputError(path.string() + ": cannot read EXR: header attribute '" + oneLine(*name) +
                   "' declares " + std::to_string(size) + " bytes, more than the " +
                   std::to_string(fileSize - uintmax_t(at)) + " left in the file");
      in.seekg(size, std::ios::cur);
    }
    if (!multiPart) return;
    // A multi-part file: the next header, or an empty one (a lone NUL) ending the list.
    if (in.peek() == 0 || !in) return;
  }
}
}  // namespace

LayeredImage readExr(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) inputError(path.string() + ": cannot read EXR: file not found");
  if (fs::is_directory(path, ec)) inputError(path.string() + ": cannot read EXR: is a directory");
  refuseSpecialFile(path);

  // A header can claim any data window: OpenEXR allocates its line-offset table from it in
  // the constructor, and we the pixels, so a 100-byte file took all memory (tests/fuzz
  // image_fuzz, issue 31). OpenEXR refuses a window past these sides before allocating; the
  // values are capped below.
  static const bool limited = [] {
    Imf::Header::setMaxImageSize(kMaxExrSide, kMaxExrSide);
    Imf::Header::setMaxTileSize(kMaxExrSide, kMaxExrSide);
    return true;
  }();
  (void)limited;
  refuseOversizedAttributes(path);

  LayeredImage image;
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i dw = header.dataWindow();
    const int64_t width = int64_t(dw.max.x) - dw.min.x + 1, height = int64_t(dw.max.y) - dw.min.y + 1;
    if (width <= 0 || height <= 0) inputError(path.string() + ": EXR has an empty data window");
    int64_t channels = 0;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) ++channels;
    if (width > kMaxExrSide || height > kMaxExrSide || width * height * channels > kMaxExrValues)
      inputError(path.string() + ": EXR data window " + std::to_string(width) + "x" +
                 std::to_string(height) + " with " + std::to_string(channels) +
                 " channels is larger than skylayers reads (" + std::to_string(kMaxExrSide) +
                 " a side, " + std::to_string(kMaxExrValues) + " values)");
    image.width = int(width);
    image.height = int(height);

    // Group channels into layers by the text before the last '.' ("sky.R" -> "sky", "R").
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      const std::string name = it.name();
      if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
        inputError(path.string() + ": EXR channel '" + name + "' is subsampled (unsupported)");
      const size_t dot = name.rfind('.');
      const std::string layerName = dot == std::string::npos ? "" : name.substr(0, dot);
      const std::string channel = dot == std::string::npos ? name : name.substr(dot + 1);
      auto layer = std::find_if(image.layers.begin(), image.layers.end(),
                                [&](const ImageLayer& l) { return l.name == layerName; });
      if (layer == image.layers.end()) {
        image.layers.push_back({layerName, {}, {}});
        layer = image.layers.end() - 1;
      }
      layer->channels.push_back(channel);
    }
    if (image.layers.empty()) inputError(path.string() + ": EXR has no channels");
    std::sort(image.layers.begin(), image.layers.end(),
              [](const ImageLayer& a, const ImageLayer& b) { return a.name < b.name; });

    const size_t pixels = size_t(image.width) * size_t(image.height);
    size_t total = 0;
    for (const ImageLayer& layer : image.layers) total += pixels * layer.channels.size();
    if (total > kMaxReadValues)
      inputError(path.string() + ": EXR of " + std::to_string(image.width) + "x" +
                 std::to_string(image.height) + " is too large to read");

    Imf::FrameBuffer frame;
    for (ImageLayer& layer : image.layers) {
      std::stable_sort(layer.channels.begin(), layer.channels.end(),
                       [](const std::string& a, const std::string& b) {
                         const int ra = channelRank(a), rb = channelRank(b);
                         return ra != rb ? ra < rb : a < b;
                       });
      const size_t n = layer.channels.size();
      layer.pixels.assign(pixels * n, 0.0f);
      for (size_t c = 0; c < n; ++c)
        frame.insert(fullName(layer.name, layer.channels[c]),
                     Imf::Slice::Make(Imf::FLOAT, layer.pixels.data() + c, dw, n * sizeof(float),
                                      size_t(image.width) * n * sizeof(float)));
    }
    file.setFrameBuffer(frame);
    file.readPixels(dw.min.y, dw.max.y);

    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        image.attributes[it.name()] = s->value();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    inputError(path.string() + ": cannot read EXR: " + oneLine(e.what()));
  }
  return image;
}

}  // namespace sky
