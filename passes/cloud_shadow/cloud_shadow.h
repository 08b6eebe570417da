#pragma once
// The cloud shadow map (shaders/cloud_shadow.comp): the transmittance of the volumetric
// clouds toward the key light from every point of a square of ground around the camera, so
// the composite's ground lies in the shadows of the clouds above it. It marches the cloud
// pass's own density field with the same parameters and textures.
#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "passes/cloud_field/cloud_field.h"
#include "shaders/common/cloud_shadow_shared.h"

namespace sky {

class Context;
class ShaderCompiler;

// The map for a frame: the key light of the cloud parameters (their keyDirection) and a
// square reaching past the ground horizon seen from `cameraAltitudeM` (m above sea level).
shared::CloudShadowMap cloudShadowMap(const shared::CloudParams& params, double cameraAltitudeM);

// The map is persistent: a frame whose clouds, light and camera are those it was made for
// (CloudFieldKey) reads it again, shifted by the wind's drift since, instead of marching it:
// a sequence pays for it when the sun or the clouds have moved on, not every frame.
class CloudShadowPass {
public:
  static constexpr const char* kName = "cloud_shadow";
  struct Inputs {
    shared::CloudParams params{};  // the volumetric clouds' parameters (cloudParams)
    CloudVariant variant;
    shared::CloudShadowMap map{};  // cloudShadowMap
    CloudTextures textures;
    CloudFieldKey key;  // what the map is made from
  };
  struct Outputs {
    ImageId shadow;                // R16F CLOUD_SHADOW_SIZE^2: transmittance toward the light
    shared::CloudShadowMap map{};  // where it lies, with the drift to read it by
  };

  CloudShadowPass(const Context& ctx, ShaderCompiler& compiler);
  // Imports the map, adding the pass that makes it unless the last one serves (see above).
  // This object must outlive graph.execute().
  Outputs addTo(FrameGraph& graph, const Inputs& inputs);
  // Forgets the map (a frame that failed may not have made it).
  void invalidate() { mKept.invalidate(); }
  // One use's data, in the frame graph.
  struct Data {
    const ComputePipeline* pipeline = nullptr;  // this use's variant, chosen in setup()
    Inputs inputs{};
    Outputs outputs;
    ImageId target;  // the imported map, written
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  CloudPipelines mPipelines;
  PersistentImage mShadow;
  KeptCloudProduct mKept;         // what the map in memory was made from
  shared::CloudShadowMap mMap{};  // where it lies
};

}  // namespace sky
