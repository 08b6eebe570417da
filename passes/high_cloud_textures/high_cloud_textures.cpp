#include "passes/high_cloud_textures/high_cloud_textures.h"

#include <algorithm>
#include <cstdio>
#include <string_view>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/paths.h"
#include "engine/graph/graph_runtime.h"
#include "engine/scene/scene.h"
#include "passes/high_cloud_textures/high_cloud_images.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using high_clouds::Texture;

// The clear texture of cover 0: the smallest size the textures take.
constexpr uint32_t kClearSize = high_clouds::kMinSize;
// Storage for the passes, sampled by the shading pass, transfer for uploads and read-back.
constexpr VkImageUsageFlags kTextureUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
    VK_IMAGE_USAGE_TRANSFER_DST_BIT;
// Bumped when the meaning of a cache entry changes without its shaders changing (v2: the
// rank/shape layer; v3: cirrus normals from a mip level at a third of the relief, chosen in C++
// by style and size).
constexpr std::string_view kCacheFormat = "high_clouds cache v3";

uint32_t coarseSizeOf(uint32_t n) {
  return std::max(n / HIGH_CLOUD_COARSE_DIVISOR, HIGH_CLOUD_COARSE_MIN);
}

// log2 of a power of two.
uint32_t log2Of(uint32_t v) {
  uint32_t l = 0;
  while (v > 1) {
    v >>= 1;
    ++l;
  }
  return l;
}

// Where a bake's normals come from. Cirrus: the mip level whose texels are 1/128 of the tile
// (235 m of a 30 km tile; at most the last level before the coarse one), the relief of its
// wisps without a lit and a dark flank on every fibre, at a third of the relief
// (HIGH_CLOUD_CIRRUS_NORMAL_RELIEF). Other styles keep the texture's own texels and the full
// relief: cirrocumulus cloudlets are a few texels across.
struct NormalsSource {
  uint32_t level = 0;
  float relief = float(HIGH_CLOUD_NORMAL_RELIEF);
};
NormalsSource normalsSourceOf(HighCloudStyle style, uint32_t n) {
  if (style != HighCloudStyle::Cirrus) return {};
  const uint32_t level = n <= 128 ? 0 : std::min(log2Of(n / 128), log2Of(n / coarseSizeOf(n)) - 1);
  return {level, float(HIGH_CLOUD_CIRRUS_NORMAL_RELIEF)};
}

// Bands of rows per bake: one per 64 rows, at most 32, so a 512 texture reports progress
// eight times and no single dispatch grows past 128 rows of a 4096 texture (a GPU watchdog).
uint32_t bandsFor(uint32_t n) {
  return std::clamp(n / 64u, 1u, 32u);
}

// With regional cover the bake's cover is the reference cover and the cover map does not
// apply: the weather map sets the cover per pixel at draw time.
double bakeCover(const HighCloudSettings& h, bool regionalCover) {
  return regionalCover ? HIGH_CLOUD_REGIONAL_REFERENCE_COVER : h.cover;
}
std::string bakeCoverMap(const HighCloudSettings& h, bool regionalCover) {
  return regionalCover ? std::string() : h.coverMap;
}

uint32_t styleId(HighCloudStyle style) {
  switch (style) {
    case HighCloudStyle::Cirrus:
      return HIGH_CLOUD_STYLE_CIRRUS;
    case HighCloudStyle::Cirrostratus:
      return HIGH_CLOUD_STYLE_CIRROSTRATUS;
    case HighCloudStyle::Cirrocumulus:
      return HIGH_CLOUD_STYLE_CIRROCUMULUS;
  }
  internalError("high cloud textures: no style " + std::to_string(static_cast<int>(style)));
}

uint32_t resolutionOf(const HighCloudSettings& h) {
  const auto n = static_cast<uint32_t>(h.resolution);
  if (h.resolution < int(high_clouds::kMinSize) || h.resolution > int(high_clouds::kMaxSize) ||
      (n & (n - 1)) != 0)
    inputError("high_clouds.resolution: " + std::to_string(h.resolution) +
               " must be a power of two from " + std::to_string(high_clouds::kMinSize) + " to " +
               std::to_string(high_clouds::kMaxSize));
  return n;
}

