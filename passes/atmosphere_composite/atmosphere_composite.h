#pragma once
// The atmosphere composite: the final scene-linear image. The clear sky and high clouds of
// passes/sky_high_clouds, the star field, and the sun and moon discs from the frame's
// LightingState, seen through the high clouds and the volumetric clouds.
#include <optional>

#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "shaders/common/atmosphere_composite_shared.h"
#include "shaders/common/lighting_shared.h"

namespace sky {

class Context;
class ShaderCompiler;

class AtmosphereCompositePass {
public:
  static constexpr const char* kName = "atmosphere_composite";
  struct Inputs {
    shared::AtmosphereCompositeParams params;  // the view; layers.y: camera above high clouds
    shared::LightingState lighting;            // this frame's lights and palette
    BufferId starFlux;                         // from StarFieldPass
    ImageId sky;                               // from SkyHighCloudsPass
    ImageId highClouds;                        // from SkyHighCloudsPass
    std::optional<ImageId> clouds;             // from VolumetricCloudsPass (none: clear)
  };
  struct Outputs {
    ImageId beauty;  // RGBA16F scene-linear, alpha 1
  };

  // Compiles the shader and builds the pipeline (once, at renderer start-up).
  AtmosphereCompositePass(const Context& ctx, ShaderCompiler& compiler);
  Outputs setup(GraphBuilder& builder, const Inputs& inputs);
  void execute(PassContext& ctx) const;

private:
  ComputePipeline mPipeline;
  Inputs mInputs{};
  Outputs mOutputs;
};

}  // namespace sky
