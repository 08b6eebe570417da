#pragma once
// The cloud density field sampled on a voxel grid (skyrender export-volume, the path-traced
// reference of scripts/pathtrace): shaders/cloud_volume_export.comp evaluates the raymarch's
// own density function (cloud_field.glsl) at every voxel centre of a box in the camera's ENU
// frame, with the frame's CloudParams and textures, into an R32F 3D image.
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "passes/cloud_field/cloud_field.h"
#include "shaders/common/cloud_volume_export_shared.h"

namespace sky {

class CloudVolumeExportPass {
public:
  static constexpr const char* kName = "cloud_volume_export";
  struct Inputs {
    shared::CloudParams params{};  // cloudParams() of the frame, as the raymarch gets them
    CloudVariant variant;
    shared::CloudVolumeExportParams box{};
    CloudTextures textures;
  };
  struct Outputs {
    ImageId grid;  // R32F, box.voxels: density (extinction / clouds.extinction) per voxel
  };

  CloudVolumeExportPass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    const ComputePipeline* pipeline = nullptr;  // this use's variant, chosen in setup()
    Inputs inputs{};
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  CloudPipelines mPipelines;  // the same shader variants as the raymarch's
};

}  // namespace sky