// Exact text of a double, so equal keys mean equal values.
std::string exact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::vector<float> constantTexture(uint32_t size, glm::vec4 value) {
  std::vector<float> out(size_t(size) * size * 4);
  for (size_t i = 0; i < out.size(); i += 4)
    for (int c = 0; c < 4; ++c) out[i + size_t(c)] = value[c];
  return out;
}

PersistentImage makeImage(const Context& ctx, const char* name, const char* about, VkFormat format,
                          uint32_t width, uint32_t height, VkImageUsageFlags usage,
                          uint32_t depth = 1, DebugView view = DebugView::Color) {
  ImageDesc desc;
  desc.name = name;
  desc.about = about;
  desc.view = view;
  desc.dim = depth > 1 ? ImageDim::Tex3D : ImageDim::Tex2D;
  desc.format = format;
  desc.width = width;
  desc.height = height;
  desc.depth = depth;
  desc.usage = usage;
  return {Image(ctx, desc), {}};
}

}  // namespace

HighCloudTextures::HighCloudTextures(const Context& ctx, ShaderCompiler& compiler,
                                     GraphRuntime& runtime)
    : mCtx(ctx),
      mRuntime(runtime),
      mSampler(ctx, SamplerWrap::Repeat, true),
      mBakePass(ctx, compiler, mSampler),
      mNormalsPass(ctx, compiler, mSampler),
      mReducePass(ctx, compiler),
      mLevelsPass(ctx, compiler),
      mCoverReducePass(ctx, compiler) {}

float HighCloudTextures::rampWidth(HighCloudStyle style) {
  switch (styleId(style)) {
    case HIGH_CLOUD_STYLE_CIRROSTRATUS:
      return float(HIGH_CLOUD_RAMP_CIRROSTRATUS);
    case HIGH_CLOUD_STYLE_CIRROCUMULUS:
      return float(HIGH_CLOUD_RAMP_CIRROCUMULUS);
    default:
      return float(HIGH_CLOUD_RAMP_CIRRUS);
  }
}

HighCloudTextures::Outputs HighCloudTextures::addTo(FrameGraph& graph, const Scene& scene,
                                                    bool regionalCover) {
  mActivity = {};
  const HighCloudSettings& h = scene.highClouds;
  if (regionalCover && h.source != HighCloudSource::Procedural)
    inputError(
        "high_clouds.cover_source: a cover from the weather map needs high_clouds.source "
        "procedural, not '" +
        std::string(enumName(h.source)) + "'");
  const std::string sig = signature(scene, regionalCover);
  if (!mSignature || *mSignature != sig) {
    // Forget what the images held until the new contents are complete: an error on the way
    // makes the next call load again.
    mSignature.reset();
    mHasRankShape = mHasCoverCoarse = false;
    if (h.source == HighCloudSource::Image)
      loadImages(scene);
    else if (!regionalCover && h.cover <= 0.0)
      makeClear();
    else
      loadProcedural(scene, regionalCover);
    mSignature = sig;
  }
  Outputs out;
  out.coefficients = graph.importImage(mCoefficients);
  out.normals = graph.importImage(mNormals);
  out.coarse = graph.importImage(mCoarse);
  out.levels = graph.importImage(mLevels);
  out.mean = mMean;
  if (mHasRankShape) {
    out.rankShape = graph.importImage(mRankShape);
    out.rampWidth = mRampWidth;
  }
  if (mHasCoverCoarse) {
    out.coverCoarse = graph.importImage(mCoverCoarse);
    out.farField = mFarField;
  }
  return out;
}

