#pragma once
// The high-cloud layer's textures (Kozlov et al. section 3): the coefficient texture (R thin
// lit parts, G dense parts, B clear sky, A sparse edges), its tangent-space normal map and a
// coarse box-filtered copy for the far field, all persistent on the GPU and imported into
// each frame's graph. They come from the scene's images or from a procedural bake (styles
// cirrus, cirrostratus, cirrocumulus) that is cached on disk. Channels, conventions, the
// image formats and the cache are described in docs/high-clouds.md.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "engine/gpu/sampler.h"
#include "engine/graph/frame_graph.h"
#include "passes/high_cloud_textures/high_cloud_passes.h"

namespace sky {

class Context;
class GraphRuntime;
class ShaderCompiler;
struct Scene;

class HighCloudTextures {
public:
  struct Outputs {
    ImageId coefficients;        // RGBA16F, N x N (N = resolution or the image size)
    ImageId normals;             // RGBA16F, N x N, xyz unit tangent-space normal, w unused (0)
    ImageId coarse;              // RGBA16F, (N/16) x (N/16) (at least 4x4): box-filtered
    glm::vec4 mean{0, 0, 1, 0};  // the mean coefficients over the texture (far field)
  };
  // What addTo did this time, for tests, reports and the progress bar.
  struct Activity {
    bool baked = false;         // ran the bake passes
    bool loadedCache = false;   // read the baked textures from the disk cache
    bool loadedImages = false;  // read the scene's coefficient/normal images
    // GPU times of the separate graphs addTo ran this time, one entry per pass name (the
    // bands of high_cloud_bake summed): the bake, and the normals/reduce passes that also run
    // after loading images or a cache entry. Empty when nothing ran.
    std::vector<PassTiming> bakeTimings;
    std::filesystem::path cacheFile;  // the cache entry used or written (procedural)
    bool wroteCache = false;          // a bake stored cacheFile (false if the folder is unwritable)
  };
  using Progress = std::function<void(double fraction)>;  // 0..1 during a bake

  // Compiles the three passes' shaders and creates the sampler; no textures yet.
  // `runtime` runs the bake graphs; all three must outlive this object.
  HighCloudTextures(const Context& ctx, ShaderCompiler& compiler, GraphRuntime& runtime);

  // Makes the textures for `scene.highClouds` current and imports them into `graph` (call
  // before adding the passes that read them; this object must outlive graph.execute()):
  //  - nothing changed since the last call (same settings, same input files by size and
  //    modification time): only imports; no pass, nothing read from disk;
  //  - source "image": reads `coefficients` (RGBA, square, power of two, 16..8192) and
  //    `normals` (same size, RGB or RGBA) or derives the normals when `normals` is empty;
  //  - source "procedural" with cover 0: a 16x16 clear texture (B = 1, others 0), no bake;
  //  - source "procedural": the disk cache entry cacheDir()/high_clouds/<key>.exr or, if it
  //    is absent or unreadable, a bake in separate graphs on the runtime, in bands with
  //    `progress` called between them, written to the cache atomically.
  // Relative paths resolve with scene.resolvePath(). Bad files are BadInput errors naming the
  // key path and the file ("high_clouds.coefficients: clouds.png: must be RGBA (4 channels),
  // has 3"); after an error the next call loads again.
  Outputs addTo(FrameGraph& graph, const Scene& scene);
  const Activity& lastActivity() const { return mActivity; }
  void setProgress(Progress progress) { mProgress = std::move(progress); }
  const Sampler& sampler() const { return mSampler; }  // linear, repeat (the texture tiles)

  // The cache key of procedural settings (hex): style, cover, seed, resolution, the cover
  // map's bytes and the bake and normals shaders' preprocessed sources.
  std::string cacheKey(const Scene& scene) const;

private:
  // What the images must hold for `scene`: settings and input files' stamps, no file read.
  std::string signature(const Scene& scene) const;
  void makeClear();
  void loadImages(const Scene& scene);
  void loadProcedural(const Scene& scene);
  void bake(const Scene& scene, uint32_t size, const std::string& key,
            const std::filesystem::path& file);
  // Creates the three images for an N x N texture unless they already have that size.
  void allocate(uint32_t size);
  // Runs normals (if asked) and reduce on the uploaded or baked coefficients in one graph and
  // sets the mean; reads back coarse (output 0), and coefficients and normals (1, 2) when
  // `readAll`.
  FrameResult finish(bool deriveNormals, bool readAll);
  void addTimings(const FrameResult& result);
  void report(double fraction) const;

  const Context& mCtx;
  GraphRuntime& mRuntime;
  Sampler mSampler;
  HighCloudBakePass mBakePass;
  HighCloudNormalsPass mNormalsPass;
  HighCloudReducePass mReducePass;
  PersistentImage mCoefficients;
  PersistentImage mNormals;
  PersistentImage mCoarse;
  PersistentImage mCoverMap;  // r16f; 1x1 white when the scene has none
  uint32_t mSize = 0;
  glm::vec4 mMean{0, 0, 1, 0};
  std::optional<std::string> mSignature;  // of what the images hold now
  Activity mActivity;
  Progress mProgress;
};

}  // namespace sky
