#pragma once
// The volumetric low and mid clouds (Lu et al. 2023, Tang et al. 2019): a raymarch through
// the spherical shells of the two layers (shaders/volumetric_clouds.comp), reading the weather
// map (engine/weather) for cover and type and the baked noise (passes/cloud_noise) for the
// density, lit by the frame's LightingState. What it shares with the other passes that sample
// the cloud field is in passes/cloud_field. See docs/clouds.md.
#include <optional>

#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "passes/cloud_field/cloud_field.h"
#include "shaders/common/host_depth_shared.h"
#include "shaders/common/lighting_shared.h"
#include "shaders/common/volumetric_clouds_shared.h"

namespace sky {

class Context;
class Sampler;
class ShaderCompiler;

class VolumetricCloudsPass {
public:
  static constexpr const char* kName = "volumetric_clouds";
  struct Inputs {
    shared::CloudParams params{};
    CloudVariant variant;
    shared::LightingState lighting{};
    CloudTextures textures;
    ImageId ambient;  // passes/cloud_ambient: the sky's and the ground's light
    // With variant.light Volume: passes/cloud_light_volume's volume and its sampler.
    ImageId lightVolume;
    const Sampler* lightVolumeSampler = nullptr;
    // A host's depth image at the view's size (skylayers::Sky::record): each march stops at
    // the host's geometry, so the clouds hold only what lies in front of it. Marching every
    // pixel (params.marchBlock 1): a history would not know where the geometry was.
    struct HostDepth {
      ImageId depth;
      const Sampler* sampler = nullptr;  // nearest, clamp
      shared::HostDepth mapping{};
    };
    std::optional<HostDepth> hostDepth;
  };
  struct Outputs {
    ImageId clouds;  // RGBA16F: rgb radiance premultiplied, a opacity (1 - transmittance)
    ImageId depth;   // RG32F: transmittance-weighted distance to the clouds (m), 0 where
                     // clear; g: where the ray reaches the shells (m), -1 if never
    ImageId steps;   // RGBA16F: density samples along the view ray, and inside light marches
  };

  VolumetricCloudsPass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add): once per view.
  struct Data {
    const ComputePipeline* pipeline = nullptr;  // this view's variant, chosen in setup()
    Inputs inputs{};
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  CloudPipelines mPipelines;
};

}  // namespace sky