std::string HighCloudTextures::signature(const Scene& scene, bool regionalCover) const {
  const HighCloudSettings& h = scene.highClouds;
  auto file = [&](const std::string& path) {
    if (path.empty()) return std::string("-");
    const fs::path resolved = scene.resolvePath(path);
    return resolved.string() + "@" + high_clouds::fileStamp(resolved);
  };
  if (h.source == HighCloudSource::Image)
    return "image|" + file(h.coefficients) + "|" + file(h.normals);
  if (!regionalCover && h.cover <= 0.0) return "clear";
  return std::string(regionalCover ? "regional" : "procedural") + "|" + enumName(h.style) + "|" +
         exact(bakeCover(h, regionalCover)) + "|" + std::to_string(h.seed) + "|" +
         std::to_string(h.resolution) + "|" + file(bakeCoverMap(h, regionalCover));
}

std::string HighCloudTextures::cacheKey(const Scene& scene, bool regionalCover) const {
  const HighCloudSettings& h = scene.highClouds;
  const std::string coverMap = bakeCoverMap(h, regionalCover);
  std::string text(kCacheFormat);
  text += "|" + std::string(enumName(h.style)) + "|" + exact(bakeCover(h, regionalCover)) + "|" +
          std::to_string(h.seed) + "|" + std::to_string(h.resolution) + "|";
  if (!coverMap.empty()) {
    const fs::path path = scene.resolvePath(coverMap);
    std::error_code ec;
    if (!fs::exists(path, ec))
      inputError("high_clouds.cover_map: " + coverMap + ": file not found (" + path.string() + ")");
    const std::vector<uint8_t> bytes = readBinaryFile(path);
    text += hex64(hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size()}));
  }
  text += "|" + hex64(mBakePass.sourceHash()) + "|" + hex64(mNormalsPass.sourceHash());
  return hex64(hash64(text));
}

void HighCloudTextures::allocate(uint32_t size, bool rankShape, bool coverCoarse) {
  const VkFormat f = VK_FORMAT_R16G16B16A16_SFLOAT;
  const uint32_t c = coarseSizeOf(size);
  if (mSize != size || !mCoefficients.image) {
    mCoefficients = makeImage(
        mCtx, "high_cloud_coefficients",
        "high-cloud coefficient texture (R thin lit, G dense, B clear, A edges), Kozlov 3.1", f,
        size, size, kTextureUsage);
    mNormals =
        makeImage(mCtx, "high_cloud_normals", "high-cloud tangent-space normal map (xyz in -1..1)",
                  f, size, size, kTextureUsage, 1, DebugView::Normals);
    mCoarse = makeImage(mCtx, "high_cloud_coarse",
                        "the coefficient texture's mean over coarse cells (distant clouds)", f, c,
                        c, kTextureUsage);
    mLevels = makeImage(mCtx, "high_cloud_levels",
                        "the coefficient texture's mip levels between it and the coarse one, side "
                        "by side (footprint filtering)",
                        f, size - 2 * c, size / 2, kTextureUsage);
    mRankShape = {};
    mCoverCoarse = {};
    mSize = size;
  }
  if (rankShape && !mRankShape.image)
    mRankShape = makeImage(mCtx, "high_cloud_rank_shape",
                           "each texel's rank (R: the cover at which it turns cloudy) and optical depth factor (G)",
                           f,
                           size, size, kTextureUsage);
  if (coverCoarse && !mCoverCoarse.image)
    mCoverCoarse = makeImage(mCtx, "high_cloud_cover_coarse",
                             "coarse coefficients by cover step (slices side by side)", f, c, c,
                             kTextureUsage, HIGH_CLOUD_COVER_STEPS);
}

void HighCloudTextures::makeClear() {
  allocate(kClearSize, false, false);
  const glm::vec4 clear(0, 0, 1, 0);
  // The box filter of a constant is the constant: no reduce pass needed for the coarse
  // texture. The levels: 16 - 2 * 4 = 8 columns of 16 / 2 rows, level 1 alone, square.
  static_assert(kClearSize - 2 * HIGH_CLOUD_COARSE_MIN == kClearSize / 2);
  uploadNow(mRuntime, {{&mCoefficients, constantTexture(kClearSize, clear)},
                       {&mNormals, constantTexture(kClearSize, {0, 0, 1, 0})},
                       {&mCoarse, constantTexture(coarseSizeOf(kClearSize), clear)},
                       {&mLevels, constantTexture(kClearSize / 2, clear)}});
  mMean = clear;
}

