#include "passes/cloud_shadow/cloud_shadow.h"

#include <algorithm>
#include <cmath>

#include "engine/gpu/context.h"

namespace sky {
namespace {

// The map reaches this far past the ground horizon, and at least kMinRadiusM: the ground near
// the horizon is seen at a grazing angle through a lot of haze, so it only needs to be there.
constexpr double kHorizonMarginM = 10000.0;
constexpr double kMinRadiusM = 40000.0;
constexpr double kMaxRadiusM = 400000.0;
// The light's path through the shells is cut after this distance: with the sun 5 degrees up it
// crosses a 2 km layer in 23 km.
constexpr double kMaxPathM = 60000.0;
// A kept map follows the clouds' drift this far before it is marched again (the cover the
// noise drifts through stays put).
constexpr double kMaxShiftM = 200.0;

PersistentImage makeShadowImage(const Context& ctx) {
  ImageDesc desc;
  desc.width = CLOUD_SHADOW_SIZE;
  desc.height = CLOUD_SHADOW_SIZE;
  desc.format = VK_FORMAT_R16_SFLOAT;
  desc.name = "cloud_shadow";
  desc.about =
      "transmittance toward the key light from the ground, around the point below the camera "
      "(east right, north up; ground distance r u|u| from the centre, r in the report's "
      "cloud_shadow.radius_m)";
  desc.view = DebugView::Scalar;
  desc.channels = "transmittance";
  desc.usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  return PersistentImage{Image(ctx, desc), {}};
}

}  // namespace

shared::CloudShadowMap cloudShadowMap(const shared::CloudParams& params, double cameraAltitudeM) {
  const double R = params.geo.origin.w, h = std::max(cameraAltitudeM, 1.0);
  // Ground distance to the horizon seen from height h: R acos(R / (R + h)).
  const double horizon = R * std::acos(R / (R + h));
  const CloudKeyLight key = cloudKeyLight(params);
  shared::CloudShadowMap map{};
  map.lightDirection = glm::vec4(key.direction, 0.0f);
  map.radiusM = static_cast<float>(std::clamp(horizon + kHorizonMarginM, kMinRadiusM, kMaxRadiusM));
  map.lightIsSun = key.isSun ? 1.0f : 0.0f;
  map.maxPathM = static_cast<float>(kMaxPathM);
  map.valid = 1.0f;
  return map;
}

CloudShadowPass::CloudShadowPass(const Context& ctx, ShaderCompiler& compiler)
    : mPipelines(ctx, compiler, "cloud_shadow.comp", kName),
      mShadow(makeShadowImage(ctx)),
      mKept(kMaxShiftM) {}

CloudShadowPass::Outputs CloudShadowPass::addTo(FrameGraph& graph, const Inputs& in) {
  const ImageId shadow = graph.importImage(mShadow);
  if (!mKept.needsMaking(in.key)) {
    Outputs out{shadow, mMap};
    const glm::dvec2 shift = mKept.shift(in.key);
    out.map.shiftEastM = static_cast<float>(shift.x);
    out.map.shiftNorthM = static_cast<float>(shift.y);
    return out;
  }
  mTarget = shadow;
  GraphBuilder b = graph.addPass(kName, [this](PassContext& ctx) { execute(ctx); });
  const Outputs out = setup(b, in);
  mMap = out.map;
  return out;
}

CloudShadowPass::Outputs CloudShadowPass::setup(GraphBuilder& b, const Inputs& in) {
  mInputs = in;
  mInputs.map.shiftEastM = mInputs.map.shiftNorthM = 0.0f;
  mPipeline = &mPipelines.get(in.variant);
  readCloudTextures(b, in.textures);
  mOutputs.shadow = mTarget = b.write(mTarget, Access::StorageWriteCompute);
  mOutputs.map = mInputs.map;
  b.sideEffect();  // later frames may read it
  return mOutputs;
}

void CloudShadowPass::execute(PassContext& ctx) const {
  std::vector<Binding> bindings = cloudTextureBindings(mInputs.textures);
  bindings.insert(bindings.end(),
                  {Binding::of(VOLUMETRIC_CLOUDS_BINDING_PARAMS, ctx.uniform(mInputs.params)),
                   Binding::of(CLOUD_SHADOW_BINDING_MAP_PARAMS, ctx.uniform(mInputs.map)),
                   Binding::of(CLOUD_SHADOW_BINDING_IMAGE, mOutputs.shadow)});
  ctx.dispatch(*mPipeline, bindings, mPipeline->groupsX(CLOUD_SHADOW_SIZE),
               mPipeline->groupsY(CLOUD_SHADOW_SIZE));
}

}  // namespace sky
