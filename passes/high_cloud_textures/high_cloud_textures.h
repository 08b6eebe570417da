#pragma once
// The high-cloud layer's textures (Kozlov et al. section 3): the coefficient texture (R thin
// lit parts, G dense parts, B clear sky, A sparse edges), its tangent-space normal map and a
// coarse box-filtered copy for the far field, all persistent on the GPU and imported into
// each frame's graph. They come from the scene's images or from a procedural bake (styles
// cirrus, cirrostratus, cirrocumulus) that is cached on disk. A procedural bake also keeps
// each texel's rank and optical depth factor, so the draw can apply a cover per pixel
// (regional cover from the weather map's high layer). Channels, conventions, the image
// formats and the cache are described in docs/high-clouds.md.
#include <array>
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
enum class HighCloudStyle;

class HighCloudTextures {
public:
  struct Outputs {
    ImageId coefficients;        // RGBA16F, N x N (N = resolution or the image size)
    ImageId normals;             // RGBA16F, N x N, xyz unit tangent-space normal, w unused (0)
    ImageId coarse;              // RGBA16F, (N/16) x (N/16) (at least 4x4): box-filtered
    // RGBA16F, (N - 2C) x N/2 with C the coarse size: the coefficients' mip levels between
    // the texture and the coarse one, side by side (shaders/common/high_cloud_levels.glsl).
    ImageId levels;
    glm::vec4 mean{0, 0, 1, 0};  // the mean coefficients over the texture (far field)
    // Procedural sources only (invalid for images and the clear texture of cover 0): R the
    // texel's rank r, G its optical depth factor `shape`, BA 0; RGBA16F, N x N. At cover c a
    // texel's optical depth is shape * presence(r, c, rampWidth)
    // (shaders/common/high_cloud_coverage.glsl).
    ImageId rankShape;
    // addTo with regionalCover only (invalid otherwise): what the draw needs for a cover per
    // pixel. coverCoarse is RGBA16F 3D, coarse x coarse x HIGH_CLOUD_COVER_STEPS, layer k the
    // coarse texture at cover k / (HIGH_CLOUD_COVER_STEPS - 1); farField[k] its mean, so
    // farField.front() is clear (0, 0, 1, 0) and farField.back() the full-cover mean.
    ImageId coverCoarse;
    float rampWidth = 0.0f;  // the style's ramp width w (procedural sources)
    std::array<glm::vec4, HIGH_CLOUD_COVER_STEPS> farField{};
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
  // With `regionalCover` (the cover comes per pixel from the weather map, see
  // highCloudsFromWeather in passes/sky_high_clouds) the source must be procedural; `cover` and
  // `cover_map` are ignored: the bake runs at HIGH_CLOUD_REGIONAL_REFERENCE_COVER even when
  // `cover` is 0, and the per-cover coarse texture and far-field table are made from the
  // rank/shape texture (high_cloud_cover_reduce, after every load or bake).
  // Relative paths resolve with scene.resolvePath(). Bad files are BadInput errors naming the
  // key path and the file ("high_clouds.coefficients: clouds.png: must be RGBA (4 channels),
  // has 3"); after an error the next call loads again.
  Outputs addTo(FrameGraph& graph, const Scene& scene, bool regionalCover = false);
  const Activity& lastActivity() const { return mActivity; }
  void setProgress(Progress progress) { mProgress = std::move(progress); }
  const Sampler& sampler() const { return mSampler; }  // linear, repeat (the texture tiles)

  // The cache key of procedural settings (hex): style, cover, seed, resolution, the cover
  // map's bytes and the bake and normals shaders' preprocessed sources. With `regionalCover`,
  // the key of the reference-cover bake addTo makes then.
  std::string cacheKey(const Scene& scene, bool regionalCover = false) const;

  // The ramp width w of a procedural style (HIGH_CLOUD_RAMP_*).
  static float rampWidth(HighCloudStyle style);

private:
  // What the images must hold for `scene`: settings and input files' stamps, no file read.
  std::string signature(const Scene& scene, bool regionalCover) const;
  void makeClear();
  void loadImages(const Scene& scene);
  void loadProcedural(const Scene& scene, bool regionalCover);
  void bake(const Scene& scene, uint32_t size, const std::string& key,
            const std::filesystem::path& file, bool regionalCover);
  // Creates the images for an N x N texture unless they already have that size (rank/shape
  // with `rankShape`, the per-cover coarse texture with `coverCoarse`).
  void allocate(uint32_t size, bool rankShape, bool coverCoarse);
  // Runs levels, normals (if asked, from level `normalsLevel` with `normalsRelief`),
  // reduce and, with `regionalCover`, the per-cover reduce on the uploaded or baked textures
  // in one graph and sets the mean and the far-field table; reads back "coarse"
  // ("cover_coarse" with regionalCover), and "coefficients", "normals" and "rank_shape" when
  // `readAll`.
  FrameResult finish(bool deriveNormals, bool readAll, bool regionalCover,
                     uint32_t normalsLevel = 0,
                     float normalsRelief = float(HIGH_CLOUD_NORMAL_RELIEF));
  void addTimings(const FrameResult& result);
  void report(double fraction) const;

  const Context& mCtx;
  GraphRuntime& mRuntime;
  Sampler mSampler;
  HighCloudBakePass mBakePass;
  HighCloudNormalsPass mNormalsPass;
  HighCloudReducePass mReducePass;
  HighCloudLevelsPass mLevelsPass;
  HighCloudCoverReducePass mCoverReducePass;
  PersistentImage mCoefficients;
  PersistentImage mNormals;
  PersistentImage mCoarse;
  PersistentImage mLevels;
  PersistentImage mRankShape;    // procedural sources
  PersistentImage mCoverCoarse;  // regional cover
  PersistentImage mCoverMap;     // r16f; 1x1 white when the scene has none
  uint32_t mSize = 0;
  glm::vec4 mMean{0, 0, 1, 0};
  bool mHasRankShape = false;    // mRankShape holds the current procedural bake
  bool mHasCoverCoarse = false;  // mCoverCoarse and mFarField are current
  float mRampWidth = 0.0f;
  std::array<glm::vec4, HIGH_CLOUD_COVER_STEPS> mFarField{};
  std::optional<std::string> mSignature;  // of what the images hold now
  Activity mActivity;
  Progress mProgress;
};

}  // namespace sky