void HighCloudTextures::loadImages(const Scene& scene) {
  const HighCloudSettings& h = scene.highClouds;
  if (h.coefficients.empty())
    inputError("high_clouds.coefficients: is required when source is image");
  // Every file is read and checked before the GPU images change.
  Texture coefficients = high_clouds::readCoefficients(scene.resolvePath(h.coefficients),
                                                       "high_clouds.coefficients", h.coefficients);
  Texture normals;
  if (!h.normals.empty())
    normals = high_clouds::readNormals(scene.resolvePath(h.normals), "high_clouds.normals",
                                       h.normals, coefficients.width);
  allocate(coefficients.width, false, false);
  uploadNow(mRuntime, {{&mCoefficients, coefficients.pixels}});
  if (!normals.pixels.empty()) uploadNow(mRuntime, {{&mNormals, normals.pixels}});
  finish(normals.pixels.empty(), false, false);
  mActivity.loadedImages = true;
}

void HighCloudTextures::loadProcedural(const Scene& scene, bool regionalCover) {
  const HighCloudSettings& h = scene.highClouds;
  const uint32_t size = resolutionOf(h);
  mRampWidth = rampWidth(h.style);
  const std::string key = cacheKey(scene, regionalCover);
  const fs::path file = cacheDir() / "high_clouds" / (key + ".exr");
  mActivity.cacheFile = file;
  if (std::optional<high_clouds::CacheEntry> entry = high_clouds::readCacheEntry(file, key, size)) {
    allocate(size, true, regionalCover);
    uploadNow(mRuntime, {{&mCoefficients, entry->coefficients},
                         {&mNormals, entry->normals},
                         {&mRankShape, entry->rankShape}});
    mHasRankShape = true;
    finish(false, false, regionalCover);
    mActivity.loadedCache = true;
    return;
  }
  bake(scene, size, key, file, regionalCover);
}

void HighCloudTextures::bake(const Scene& scene, uint32_t size, const std::string& key,
                             const fs::path& file, bool regionalCover) {
  const HighCloudSettings& h = scene.highClouds;
  report(0.0);
  const std::string coverMap = bakeCoverMap(h, regionalCover);
  const bool hasMap = !coverMap.empty();
  const Texture map = hasMap ? high_clouds::readCoverMap(scene.resolvePath(coverMap),
                                                         "high_clouds.cover_map", coverMap)
                             : Texture{1, 1, 1, {1.0f}};
  if (!mCoverMap.image || mCoverMap.image.desc().width != map.width ||
      mCoverMap.image.desc().height != map.height)
    mCoverMap = makeImage(mCtx, "high_cloud_cover_map", "high_clouds.cover_map, 0..1",
                          VK_FORMAT_R16_SFLOAT, map.width, map.height,
                          VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                          1, DebugView::Scalar);
  uploadNow(mRuntime, {{&mCoverMap, map.pixels}});
  allocate(size, true, regionalCover);

  const uint32_t bands = bandsFor(size), rows = size / bands;
  for (uint32_t b = 0; b < bands; ++b) {
    FrameGraph graph(mRuntime, GraphUse::Bake);
    HighCloudBakePass::Inputs in;
    in.coefficients = graph.importImage(mCoefficients);
    in.rankShape = graph.importImage(mRankShape);
    in.coverMap = graph.importImage(mCoverMap);
    in.params.size = glm::uvec4(size, b * rows, rows, styleId(h.style));
    in.params.cover =
        glm::vec4(float(bakeCover(h, regionalCover)), hasMap ? 1.0f : 0.0f, 0.0f, 0.0f);
    in.params.seed = glm::uvec4(static_cast<uint32_t>(h.seed), 0, 0, 0);
    graph.add(mBakePass, in);
    addTimings(graph.execute());
    report(double(b + 1) / double(bands + 1));
  }

  mHasRankShape = true;
  const NormalsSource normals = normalsSourceOf(h.style, size);
  FrameResult result = finish(true, true, regionalCover, normals.level, normals.relief);
  auto take = [&](std::string_view label) {
    for (ReadbackImage& o : result.outputs)
      if (o.label == label) return std::move(o.pixels);
    internalError("high_clouds: no read-back '" + std::string(label) + "'");
  };
  high_clouds::CacheEntry entry{size, take("coefficients"), take("normals"), take("rank_shape")};
  try {
    high_clouds::writeCacheEntry(file, key, entry);
    mActivity.wroteCache = true;
  } catch (const Error& e) {
    // An unwritable cache folder costs a bake next time, not the render; the report says so.
    noteCacheWriteFailed(e.what());
  }
  mActivity.baked = true;
  report(1.0);
}

