#include "passes/star_field/star_field.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "engine/core/error.h"
#include "engine/shader/shader_compiler.h"

namespace sky {
namespace {

// Every Vulkan device allows at least this many workgroups along x
// (maxComputeWorkGroupCount[0]); the splat loops over any stars beyond.
constexpr uint32_t kMaxGroups = 65535;

// The pass's pipeline from shaders/NAME.comp.
ComputePipeline buildPipeline(const Context& ctx, ShaderCompiler& compiler, const char* name) {
  return buildComputePipeline(ctx, compiler, std::string(name) + ".comp", name);
}

PersistentBuffer uploadStars(const Context& ctx, std::span<const Star> stars) {
  if (stars.empty()) internalError("star field: the star list is empty");
  std::vector<glm::vec4> packed;
  packed.reserve(stars.size());
  // Flux relative to a V = 0 star: Pogson's ratio, m = -2.5 log10(F / F0).
  for (const Star& s : stars)
    packed.emplace_back(s.directionJ2000, static_cast<float>(std::pow(10.0, -0.4 * s.vmag)));
  // Host-visible and coherent: the single upload is a memcpy, and host writes before the
  // first submit are visible to the device without a barrier.
  PersistentBuffer buffer{
      Buffer(ctx, {"stars", packed.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                   BufferMemory::HostVisible}),
      {}};
  std::memcpy(buffer.buffer.mapped(), packed.data(), packed.size() * sizeof(glm::vec4));
  return buffer;
}

}  // namespace

VkDeviceSize starFluxBufferBytes(uint32_t width, uint32_t height) {
  return (STAR_FLUX_HEADER_UINTS + VkDeviceSize(width) * height) * sizeof(uint32_t);
}

bool starsVisible(double brightestVmag, double fluxPerVega, double pixelSolidAngleSr,
                  double skyLuminance) {
  constexpr double kBelowACode = 1e-3;
  const double radiance = fluxPerVega * std::pow(10.0, -0.4 * brightestVmag) / pixelSolidAngleSr;
  return !(radiance < kBelowACode * skyLuminance);
}

StarClearPass::StarClearPass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline(buildPipeline(ctx, compiler, kName)) {}

StarClearPass::Outputs StarClearPass::setup(GraphBuilder& b, const Inputs& in, Data& d) {
  if (in.width == 0 || in.height == 0) internalError("star_clear: empty image size");
  d.inputs = in;
  BufferDesc desc;
  desc.name = "star_flux";
  // Viewable as an image: the flux each pixel gathered, in V = 0 units (a star of magnitude
  // 0 gives 1), after the header.
  desc.image.width = in.width;
  desc.image.height = in.height;
  desc.image.offset = STAR_FLUX_HEADER_UINTS * sizeof(uint32_t);
  desc.image.scale = static_cast<float>(1.0 / STAR_FLUX_FIXED_ONE);
  desc.image.about = "the stars' flux gathered per pixel, in V = 0 units (10^(-0.4 V) a star)";
  desc.size = starFluxBufferBytes(in.width, in.height);
  d.outputs.flux = b.write(b.create(desc), Access::StorageWriteCompute);
  return d.outputs;
}

void StarClearPass::execute(PassContext& ctx, const Data& d) const {
  shared::StarClearParams push{};
  push.size = glm::uvec4(d.inputs.width, d.inputs.height, 0, 0);
  ctx.dispatch(mPipeline, {Binding::of(STAR_CLEAR_BINDING_FLUX, d.outputs.flux)},
               mPipeline.groupsX(d.inputs.width), mPipeline.groupsY(d.inputs.height), 1, &push,
               sizeof push);
}

StarFieldPass::StarFieldPass(const Context& ctx, ShaderCompiler& compiler,
                             std::span<const Star> stars)
    : mClear(ctx, compiler),
      mPipeline(buildPipeline(ctx, compiler, kName)),
      mStars(uploadStars(ctx, stars)),
      mStarCount(static_cast<uint32_t>(stars.size())) {
  mBrightestVmag = std::min_element(stars.begin(), stars.end(), [](const Star& a, const Star& b) {
                     return a.vmag < b.vmag;
                   })->vmag;
}

std::optional<StarFieldPass::Outputs> StarFieldPass::addTo(FrameGraph& graph, const Frame& frame,
                                                           bool visible) {
  if (!visible) return std::nullopt;
  Inputs in;
  in.stars = graph.importBuffer(mStars);
  in.flux = graph.add(mClear, {frame.view.size.x, frame.view.size.y}).flux;
  in.frame = frame;
  return graph.add(*this, in);
}

StarFieldPass::Outputs StarFieldPass::setup(GraphBuilder& b, const Inputs& in, Data& d) {
  d.inputs = in;
  const Frame& f = in.frame;
  d.params = {};
  d.params.view = f.view;
  d.params.j2000ToEnu0 = glm::vec4(f.j2000ToEnu[0], 0.0f);
  d.params.j2000ToEnu1 = glm::vec4(f.j2000ToEnu[1], 0.0f);
  d.params.j2000ToEnu2 = glm::vec4(f.j2000ToEnu[2], 0.0f);
  d.params.extinction = glm::vec4(f.extinction, 0.0f, 0.0f, 0.0f);
  d.params.counts = glm::uvec4(mStarCount, 0, 0, 0);
  d.inputs.stars = b.read(in.stars, Access::StorageReadCompute);
  // Read-write: the atomics add to what star_clear wrote.
  d.outputs.flux = b.write(in.flux, Access::StorageReadWriteCompute);
  return d.outputs;
}

void StarFieldPass::execute(PassContext& ctx, const Data& d) const {
  const uint32_t groups = std::min(mPipeline.groupsX(mStarCount), kMaxGroups);
  ctx.dispatch(mPipeline,
               {Binding::of(STAR_FIELD_BINDING_PARAMS, ctx.uniform(d.params)),
                Binding::of(STAR_FIELD_BINDING_STARS, d.inputs.stars),
                Binding::of(STAR_FIELD_BINDING_FLUX, d.inputs.flux)},
               groups, 1);
}

}  // namespace sky
