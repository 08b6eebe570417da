#pragma once
// The volumetric clouds' tileable noise textures (Lu et al. 2023 Table 1; Tang et al. 2019):
// a 3D shape volume, a 3D detail volume and a 2D curl texture, baked on the GPU once per
// model, persistent, imported into each frame's graph and cached on disk. Channels, formulas
// and the cache are described in docs/cloud-noise.md.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/clouds/noise_volume.h"
#include "engine/gpu/sampler.h"
#include "engine/graph/frame_graph.h"
#include "engine/scene/scene.h"
#include "passes/cloud_noise/cloud_noise_passes.h"

namespace sky {

class Context;
class GraphRuntime;
class ShaderCompiler;

class CloudNoise {
public:
  struct Outputs {
    ImageId shape;   // 3D RGBA8 unorm, 128^3
    ImageId detail;  // 3D RGBA8 unorm, 32^3 (lu2023) or 64^3 (tang2019)
    ImageId curl;    // 2D RGBA8 unorm, 128^2, both models (xyz = 0.5 + 0.5 v, A = 1)
  };
  // What addTo did this time, for tests and reports.
  struct Activity {
    bool baked = false;                   // ran the bake passes
    bool loadedCache = false;             // read the textures from the disk cache
    std::vector<PassTiming> bakeTimings;  // GPU time per bake pass name; empty unless baked
    std::filesystem::path cacheFile;      // the cache entry used or written
    bool wroteCache = false;              // a bake stored cacheFile (false if unwritable)
    double wallMs = 0.0;                  // CPU clock time of the bake or load, read-back included
  };

  // Compiles the bake shaders and creates the sampler; no textures yet. `runtime` runs the
  // bake graph; all three must outlive this object.
  CloudNoise(const Context& ctx, ShaderCompiler& compiler, GraphRuntime& runtime);

  // Makes the textures of `model` current and imports them into `graph` (call before adding
  // the passes that read them; this object must outlive graph.execute()). Same model as last
  // time: only imports. Otherwise the disk cache entry cacheDir()/cloud_noise/<cacheKey>.bin
  // or, when it is absent or damaged, a bake in a separate graph on the runtime, stored to
  // the cache atomically.
  Outputs addTo(FrameGraph& graph, CloudModel model);
  const Activity& lastActivity() const { return mActivity; }
  const Sampler& sampler() const { return mSampler; }  // linear, repeat in u, v, w

  // The cache key of `model` (hex): the format version, the model, the sizes and the bake
  // shaders' preprocessed sources.
  std::string cacheKey(CloudModel model) const;

  // CPU copies of what the GPU textures hold now (filled from the bake's read-back or the
  // cache), valid until the next addTo with another model.
  const NoiseVolume& shapeVolume() const { return mShapeVolume; }
  const NoiseVolume& detailVolume() const { return mDetailVolume; }
  // The curl texture's texels: `size`^2 RGBA8 (one slice; NoiseVolume's layout, z = 0).
  const NoiseVolume& curlPlane() const { return mCurlPlane; }
  // Their channel means (channelMeans), computed once when the volumes change: what the
  // raymarch's level of detail fades each octave to.
  glm::vec4 shapeMean() const { return mShapeMean; }
  glm::vec4 detailMean() const { return mDetailMean; }

private:
  void load(CloudModel model);
  void bake(uint32_t modelId, const std::string& key, const std::filesystem::path& file);
  // Creates the images unless they already have these sizes.
  void allocate(uint32_t detailSize);
  void addTimings(const FrameResult& result);
  void setVolumes(NoiseVolume shape, NoiseVolume detail, NoiseVolume curl);

  const Context& mCtx;
  GraphRuntime& mRuntime;
  Sampler mSampler;
  CloudNoiseBakePass mVolumePass;
  CloudNoiseBakePass mCurlPass;
  PersistentImage mShape;
  PersistentImage mDetail;
  PersistentImage mCurl;
  NoiseVolume mShapeVolume;
  NoiseVolume mDetailVolume;
  NoiseVolume mCurlPlane;
  glm::vec4 mShapeMean{0.0f}, mDetailMean{0.0f};
  std::optional<CloudModel> mModel;  // what the images hold now
  Activity mActivity;
};

}  // namespace sky