FrameResult HighCloudTextures::finish(bool deriveNormals, bool readAll, bool regionalCover,
                                      uint32_t normalsLevel, float normalsRelief) {
  const uint32_t coarseSize = coarseSizeOf(mSize);
  FrameGraph graph(mRuntime, GraphUse::Bake);
  const ImageId coefficients = graph.importImage(mCoefficients);
  ImageId normals = graph.importImage(mNormals);
  ImageId coarse = graph.importImage(mCoarse);
  ImageId levels = graph.importImage(mLevels);
  const ImageId rankShape = mHasRankShape ? graph.importImage(mRankShape) : ImageId{};
  levels = graph.add(mLevelsPass, {coefficients, levels, mSize, coarseSize}).levels;
  if (deriveNormals)
    normals = graph
                  .add(mNormalsPass, {coefficients, levels, normals, mSize, coarseSize,
                                      normalsLevel, normalsRelief})
                  .normals;
  coarse = graph.add(mReducePass, {coefficients, coarse, mSize, coarseSize}).coarse;
  graph.requestOutput(coarse, "coarse");
  if (regionalCover) {
    if (!mHasRankShape) internalError("high_clouds: regional cover without a rank/shape texture");
    ImageId coverCoarse = graph.importImage(mCoverCoarse);
    coverCoarse =
        graph.add(mCoverReducePass, {rankShape, coverCoarse, mSize, coarseSize, mRampWidth})
            .coverCoarse;
    graph.requestOutput(coverCoarse, "cover_coarse");
  }
  if (readAll) {
    graph.requestOutput(coefficients, "coefficients");
    graph.requestOutput(normals, "normals");
    if (mHasRankShape) graph.requestOutput(rankShape, "rank_shape");
  }
  FrameResult result = graph.execute();
  addTimings(result);
  // Equal boxes: the mean of the coarse texels is the mean of the texture.
  auto meanOf = [](const float* px, size_t texels) {
    glm::dvec4 sum(0.0);
    for (size_t i = 0; i < texels * 4; i += 4)
      sum += glm::dvec4(px[i], px[i + 1], px[i + 2], px[i + 3]);
    return glm::vec4(sum / double(texels));
  };
  const std::vector<float>& px = result.output("coarse").pixels;
  mMean = meanOf(px.data(), px.size() / 4);
  if (regionalCover) {
    // The far-field table: the mean of each cover's layer (z-major read-back).
    const std::vector<float>& layers = result.output("cover_coarse").pixels;
    const size_t perLayer = size_t(coarseSize) * coarseSize;
    for (uint32_t k = 0; k < HIGH_CLOUD_COVER_STEPS; ++k)
      mFarField[k] = meanOf(layers.data() + k * perLayer * 4, perLayer);
    mHasCoverCoarse = true;
  }
  return result;
}

void HighCloudTextures::addTimings(const FrameResult& result) {
  for (const PassTiming& t : result.passes) {
    auto it = std::find_if(mActivity.bakeTimings.begin(), mActivity.bakeTimings.end(),
                           [&](const PassTiming& p) { return p.name == t.name; });
    if (it == mActivity.bakeTimings.end())
      mActivity.bakeTimings.push_back(t);
    else
      it->gpuMs += t.gpuMs;
  }
}

void HighCloudTextures::report(double fraction) const {
  if (mProgress) mProgress(fraction);
}

}  // namespace sky
