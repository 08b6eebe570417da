#include "passes/cloud_noise/cloud_noise.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string_view>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/paths.h"
#include "engine/graph/graph_runtime.h"
#include "passes/cloud_noise/cloud_noise_cache.h"

namespace sky {
namespace {
namespace fs = std::filesystem;

// Storage for the bake, sampled by the clouds, transfer for cache uploads and read-back.
constexpr VkImageUsageFlags kTextureUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
    VK_IMAGE_USAGE_TRANSFER_DST_BIT;
constexpr VkFormat kFormat = VK_FORMAT_R8G8B8A8_UNORM;
// Bumped when the meaning of a cache entry changes without its shaders changing.
constexpr std::string_view kCacheFormat = "cloud_noise cache v1";

uint32_t modelIdOf(CloudModel model) {
  switch (model) {
    case CloudModel::Lu2023:
      return CLOUD_NOISE_MODEL_LU2023;
    case CloudModel::Tang2019:
      return CLOUD_NOISE_MODEL_TANG2019;
  }
  internalError("cloud noise: no model " + std::to_string(static_cast<int>(model)));
}

uint32_t detailSizeOf(uint32_t modelId) {
  return modelId == CLOUD_NOISE_MODEL_TANG2019 ? CLOUD_NOISE_DETAIL_SIZE_TANG2019
                                               : CLOUD_NOISE_DETAIL_SIZE_LU2023;
}

PersistentImage makeImage(const Context& ctx, const char* name, const char* about, ImageDim dim,
                          uint32_t size) {
  ImageDesc desc;
  desc.name = name;
  desc.about = about;
  desc.dim = dim;
  desc.format = kFormat;
  desc.width = desc.height = size;
  desc.depth = dim == ImageDim::Tex3D ? size : 1;
  desc.usage = kTextureUsage;
  return {Image(ctx, desc), {}};
}

// UNORM bytes and the floats the engine's upload and read-back speak: b / 255 and back by
// rounding, which is exact both ways.
std::vector<uint8_t> toBytes(const std::vector<float>& pixels) {
  std::vector<uint8_t> out(pixels.size());
  for (size_t i = 0; i < pixels.size(); ++i)
    out[i] = static_cast<uint8_t>(std::lround(std::clamp(pixels[i], 0.0f, 1.0f) * 255.0f));
  return out;
}

}  // namespace

CloudNoise::CloudNoise(const Context& ctx, ShaderCompiler& compiler, GraphRuntime& runtime)
    : mCtx(ctx),
      mRuntime(runtime),
      mSampler(ctx, SamplerWrap::Repeat, true),
      mVolumePass(ctx, compiler, "cloud_noise_volume"),
      mCurlPass(ctx, compiler, "cloud_noise_curl") {}

CloudNoise::Outputs CloudNoise::addTo(FrameGraph& graph, CloudModel model) {
  mActivity = {};
  if (!mModel || *mModel != model) {
    // Forget what the images held until the new contents are complete: an error on the way
    // makes the next call load again.
    mModel.reset();
    const auto start = std::chrono::steady_clock::now();
    load(model);
    mActivity.wallMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    mModel = model;
  }
  Outputs out;
  out.shape = graph.importImage(mShape);
  out.detail = graph.importImage(mDetail);
  out.curl = graph.importImage(mCurl);
  return out;
}

std::string CloudNoise::cacheKey(CloudModel model) const {
  const uint32_t id = modelIdOf(model);
  std::string text(kCacheFormat);
  text += "|" + std::string(enumName(model)) + "|" + std::to_string(CLOUD_NOISE_SHAPE_SIZE) + "|" +
          std::to_string(detailSizeOf(id)) + "|" + std::to_string(CLOUD_NOISE_CURL_SIZE) + "|" +
          hex64(mVolumePass.sourceHash()) + "|" + hex64(mCurlPass.sourceHash());
  return hex64(hash64(text));
}

void CloudNoise::allocate(uint32_t detailSize) {
  if (!mShape.image)
    mShape = makeImage(mCtx, "cloud_noise_shape",
                       "cloud shape noise: Perlin-Worley or simplex (R), Worley fbm (GBA), 3D",
                       ImageDim::Tex3D, CLOUD_NOISE_SHAPE_SIZE);
  if (!mCurl.image)
    mCurl = makeImage(mCtx, "cloud_noise_curl",
                      "curl noise that distorts the detail noise (RGB: a 3D offset, 0.5 none)",
                      ImageDim::Tex2D, CLOUD_NOISE_CURL_SIZE);
  if (!mDetail.image || mDetail.image.desc().width != detailSize)
    mDetail = makeImage(mCtx, "cloud_noise_detail",
                        "cloud detail noise: Worley fbm (RGB) and Lu (14) NDfbm (A), 3D",
                        ImageDim::Tex3D, detailSize);
}

void CloudNoise::load(CloudModel model) {
  const uint32_t id = modelIdOf(model);
  const uint32_t detailSize = detailSizeOf(id);
  const std::string key = cacheKey(model);
  const fs::path file = cacheDir() / "cloud_noise" / (key + ".bin");
  mActivity.cacheFile = file;
  allocate(detailSize);
  if (std::optional<cloud_noise::CacheEntry> entry = cloud_noise::readCacheEntry(
          file, key, CLOUD_NOISE_SHAPE_SIZE, detailSize, CLOUD_NOISE_CURL_SIZE)) {
    // The cache holds the images' own RGBA8 texels: copied as they are.
    uploadNow(mRuntime, {{&mShape, {}, entry->shape.rgba},
                         {&mDetail, {}, entry->detail.rgba},
                         {&mCurl, {}, entry->curl}});
    setVolumes(std::move(entry->shape), std::move(entry->detail),
               {CLOUD_NOISE_CURL_SIZE, std::move(entry->curl)});
    mActivity.loadedCache = true;
    return;
  }
  bake(id, key, file);
}

void CloudNoise::bake(uint32_t modelId, const std::string& key, const fs::path& file) {
  FrameGraph graph(mRuntime, GraphUse::Bake);
  shared::CloudNoiseParams params{};
  params.size = glm::uvec4(CLOUD_NOISE_SHAPE_SIZE, modelId, CLOUD_NOISE_VOLUME_SHAPE, 0);
  const ImageId shape =
      mVolumePass.addTo(graph, {graph.importImage(mShape), params, "cloud_noise_shape"}).target;
  params.size = glm::uvec4(detailSizeOf(modelId), modelId, CLOUD_NOISE_VOLUME_DETAIL, 0);
  const ImageId detail =
      mVolumePass.addTo(graph, {graph.importImage(mDetail), params, "cloud_noise_detail"}).target;
  params.size = glm::uvec4(CLOUD_NOISE_CURL_SIZE, modelId, 0, 0);
  const ImageId curl = mCurlPass.addTo(graph, {graph.importImage(mCurl), params}).target;
  // The read-back feeds the CPU copies and the cache in the same submit as the bake.
  graph.requestOutput(shape, "shape");
  graph.requestOutput(detail, "detail");
  graph.requestOutput(curl, "curl");
  FrameResult result = graph.execute();
  addTimings(result);

  cloud_noise::CacheEntry entry;
  entry.shape = {CLOUD_NOISE_SHAPE_SIZE, toBytes(result.output("shape").pixels)};
  entry.detail = {detailSizeOf(modelId), toBytes(result.output("detail").pixels)};
  entry.curlSize = CLOUD_NOISE_CURL_SIZE;
  entry.curl = toBytes(result.output("curl").pixels);
  try {
    cloud_noise::writeCacheEntry(file, key, entry);
    mActivity.wroteCache = true;
  } catch (const Error& e) {
    // An unwritable cache folder costs a bake next time, not the render; the report says so.
    noteCacheWriteFailed(e.what());
  }
  setVolumes(std::move(entry.shape), std::move(entry.detail),
             {CLOUD_NOISE_CURL_SIZE, std::move(entry.curl)});
  mActivity.baked = true;
}

void CloudNoise::setVolumes(NoiseVolume shape, NoiseVolume detail, NoiseVolume curl) {
  mShapeVolume = std::move(shape);
  mDetailVolume = std::move(detail);
  mCurlPlane = std::move(curl);
  mShapeMean = channelMeans(mShapeVolume);
  mDetailMean = channelMeans(mDetailVolume);
}

void CloudNoise::addTimings(const FrameResult& result) {
  for (const PassTiming& t : result.passes) {
    if (t.name == "readback") continue;
    auto it = std::find_if(mActivity.bakeTimings.begin(), mActivity.bakeTimings.end(),
                           [&](const PassTiming& p) { return p.name == t.name; });
    if (it == mActivity.bakeTimings.end())
      mActivity.bakeTimings.push_back(t);
    else
      it->gpuMs += t.gpuMs;
  }
}

}  // namespace sky
