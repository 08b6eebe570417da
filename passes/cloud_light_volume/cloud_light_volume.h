#pragma once
// The cloud light volume (shaders/cloud_light_volume.comp; docs/clouds.md, "Light volume"):
// the optical depth toward the sun and the moon over the cloud shells around the camera,
// marched once with the reference's refined schedule and read by every view sample of the
// raymarch, which marches only the nearest steps itself (clouds.light volume). The volume is
// persistent: a frame whose lights, clouds and camera are those it was made for reuses it,
// following the wind's drift by a shift, and makes it again only when they have moved on.
#include "engine/gpu/sampler.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "passes/cloud_field/cloud_field.h"
#include "shaders/common/cloud_light_volume_shared.h"

namespace sky {

class Context;
class ShaderCompiler;

// The volume's place for the clouds of `params`, seen from `cameraAltitudeM`: around the
// point below the camera out to where the shells' top meets the horizon, over the marched
// shells, the view samples' own part of the march ending at startM. Shift 0.
shared::CloudLightVolume cloudLightVolumePlace(const shared::CloudParams& params,
                                               double cameraAltitudeM);

class CloudLightVolumePass {
public:
  static constexpr const char* kName = "cloud_light_volume";
  struct Inputs {
    shared::CloudParams params{};  // with lightVolume's place (cloudLightVolumePlace)
    CloudVariant variant;          // the raymarch's
    CloudTextures textures;
    CloudFieldKey key;
  };
  struct Outputs {
    ImageId volume;                  // RG16F, CLOUD_LIGHT_VOLUME_SIZE^2 x CLOUD_LIGHT_VOLUME_SLICES
    shared::CloudLightVolume place;  // where it lies, with the shift to read it by
    bool made = false;               // made this frame (false: reused)
  };

  CloudLightVolumePass(const Context& ctx, ShaderCompiler& compiler);
  // Imports the volume into `graph`, adding the pass that makes it when the key says so.
  // This object must outlive graph.execute().
  Outputs addTo(FrameGraph& graph, const Inputs& inputs);
  // Forgets the volume, so the next frame makes it (a failed frame may not have).
  void invalidate() { mKept.invalidate(); }
  // The pieces addTo() uses.
  // One use's data, in the frame graph.
  struct Data {
    const ComputePipeline* pipeline = nullptr;  // this use's variant, chosen in setup()
    Inputs inputs{};
    ImageId target;  // the imported volume, written
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;
  const Sampler& sampler() const { return mSampler; }

private:
  CloudPipelines mPipelines;
  const Context& mCtx;
  Sampler mSampler;  // linear, clamp
  PersistentImage mVolume;
  KeptCloudProduct mKept;  // what the volume in memory was made from
  shared::CloudLightVolume mPlace{};
};

}  // namespace sky
