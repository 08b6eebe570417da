#include "passes/cloud_light_volume/cloud_light_volume.h"

#include <memory>

#include <algorithm>
#include <cmath>

#include "engine/clouds/cloud_math.h"
#include "engine/core/error.h"
#include "engine/gpu/context.h"
#include "engine/gpu/sampler.h"

namespace sky {
namespace {

// A reused volume follows the clouds' drift by a shift; beyond this the cover they drift
// through (which stays put) has changed under them, and the volume is made again.
constexpr double kMaxShiftM = 200.0;
// Past where the shells' top meets the horizon, and never under or over these.
constexpr double kHorizonMarginM = 10000.0;
constexpr double kMinRadiusM = 40000.0;
constexpr double kMaxRadiusM = 400000.0;

PersistentImage makeVolume(const Context& ctx) {
  ImageDesc d;
  d.name = "cloud_light_volume";
  d.about = "light through the clouds toward the sun (R) and the moon (G), slices up the shells";
  d.view = DebugView::Scalar;
  d.channels = "sun,moon";
  d.dim = ImageDim::Tex3D;
  d.format = VK_FORMAT_R16G16_SFLOAT;
  d.width = d.height = CLOUD_LIGHT_VOLUME_SIZE;
  d.depth = CLOUD_LIGHT_VOLUME_SLICES;
  d.usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  return PersistentImage{Image(ctx, d), {}};
}

}  // namespace

shared::CloudLightVolume cloudLightVolumePlace(const shared::CloudParams& params,
                                               double cameraAltitudeM) {
  const double R = params.geo.origin.w;
  // Ground distance to where a ray grazing the horizon from the camera reaches the top.
  const double reach = std::sqrt(2.0 * R * std::max<double>(params.shellTopM, 1.0)) +
                       std::sqrt(2.0 * R * std::max(cameraAltitudeM, 1.0));
  shared::CloudLightVolume v{};
  v.radiusM = static_cast<float>(std::clamp(reach + kHorizonMarginM, kMinRadiusM, kMaxRadiusM));
  v.baseM = params.shellBaseM;
  v.topM = params.shellTopM;
  v.startM = clouds::lightStepStart(CLOUD_LIGHT_VOLUME_NEAR, static_cast<int>(params.lightSteps),
                                    params.lightDistanceM);
  return v;
}

CloudLightVolumePass::CloudLightVolumePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipelines(ctx, compiler, "cloud_light_volume.comp", kName),
      mCtx(ctx),
      mSampler(ctx, SamplerWrap::Clamp),
      mKept(kMaxShiftM) {}

CloudLightVolumePass::Outputs CloudLightVolumePass::addTo(FrameGraph& graph, const Inputs& in) {
  Outputs out;
  if (!mVolume.image) mVolume = makeVolume(mCtx);  // 8 MB, only for scenes that use it
  const ImageId volume = graph.importImage(mVolume);
  if (!mKept.needsMaking(in.key)) {
    out.volume = volume;
    out.place = mPlace;
    // The clouds drifted on since: read the volume where they were.
    const glm::dvec2 shift = mKept.shift(in.key);
    out.place.shiftEastM = static_cast<float>(shift.x);
    out.place.shiftNorthM = static_cast<float>(shift.y);
    return out;
  }
  auto data = std::make_shared<Data>();
  data->target = volume;
  GraphBuilder b = graph.addPass(kName, [this, data](PassContext& ctx) { execute(ctx, *data); });
  out = setup(b, in, *data);
  mPlace = in.params.lightVolume;
  mPlace.shiftEastM = mPlace.shiftNorthM = 0.0f;
  return out;
}

CloudLightVolumePass::Outputs CloudLightVolumePass::setup(GraphBuilder& b, const Inputs& in,
                                                          Data& d) {
  d.inputs = in;
  d.inputs.params.lightVolume.shiftEastM = d.inputs.params.lightVolume.shiftNorthM = 0.0f;
  d.pipeline = &mPipelines.get(in.variant);
  readCloudTextures(b, in.textures);
  Outputs out;
  out.volume = d.target = b.write(d.target, Access::StorageWriteCompute);
  out.place = d.inputs.params.lightVolume;
  out.made = true;
  b.sideEffect();  // later frames read it
  return out;
}

void CloudLightVolumePass::execute(PassContext& ctx, const Data& d) const {
  std::vector<Binding> bindings = cloudTextureBindings(d.inputs.textures);
  bindings.insert(bindings.end(),
                  {Binding::of(VOLUMETRIC_CLOUDS_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
                   Binding::of(CLOUD_LIGHT_VOLUME_BINDING_IMAGE, d.target)});
  ctx.dispatch(*d.pipeline, bindings, d.pipeline->groupsX(CLOUD_LIGHT_VOLUME_SIZE),
               d.pipeline->groupsY(CLOUD_LIGHT_VOLUME_SIZE),
               d.pipeline->groupsZ(CLOUD_LIGHT_VOLUME_SLICES));
}

}  // namespace sky
