#pragma once
// The volumetric clouds' ambient light from the frame's own sky (shaders/cloud_ambient.comp):
// the clear sky of either model sampled over the upper hemisphere, its light on a surface of
// each orientation of a small table, and the ground below lit by the sun, the moon and that
// sky, into a small image the raymarch reads. So the clouds are lit by the sky the viewer sees,
// whatever the sky model, the hour or the turbidity, not by the palette's two constant colours.
#include <optional>

#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "engine/lighting/lighting_state.h"
#include "shaders/common/atmosphere_shared.h"
#include "shaders/common/cloud_ambient_shared.h"
#include "shaders/common/lighting_shared.h"

namespace sky {

class Context;
class Sampler;
class ShaderCompiler;

// What the pass takes from the scene: the ground's reflectance, the air between the clouds and
// the ground, the cover around the camera and the clouds' phase function.
struct CloudAmbientSettings {
  glm::vec3 groundAlbedo{0.1f};  // ground.albedo
  double turbidity = 0.15;       // lighting.turbidity: the haze below the clouds
  double cloudBaseM = 1500.0;    // the lowest marched cloud base (m above sea level)
  double overcast = 0.0;         // LightingState::overcast, the cover around the camera
  // The clouds' phase function (clouds.g and clouds.phase): dualLobeHG(g, gBack, backWeight),
  // backWeight 0 for Henyey-Greenstein.
  double phaseG = 0.6;
  double phaseGBack = -0.3;
  double phaseBackWeight = 0.2;
};

// The pass's uniforms for `settings`.
shared::CloudAmbientParams cloudAmbientParams(const CloudAmbientSettings& settings);

class CloudAmbientPass {
public:
  static constexpr const char* kName = "cloud_ambient";
  struct Atmosphere {  // passes/atmosphere_luts; sky.model physical only
    shared::AtmosphereParams params{};
    ImageId transmittance, skyViewSun, skyViewMoon;
    const Sampler* sampler = nullptr;  // linear, clamp
  };
  struct Inputs {
    shared::CloudAmbientParams params{};
    shared::LightingState lighting{};
    bool moon = false;                     // the moon's light is not negligible (its LUT bound)
    std::optional<Atmosphere> atmosphere;  // sky.model physical
  };
  struct Outputs {
    ImageId ambient;  // RGBA32F, the table of cloud_ambient_shared.h
  };

  CloudAmbientPass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    const ComputePipeline* pipeline = nullptr;  // this use's variant, chosen in setup()
    Inputs inputs{};
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  ComputePipelineVariants mVariants;
};

}  // namespace sky
