#include "passes/cloud_temporal/cloud_temporal.h"

#include "engine/core/error.h"
#include "engine/gpu/sampler.h"
#include "engine/shader/shader_compiler.h"

namespace sky {
namespace {

// Bayer's ordered-dither matrices: entry (x, y) is the frame (mod block^2) that marches pixel
// (x, y) of its square, so each frame's pixels lie as far from the last frame's as they can.
constexpr uint32_t kBayer2[2][2] = {{0, 2}, {3, 1}};
constexpr uint32_t kBayer4[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
// For 3: a knight's-move order (each frame's pixel a knight's move from the last).
constexpr uint32_t kOrder3[3][3] = {{0, 5, 7}, {4, 6, 2}, {8, 1, 3}};

}  // namespace

glm::uvec2 cloudMarchOffset(uint32_t block, uint64_t frame) {
  if (block <= 1) return {0, 0};
  if (block > 4) internalError("cloud march block " + std::to_string(block) + " is over 4");
  const uint32_t k = static_cast<uint32_t>(frame % (block * block));
  for (uint32_t y = 0; y < block; ++y)
    for (uint32_t x = 0; x < block; ++x) {
      const uint32_t at = block == 2 ? kBayer2[y][x] : block == 3 ? kOrder3[y][x] : kBayer4[y][x];
      if (at == k) return {x, y};
    }
  internalError("cloud march order has no entry " + std::to_string(k));
}

shared::CloudTemporalParams cloudTemporalParams(const shared::ViewState& view,
                                                const shared::ViewState& previousView,
                                                const CloudTemporalMotion& motion, uint32_t block,
                                                glm::uvec2 offset, bool historyValid,
                                                double planetRadiusM, double cameraAltitudeM,
                                                double shellBaseM, double shellTopM) {
  shared::CloudTemporalParams p{};
  p.view = view;
  p.previousView = previousView;
  p.previousPosition = glm::vec4(motion.previousPosition, 0.0f);
  // glm is column-major: row r of the matrix is (m[0][r], m[1][r], m[2][r]).
  const glm::mat3& m = motion.toPrevious;
  p.toPreviousX = glm::vec4(m[0][0], m[1][0], m[2][0], 0.0f);
  p.toPreviousY = glm::vec4(m[0][1], m[1][1], m[2][1], 0.0f);
  p.toPreviousZ = glm::vec4(m[0][2], m[1][2], m[2][2], 0.0f);
  p.windShift = glm::vec4(motion.windShift, 0.0f);
  p.block = block;
  p.offsetX = offset.x;
  p.offsetY = offset.y;
  p.historyValid = historyValid ? 1u : 0u;
  p.planetRadiusM = static_cast<float>(planetRadiusM);
  p.cameraAltitudeM = static_cast<float>(cameraAltitudeM);
  p.shellBaseM = static_cast<float>(shellBaseM);
  p.shellTopM = static_cast<float>(shellTopM);
  return p;
}

CloudTemporalPass::CloudTemporalPass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline(buildComputePipeline(ctx, compiler, "cloud_temporal.comp", kName)) {}

CloudTemporalPass::Outputs CloudTemporalPass::setup(GraphBuilder& b, const Inputs& in, Data& d) {
  if (!in.historySampler) internalError("cloud_temporal: no history sampler");
  d.inputs = in;
  b.read(in.marched, Access::StorageReadCompute);
  b.read(in.marchedDepth, Access::StorageReadCompute);
  // Read even after a cut (the shader then ignores them), so the bindings never change.
  b.read(in.clouds.previous, Access::SampledCompute);
  b.read(in.depth.previous, Access::StorageReadCompute);
  d.outputs.clouds = b.write(in.clouds.next, Access::StorageWriteCompute);
  d.outputs.depth = b.write(in.depth.next, Access::StorageWriteCompute);
  b.sideEffect();  // the next frame reads what this one writes
  return d.outputs;
}

void CloudTemporalPass::execute(PassContext& ctx, const Data& d) const {
  const auto& size = d.inputs.params.view.size;
  std::vector<Binding> bindings = {
      Binding::of(CLOUD_TEMPORAL_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
      Binding::of(CLOUD_TEMPORAL_BINDING_MARCHED, d.inputs.marched),
      Binding::of(CLOUD_TEMPORAL_BINDING_MARCHED_DEPTH, d.inputs.marchedDepth),
      Binding::of(CLOUD_TEMPORAL_BINDING_HISTORY, d.inputs.clouds.previous,
                  d.inputs.historySampler),
      Binding::of(CLOUD_TEMPORAL_BINDING_HISTORY_DEPTH, d.inputs.depth.previous),
      Binding::of(CLOUD_TEMPORAL_BINDING_CLOUDS, d.outputs.clouds),
      Binding::of(CLOUD_TEMPORAL_BINDING_DEPTH, d.outputs.depth)};
  ctx.dispatch(mPipeline, bindings, mPipeline.groupsX(size.x), mPipeline.groupsY(size.y));
}

}  // namespace sky
