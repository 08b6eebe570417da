#pragma once
// The atmosphere composite: the final scene-linear image. The Kozlov 3.1 clear sky lit by
// sun and moon, the star field, and the sun and moon discs, all from the frame's
// LightingState; later issues add high clouds, volumetric clouds and aerial perspective.
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
    shared::AtmosphereCompositeParams params;  // the view
    shared::LightingState lighting;            // this frame's lights and palette
    BufferId starFlux;                         // from StarFieldPass
  };
  struct Outputs {
    ImageId beauty;  // RGBA16F scene-linear, alpha 1
    ImageId sky;     // the clear sky alone (no sun disc), an AOV
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
