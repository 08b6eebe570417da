#pragma once
// The second layer of a frame: the low and mid clouds, raymarched through the weather map's
// cover (Lu et al. 2023, Tang et al. 2019), with their ambient light, light volume, shadow map
// and, over a sequence, temporal reuse. One of the Renderer's jobs, beside the sky
// (sky_layer.h), the cloud history (cloud_reuse.h, which this layer steps) and the outputs
// (frame_outputs.h). It owns those passes and what they keep from frame to frame: the light
// volume and shadow map while the clouds and lights stay (keyed by SettingsRevisions), and the
// history.
#include <optional>

#include "engine/render/cloud_field.h"
#include "engine/render/cloud_layers.h"
#include "engine/render/cloud_reuse.h"
#include "engine/render/cloud_volume.h"
#include "engine/render/frame_inputs.h"
#include "engine/render/sky_layer.h"
#include "passes/cloud_ambient/cloud_ambient.h"
#include "passes/cloud_density_slice/cloud_density_slice.h"
#include "passes/cloud_light_volume/cloud_light_volume.h"
#include "passes/cloud_perception/cloud_perception.h"
#include "passes/cloud_shadow/cloud_shadow.h"
#include "passes/cloud_denoise/cloud_denoise.h"
#include "passes/cloud_upsample/cloud_upsample.h"
#include "passes/cloud_volume_export/cloud_volume_export.h"
#include "passes/volumetric_clouds/volumetric_clouds.h"

namespace sky {

class Context;
class GraphRuntime;
class ShaderCompiler;

class VolumetricCloudLayer {
public:
  // `weather` is the frame's weather map, noise and their textures.
  VolumetricCloudLayer(const Context& ctx, ShaderCompiler& compiler, GraphRuntime& runtime,
                       CloudLayers& weather);

  // The volumetric clouds of a frame at the view's size, their shadow map and their textures,
  // and what the layer reports of the frame.
  struct Images {
    ImageId clouds, depth;
    // With output.perception: each pixel's optical depth and first hit (CloudPerceptionPass).
    std::optional<ImageId> perception;
    CloudShadowPass::Outputs shadow{};
    CloudLayers::Frame frame;
    double texturesMs = 0.0;     // keeping, loading or baking the noise and weather textures
    CloudNoise::Activity noise;  // which of those the noise was
    bool reuseStep = false;      // the frame took a step of the history: commitReuse() once run
  };
  // `sky` is the frame's first layer (its LUTs light the clouds' ambient), `atmosphere` the
  // physical sky's parameters.
  Images addTo(FrameGraph& graph, const FrameInputs& f, const SkyLayer::Images& sky,
               const AtmosphereLuts& atmosphere);

  // The frame that took a history step has run: it is the history now.
  void commitReuse() { mReuse.commit(); }
  // Forgets the history: the next frame is a cut (a frame of several views marched in full).
  void invalidateReuse() { mReuse.invalidate(); }
  // A frame failed, or was built and never run: the light volume and shadow map it would have
  // made were not made.
  void forgetKept();

  // The field of a frame of `scene` with `setup` (frameSetup) in each part of `request`, each
  // times its share (Renderer::exportCloudVolumes).
  std::vector<CloudVolume> exportVolumes(const Scene& scene, const FrameSetup& setup,
                                         const IsoTime& time, const CloudVolumeRequest& request);
  // The cloud density field of such a frame on the CPU (Renderer::cloudField).
  CloudField field(const Scene& scene, const FrameSetup& setup, const IsoTime& time);

private:
  // The clouds' ambient light (CloudAmbientPass) for the march `in`.
  ImageId addAmbient(FrameGraph& graph, const FrameInputs& f,
                     const VolumetricCloudsPass::Inputs& in, const SkyLayer::Images& sky,
                     const AtmosphereLuts& atmosphere);
  // The clouds `c` marched at `marchedView` (half the view's size) brought to the view's.
  void upsampleToView(FrameGraph& graph, const FrameInputs& f,
                      const shared::ViewState& marchedView, const shared::CloudParams& params,
                      Images& c);

  GraphRuntime& mRuntime;
  CloudLayers& mWeather;
  CloudAmbientPass mAmbient;
  VolumetricCloudsPass mVolumetric;
  CloudShadowPass mShadow;
  CloudReuse mReuse;  // the cloud history: temporal reuse across a sequence's frames
  CloudUpsamplePass mUpsample;
  CloudDenoisePass mDenoise;
  CloudLightVolumePass mLightVolume;
  SettingsRevisions mFieldSettings;  // what the light volume and shadow map were made for
  CloudDensitySlicePass mSlice;
  CloudPerceptionPass mPerception;
  CloudVolumeExportPass mVolumeExport;
};

}  // namespace sky
