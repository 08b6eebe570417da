#pragma once
// The density-slice debug view (shaders/cloud_density_slice.comp): a vertical cut through the
// volumetric clouds' density field along the camera's heading, from the camera out to 60 km
// and from sea level to above the highest layer, with the cover, type and layer beside the
// density. It reads the cloud pass's own parameters and textures (cloud_field.glsl), so it
// shows exactly the field the raymarch marches. docs/clouds.md, "Outputs".
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "passes/cloud_field/cloud_field.h"

namespace sky {

class CloudDensitySlicePass {
public:
  static constexpr const char* kName = "cloud_density_slice";
  static constexpr uint32_t kWidth = 512, kHeight = 128;
  struct Inputs {
    shared::CloudParams params{};  // sliceLengthM: length ahead (m); sliceTopM: top altitude (m)
    CloudVariant variant;
    CloudTextures textures;
  };
  struct Outputs {
    ImageId slice;  // RGBA16F kWidth x kHeight: r density, g cover, b type, a layer (0/1, -1)
  };

  CloudDensitySlicePass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    Inputs inputs{};
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  // Every frame with clouds adds this pass for the debug view, and nearly every frame culls
  // it: its variant is compiled when it first runs, in execute(), not in setup().
  mutable CloudPipelines mPipelines;
};

}  // namespace sky
