#pragma once
// The atmosphere composite: the final scene-linear image. The clear sky and high clouds of
// passes/sky_high_clouds, the star field, the sun and moon discs from the frame's
// LightingState, the lit ground in the clouds' shadows (passes/cloud_shadow), and the
// volumetric clouds, the ground and the clouds seen through the aerial perspective.
#include <optional>
#include <utility>
#include <vector>

#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "engine/lighting/lighting_state.h"
#include "engine/scene/scene.h"
#include "engine/shader/shader_compiler.h"
#include "shaders/common/atmosphere_composite_shared.h"
#include "shaders/common/atmosphere_shared.h"
#include "shaders/common/lighting_shared.h"

namespace sky {

class Context;
class Sampler;
class ShaderCompiler;

// What the composite takes from the scene (built by engine/render, not the whole Scene).
struct AtmosphereCompositeSettings {
  GroundSettings ground;
  double planetRadiusM = 0.0;    // the sky model's planet (kozlov: the geographic Earth)
  double cameraAltitudeM = 0.0;  // above sea level
  double turbidity = 0.15;       // lighting.turbidity: the kozlov haze (light::hazeMedium)
  bool observer = true;          // false for a top-down render: no ground, no aerial perspective
  bool aboveHighClouds = false;  // the camera flies above the high-cloud layer
  bool belowClouds = true;       // the camera is below the volumetric clouds' lowest base
  double highCloudsAltitudeM = 0.0;  // the high-cloud layer (the perception layers' air)
};

// The pass's uniforms for one frame (the shadow map's part stays invalid until
// AtmosphereCompositePass::Inputs::clouds sets it).
shared::AtmosphereCompositeParams atmosphereCompositeParams(
    const AtmosphereCompositeSettings& settings, const LightingState& lighting,
    const shared::ViewState& view);

// Whether a disc of angular radius `radius` (radians) centred on unit `direction` covers any
// part of a pixel of `view` by the composite's discCoverage: false only when no pixel can get
// a share, so leaving the disc out changes nothing.
bool discReachesView(const shared::ViewState& view, const glm::vec3& direction, float radius);

// A band of whole rows of the composite's workgroups, drawn by one dispatch, and what its
// rows can see: the ground below the horizon, the volumetric clouds (their aerial
// perspective). The variant for the band compiles out what it cannot see.
struct CompositeBand {
  uint32_t firstRow = 0, rows = 0;
  bool ground = true, cloudAir = true;
  bool operator==(const CompositeBand&) const = default;
};

// The bands of the image of `params` (its view, planet and camera), in order from the top,
// neighbours with the same needs merged. A band sees the ground where some pixel of it looks
// within a few pixels of the horizon or below it; the clouds' air where some pixel looks
// within a few pixels below the horizon or above it, or everywhere when `cloudsAboveHorizon`
// is false (the camera at or above the clouds' lowest base, or no ground to hide them).
// `bandRows` is the workgroup's height.
std::vector<CompositeBand> compositeBands(const shared::AtmosphereCompositeParams& params,
                                          bool clouds, bool cloudsAboveHorizon, uint32_t bandRows);

// The variant of atmosphere_composite.comp one band draws with: what the frame and the band
// show, each compiled in or out (a software rasteriser runs both sides of a branch, so what a
// frame cannot see is left out, not branched around). The image is the same either way.
enum class CompositeSky { Kozlov, Physical };           // sky.model: whose air and ground
enum class HostColourFormat { Rgba16f, Rgba32f };        // the host's colour image, if any
struct CompositeVariant {
  CompositeSky sky = CompositeSky::Kozlov;
  bool clouds = false;      // the volumetric clouds
  bool stars = false;       // the star passes ran this frame
  bool sunDisc = false;     // the sun's disc can reach a pixel of the view (discReachesView)
  bool moonDisc = false;    // the moon's likewise
  bool ground = true;       // the band sees the ground (CompositeBand::ground)
  bool cloudAir = true;     // the band sees the clouds' aerial perspective (CompositeBand)
  bool host = false;        // drawing into a host's colour image
  bool hostDepth = false;   // ... with its depth
  HostColourFormat hostFormat = HostColourFormat::Rgba16f;
  bool perception = false;  // the perception layers

  bool operator==(const CompositeVariant&) const = default;
};
// The GLSL defines that compile `v`.
std::vector<ShaderDefine> compositeVariantDefines(const CompositeVariant& v);

class AtmosphereCompositePass {
public:
  static constexpr const char* kName = "atmosphere_composite";
  // The volumetric clouds and their shadow map.
  struct Clouds {
    ImageId clouds;                          // from VolumetricCloudsPass
    ImageId depth;                           // from VolumetricCloudsPass
    ImageId shadow;                          // from CloudShadowPass
    shared::CloudShadowMap shadowMap{};      // how the shadow map lies on the ground
    const Sampler* shadowSampler = nullptr;  // linear, clamp to edge
    // The camera is below the clouds' lowest base: no ray below the horizon reaches them.
    bool belowBase = false;
  };
  // sky.model physical: the atmosphere's LUTs (passes/atmosphere_luts).
  struct Atmosphere {
    shared::AtmosphereParams params{};
    ImageId transmittance, aerialPerspective;
    const Sampler* sampler = nullptr;
  };
  // Drawing into the host's own images (skylayers::Sky::record): the sky behind the host's
  // geometry, the volumetric clouds over it, and the host's pixels seen through the aerial
  // perspective by their depth. The clouds must have been marched to the same depth
  // (VolumetricCloudsPass::Inputs::hostDepth): all of them then lie in front.
  struct Host {
    ImageId colour;                // the host's scene-linear colour: read and written
    std::optional<ImageId> depth;  // the host's depth; none: the sky everywhere
    VkFormat colourFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // rgba16f or rgba32f
    shared::HostDepth depthMapping{};                       // present is set by setup
    const Sampler* depthSampler = nullptr;                  // nearest, clamp to edge
  };
  // The perception layers (docs/outputs.md): what each pixel's centre ray meets first.
  struct Perception {
    // From CloudPerceptionPass, with Inputs::clouds (none: no volumetric clouds).
    std::optional<ImageId> cloudHit;
  };
  struct Inputs {
    shared::AtmosphereCompositeParams params;  // atmosphereCompositeParams
    shared::LightingState lighting;            // this frame's lights and palette
    std::optional<BufferId> starFlux;          // from StarFieldPass; none: no stars this frame
    ImageId sky;                               // from SkyHighCloudsPass
    ImageId highClouds;                        // from SkyHighCloudsPass
    std::optional<Clouds> clouds;              // none: no volumetric clouds
    std::optional<Atmosphere> atmosphere;      // none: sky.model kozlov
    std::optional<Host> host;                  // none: the frame is the beauty alone
    std::optional<Perception> perception;      // none: no perception layers
  };
  struct Outputs {
    ImageId beauty;  // RGBA32F scene-linear, alpha 1
    ImageId host;    // with Inputs::host: the host's colour, drawn into
    // With Inputs::perception, RGBA32F: r label, g cloud type (cloud_perception_shared.h's
    // numbers), b the air's transmittance to what the ray meets, a the ground's cloud shadow.
    ImageId perception;
  };

  // The shader's variants (CompositeVariant) are compiled on first use: setup picks those this
  // frame's bands need.
  AtmosphereCompositePass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add): once per view.
  struct Data {
    // This view's bands, each with its variant.
    std::vector<std::pair<CompositeBand, const ComputePipeline*>> bands;
    Inputs inputs{};
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  ComputePipelineVariants mVariants;
};

}  // namespace sky
