#include "passes/cloud_shadow/cloud_shadow.h"

#include <memory>

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
  auto data = std::make_shared<Data>();
  data->target = shadow;
  GraphBuilder b = graph.addPass(kName, [this, data](PassContext& ctx) { execute(ctx, *data); });
  const Outputs out = setup(b, in, *data);
  mMap = out.map;
  return out;
}

CloudShadowPass::Outputs CloudShadowPass::setup(GraphBuilder& b, const Inputs& in, Data& d) {
  d.inputs = in;
  d.inputs.map.shiftEastM = d.inputs.map.shiftNorthM = 0.0f;
  d.pipeline = &mPipelines.get(in.variant);
  readCloudTextures(b, in.textures);
  d.outputs.shadow = d.target = b.write(d.target, Access::StorageWriteCompute);
  d.outputs.map = d.inputs.map;
  b.sideEffect();  // later frames may read it
  return d.outputs;
}

void CloudShadowPass::execute(PassContext& ctx, const Data& d) const {
  std::vector<Binding> bindings = cloudTextureBindings(d.inputs.textures);
  bindings.insert(bindings.end(),
                  {Binding::of(VOLUMETRIC_CLOUDS_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
                   Binding::of(CLOUD_SHADOW_BINDING_MAP_PARAMS, ctx.uniform(d.inputs.map)),
                   Binding::of(CLOUD_SHADOW_BINDING_IMAGE, d.outputs.shadow)});
  ctx.dispatch(*d.pipeline, bindings, d.pipeline->groupsX(CLOUD_SHADOW_SIZE),
               d.pipeline->groupsY(CLOUD_SHADOW_SIZE));
}

}  // namespace sky
