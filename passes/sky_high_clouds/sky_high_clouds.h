#pragma once
// The sky and high-cloud layer (Kozlov et al. §3): the clear sky (Kozlov 3.1 or, with
// sky.model physical, Hillaire's sky-view LUTs) and the high clouds from a coefficient texture
// and normal map mapped onto a sphere at the layer's altitude, scrolled by the wind and shaded
// by Kozlov 3.2-3.4 for the sun and the moon (shaders/sky_high_clouds.comp). The textures come
// from passes/high_cloud_textures, the LUTs from passes/atmosphere_luts; nothing here depends on
// the time of day except the uniforms, so moving the light never re-bakes anything.
#include <glm/vec3.hpp>

#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "engine/lighting/lighting_state.h"
#include "engine/scene/scene.h"
#include "shaders/common/atmosphere_shared.h"
#include "shaders/common/lighting_shared.h"
#include "shaders/common/sky_high_clouds_shared.h"

namespace sky {

class Context;
class Sampler;
class ShaderCompiler;

class SkyHighCloudsPass {
public:
  static constexpr const char* kName = "sky_high_clouds";
  struct Textures {  // passes/high_cloud_textures
    ImageId coefficients, normals, coarse;
    const Sampler* sampler = nullptr;  // linear, repeat
  };
  struct Atmosphere {  // passes/atmosphere_luts; sky.model physical only
    shared::AtmosphereParams params{};
    ImageId transmittance, skyViewSun, skyViewMoon;
    const Sampler* sampler = nullptr;  // linear, clamp
  };
  struct Inputs {
    shared::SkyHighCloudsParams params{};
    shared::LightingState lighting{};
    Textures textures;
    bool physical = false;  // sky.model physical: `atmosphere` must be set
    Atmosphere atmosphere;
  };
  struct Outputs {
    ImageId sky;         // RGBA16F: the clear sky radiance alone (no discs, stars or clouds)
    ImageId highClouds;  // RGBA16F: cloud radiance premultiplied, a = coverage
  };

  // Compiles both variants (kozlov, physical) once, at renderer start-up.
  SkyHighCloudsPass(const Context& ctx, ShaderCompiler& compiler);
  Outputs setup(GraphBuilder& builder, const Inputs& inputs);
  void execute(PassContext& ctx) const;

private:
  ComputePipeline mKozlov;
  ComputePipeline mPhysical;
  Inputs mInputs{};
  Outputs mOutputs;
};

// The layer's uniforms for one frame: geometry from the scene and camera, the wind's drift
// since the start of the scene's time, and each light's illuminance at the layer's altitude.
// `textureSize`/`coarseSize` are the texel counts across the fine and coarse textures.
shared::SkyHighCloudsParams skyHighCloudsParams(const Scene& scene, const LightingState& lighting,
                                                const IsoTime& time, const shared::ViewState& view,
                                                bool cloudsPresent, uint32_t textureSize,
                                                uint32_t coarseSize,
                                                const glm::vec4& meanCoefficients);

// Illuminance (renderer units, rgb) from a body at apparent elevation `elevationDeg` with
// angular radius `radiusDeg` and illuminance `aboveAtmosphere` outside the air, arriving at a
// point `altitudeM` above the ground: the point sees below the sea-level horizon by the dip
// acos(R / (R + h)), so high clouds stay sunlit after sunset, through a redder, longer path.
glm::vec3 illuminanceAtAltitude(const glm::vec3& aboveAtmosphere, double elevationDeg,
                                double radiusDeg, double altitudeM, double turbidity);

}  // namespace sky
