#pragma once
// Temporal reuse of the volumetric clouds (shaders/cloud_temporal.comp; docs/clouds.md,
// "Temporal reuse"): merges the cloud pass's sparse march of this frame with last frame's
// clouds, reprojected through the camera's motion and the wind, into this frame's full-size
// clouds and depth. Those are the HistoryImages' `next` images: the next frame reads them.
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "shaders/common/cloud_temporal_shared.h"

namespace sky {

class Context;
class Sampler;
class ShaderCompiler;

// Which pixel of each block x block square frame `frame` of a history marches: every pixel
// once in block^2 frames, in an order that spreads consecutive frames' pixels apart (Bayer's
// ordered-dither matrix for 2 and 4).
glm::uvec2 cloudMarchOffset(uint32_t block, uint64_t frame);

// Where the camera of the frame before stood and how it was turned, in this frame's terms.
struct CloudTemporalMotion {
  glm::vec3 previousPosition{0.0f};  // last frame's camera in this frame's ENU frame (m)
  glm::mat3 toPrevious{1.0f};        // this frame's ENU axes to last frame's
  glm::vec3 windShift{0.0f};         // the clouds' drift since last frame, this frame's ENU (m)
};

class CloudTemporalPass {
public:
  static constexpr const char* kName = "cloud_temporal";
  struct Inputs {
    shared::CloudTemporalParams params{};
    ImageId marched;       // the cloud pass's clouds, the view's size / block
    ImageId marchedDepth;  // and depth
    HistoryIds clouds;     // RGBA32F, the view's size
    HistoryIds depth;      // RG32F, the view's size: depth (m), where the ray reaches the shells
    const Sampler* historySampler = nullptr;  // linear, clamp
  };
  struct Outputs {
    ImageId clouds;  // this frame's clouds: rgb premultiplied radiance, a opacity (= clouds.next)
    ImageId depth;   // this frame's transmittance-weighted depth, m (= depth.next)
  };

  CloudTemporalPass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    Inputs inputs{};
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  ComputePipeline mPipeline;
};

// The pass's parameters: this frame's and last frame's views, the motion between them, the
// march's block and this frame's offset, whether the history holds anything, and the sphere
// and shells its depth-aware upsampling measures rays against.
shared::CloudTemporalParams cloudTemporalParams(const shared::ViewState& view,
                                                const shared::ViewState& previousView,
                                                const CloudTemporalMotion& motion, uint32_t block,
                                                glm::uvec2 offset, bool historyValid,
                                                double planetRadiusM, double cameraAltitudeM,
                                                double shellBaseM, double shellTopM);

}  // namespace sky
