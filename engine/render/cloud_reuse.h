#pragma once
// The cloud history: temporal reuse of the volumetric clouds across the frames of a sequence
// (clouds.temporal; docs/clouds.md, "Temporal reuse"). It keeps the two history images
// (HistoryImage) and which frame they hold, decides each frame's step (whether last frame's
// clouds can be reprojected, or a cut, and which pixel of each block this frame marches) and
// adds the pass that merges the frame's sparse march with the history (passes/cloud_temporal).
// One of the Renderer's jobs, apart from the sky, the clouds and the outputs.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "engine/graph/frame_graph.h"
#include "engine/gpu/sampler.h"
#include "engine/scene/scene.h"
#include "passes/cloud_temporal/cloud_temporal.h"
#include "shaders/common/view_shared.h"

namespace sky {

class Context;
class ShaderCompiler;

// `scene` without the camera's pose and the time: what temporal reuse and the clouds' kept
// products (light volume, shadow map) compare to see whether anything else changed.
Scene withoutPose(const Scene& scene);

// A revision number for each distinct scene it is shown, compared without the camera's pose
// and the time, field by field (Scene's operator==, which the compiler writes, so a new key
// is compared without anyone remembering to). A kept product carries the number, not the
// scene. The last kRemembered distinct scenes keep their numbers: the views of a rig differ
// in size and field of view, and each finds its own number again frame after frame.
class SettingsRevisions {
public:
  static constexpr size_t kRemembered = 8;
  uint64_t of(const Scene& scene);

private:
  std::vector<std::pair<Scene, uint64_t>> mKnown;  // the most recently shown first
  uint64_t mNext = 1;
};

class CloudReuse {
public:
  CloudReuse(const Context& ctx, ShaderCompiler& compiler);

  // This frame's step of the history.
  struct Step {
    bool valid = false;  // last frame's clouds can be reprojected (false: a cut)
    uint32_t block = 1;  // this frame marches one pixel of each block x block square
    glm::uvec2 offset{0};
    CloudTemporalMotion motion;
    uint64_t frame = 0;  // the frame's number: a cut's (cutFrame), then one more each frame
  };
  // The step of a frame of `scene` at `time` whose clouds are marched at `view` (its size,
  // or half of it), with the weather map at `mapRevision`. It becomes the history once the
  // frame has run (commit()); a frame built but not run leaves the history as it was.
  // `cutFrame` numbers a cut (the frame's index in its sequence, RenderOptions::sequenceFrame):
  // the frames after it take their marched pixels and jitter by their numbers, so a shard
  // that starts inside a sequence marches as the whole run does from its cut on.
  Step step(const Scene& scene, const IsoTime& time, const shared::ViewState& view,
            uint64_t mapRevision, uint64_t cutFrame = 0);
  // Where the clouds lie for the reprojection.
  struct Shells {
    double planetRadiusM = 0.0, cameraAltitudeM = 0.0, shellBaseM = 0.0, shellTopM = 0.0;
  };
  // Adds the temporal pass: `marched` and `marchedDepth` (the cloud pass's sparse march for
  // `step`) merged with the history into this frame's clouds, the history's next images.
  CloudTemporalPass::Outputs addTo(FrameGraph& graph, const Step& step, ImageId marched,
                                   ImageId marchedDepth, const Shells& shells);
  // The frame of the last step() has run: it is the history now.
  void commit();
  // Forgets the history: the next frame is a cut (a frame of several views marched in full).
  void invalidate();

private:
  // The frame the history images hold.
  struct Held {
    uint64_t settings = 0;  // mSettings' number of the frame's scene
    shared::ViewState view{};
    double latDeg = 0.0, lonDeg = 0.0, altitudeM = 0.0;
    IsoTime time;
    uint64_t mapRevision = 0;
    uint64_t frame = 0;
  };
  const Context& mCtx;
  CloudTemporalPass mTemporal;
  Sampler mSampler;      // linear, clamp
  HistoryImage mClouds;  // RGBA32F: premultiplied radiance and opacity, the view's size
  HistoryImage mDepth;   // RG32F: transmittance-weighted distance (m) in r
  Held mHeld;            // the frame they hold
  SettingsRevisions mSettings;
  std::optional<Held> mNext;  // the last step's frame, until commit()
};

}  // namespace sky
