#include "engine/render/volumetric_cloud_layer.h"

#include "engine/core/error.h"
#include "engine/render/camera.h"
#include "engine/weather/weather_map.h"

namespace sky {
namespace {

// cloud_denoise: two cloudy neighbours whose depths differ by this share mix by 1/e, more for a
// near cloud (CLOUD_DENOISE_NEAR_PIXELS). Measured on the peer's noon view at 640 x 360
// (docs/clouds.md, "Grain"): the lit faces' high-frequency energy goes from 1.53 to 0.96 times
// the reference march's over the frame and the error against the reference from 4.6 to 3.4 %.
// With 0.02 alone a near cloud kept 2.8 times the reference's; with 0.3 the far clouds lost
// their texture (both measured on the cumulus of branch cumulus2).
constexpr float kDenoiseDepthSpread = 0.02f;

}  // namespace

VolumetricCloudLayer::VolumetricCloudLayer(const Context& ctx, ShaderCompiler& compiler,
                                           GraphRuntime& runtime, CloudLayers& weather)
    : mRuntime(runtime),
      mWeather(weather),
      mAmbient(ctx, compiler),
      mVolumetric(ctx, compiler),
      mShadow(ctx, compiler),
      mReuse(ctx, compiler),
      mUpsample(ctx, compiler),
      mDenoise(ctx, compiler),
      mLightVolume(ctx, compiler),
      mSlice(ctx, compiler),
      mPerception(ctx, compiler),
      mVolumeExport(ctx, compiler) {}

void VolumetricCloudLayer::forgetKept() {
  mLightVolume.invalidate();
  mShadow.invalidate();
}

VolumetricCloudLayer::Images VolumetricCloudLayer::addTo(FrameGraph& graph, const FrameInputs& f,
                                                         const SkyLayer::Images& sky,
                                                         const AtmosphereLuts& atmosphere) {
  const Scene& scene = f.scene;
  const Scene& cloudScene = f.setup.cloudScene;
  const CloudFrameGeometry& geometry = f.setup.geometry;
  Images c;
  SharedFrame* shared = f.shared;
  const SharedFrame::Clouds* made = shared && shared->clouds ? &*shared->clouds : nullptr;
  // Temporal reuse: a sequence's frames march a share of the pixels and reproject the rest,
  // at the view's size or at half its width and height. Not in a frame of several views.
  // Nor with a host's depth: the march stops at its geometry, which a history would not know.
  const bool temporal = scene.clouds.temporal.mode == CloudTemporalMode::On &&
                        scene.clouds.quality == CloudQuality::Standard && !f.topDown && !shared &&
                        !f.hostDepth;
  const bool half = temporal && scene.clouds.temporal.resolution == CloudTemporalResolution::Half;
  const uint32_t cloudWidth = half ? (f.width + 1) / 2 : f.width;
  const uint32_t cloudHeight = half ? (f.height + 1) / 2 : f.height;
  const shared::ViewState cloudView =
      half ? makeViewState(scene.camera, cloudWidth, cloudHeight) : f.view;
  const CloudFieldFrame field = cloudFieldFrame(graph, mWeather, f.setup, f.time, cloudView,
                                                mFieldSettings.of(cloudScene),
                                                made ? &made->frame : nullptr);
  c.frame = field.frame;
  c.texturesMs = field.texturesMs;
  c.noise = mWeather.noiseActivity();
  VolumetricCloudsPass::Inputs in;
  in.params = field.params;
  in.variant = field.variant;
  in.lighting = f.lighting.gpu;
  in.textures = c.frame.textures;
  in.hostDepth = f.hostDepth;
  in.ambient = made ? made->ambient : addAmbient(graph, f, in, sky, atmosphere);
  std::optional<CloudLightVolumePass::Outputs> lightVolume;
  // The light through the clouds from the light volume (the reference marches it).
  if (in.variant.light == CloudLight::Volume) {
    CloudLightVolumePass::Inputs v;
    v.params = in.params;
    v.variant = in.variant;
    v.params.lightVolume = cloudLightVolumePlace(in.params, geometry.altitudeM);
    v.textures = in.textures;
    v.key = field.key;  // kept while it holds
    const CloudLightVolumePass::Outputs volume =
        made && made->volume ? *made->volume : mLightVolume.addTo(graph, v);
    if (shared) lightVolume = volume;
    in.params.lightVolume = volume.place;
    in.lightVolume = volume.volume;
    in.lightVolumeSampler = &mLightVolume.sampler();
  }
  std::optional<CloudReuse::Step> step;
  if (temporal) {
    step = mReuse.step(scene, f.time, cloudView, mWeather.mapRevision(), f.sequenceFrame);
    in.params.marchBlock = step->block;
    in.params.marchOffsetX = step->offset.x;
    in.params.marchOffsetY = step->offset.y;
    // A new jitter every frame, so a pixel marched again averages differently.
    in.params.frameIndex =
        (in.params.frameIndex + static_cast<uint32_t>(step->frame) * 0x9E3779B9u) & 0x7fffffffu;
  }
  const VolumetricCloudsPass::Outputs marched = graph.add(mVolumetric, in);
  if (scene.output.perception && !f.topDown) {
    // Every pixel at the output's size, whatever the beauty's march does.
    CloudPerceptionPass::Inputs p{in.params, in.variant, in.textures};
    p.params.view = f.view;
    c.perception = graph.add(mPerception, p).hit;
  }
  c.clouds = marched.clouds;
  c.depth = marched.depth;
  if (temporal) {
    const CloudTemporalPass::Outputs resolved =
        mReuse.addTo(graph, *step, c.clouds, c.depth,
                     {in.params.geo.origin.w, scene.camera.altitudeM, in.params.shellBaseM,
                      in.params.shellTopM});
    c.clouds = resolved.clouds;
    c.depth = resolved.depth;
    c.reuseStep = true;
  }
  if (half) upsampleToView(graph, f, cloudView, in.params, c);
  // A still's one march per pixel keeps its grain, which a sequence's reuse averages out.
  const CloudSettings& cs = scene.clouds;
  if (!temporal && cs.denoise && cs.samples == 1 && cs.quality == CloudQuality::Standard &&
      !f.topDown) {
    CloudDenoisePass::Inputs d;
    d.params.view = f.view;
    d.params.depthSpread = kDenoiseDepthSpread;
    // The detail noise's finest octave (B), a quarter of its coarsest cell.
    d.params.detailCellM = static_cast<float>(
        0.25 * cloudDetailCellM(1.0 / field.params.detailRepeatsPerM, field.variant.model));
    d.clouds = c.clouds;
    d.depth = c.depth;
    const CloudDenoisePass::Outputs filtered = graph.add(mDenoise, d);
    c.clouds = filtered.clouds;
    c.depth = filtered.depth;
  }
  // The clouds' shadows on the ground around the observer (a top-down render draws no
  // ground, but the composite's cloud variant binds a map all the same).
  if (made) {
    c.shadow = made->shadow;
  } else {
    c.shadow =
        mShadow.addTo(graph, CloudShadowPass::Inputs{in.params, in.variant,
                                                     cloudShadowMap(in.params, geometry.altitudeM),
                                                     in.textures, field.key});
    // A cut through the density field for the debug view: culled unless it is asked for.
    graph.add(mSlice, CloudDensitySlicePass::Inputs{in.params, in.variant, in.textures});
    if (shared) shared->clouds = SharedFrame::Clouds{c.frame, in.ambient, lightVolume, c.shadow};
  }
  return c;
}

ImageId VolumetricCloudLayer::addAmbient(FrameGraph& graph, const FrameInputs& f,
                                         const VolumetricCloudsPass::Inputs& in,
                                         const SkyLayer::Images& sky,
                                         const AtmosphereLuts& atmosphere) {
  // The ambient light from the sky the frame draws (either model) and the ground under it.
  CloudAmbientPass::Inputs ambient;
  const bool dualLobe = in.variant.phase == CloudPhase::DualLobe;
  ambient.params = cloudAmbientParams({f.scene.ground.albedo, f.scene.lighting.turbidity,
                                       in.params.shellBaseM, f.lighting.overcast, in.params.g,
                                       in.params.gBack, dualLobe ? in.params.backWeight : 0.0f});
  ambient.lighting = f.lighting.gpu;
  ambient.moon = !moonLightNegligible(f.lighting.gpu);
  if (f.physical)
    ambient.atmosphere = CloudAmbientPass::Atmosphere{
        atmosphere.cloudParams(), sky.luts.transmittance, sky.luts.skyViewSunClouds,
        sky.luts.skyViewMoonClouds, &atmosphere.sampler()};
  return graph.add(mAmbient, ambient).ambient;
}

void VolumetricCloudLayer::upsampleToView(FrameGraph& graph, const FrameInputs& f,
                                          const shared::ViewState& marchedView,
                                          const shared::CloudParams& params, Images& c) {
  CloudUpsamplePass::Inputs u;
  u.params.view = f.view;
  u.params.source = marchedView;
  u.params.planetRadiusM = params.geo.origin.w;
  u.params.cameraAltitudeM = static_cast<float>(f.scene.camera.altitudeM);
  u.params.shellBaseM = params.shellBaseM;
  u.params.shellTopM = params.shellTopM;
  u.clouds = c.clouds;
  u.depth = c.depth;
  const CloudUpsamplePass::Outputs full = graph.add(mUpsample, u);
  c.clouds = full.clouds;
  c.depth = full.depth;
}

std::vector<CloudVolume> VolumetricCloudLayer::exportVolumes(const Scene& scene,
                                                             const FrameSetup& setup,
                                                             const IsoTime& time,
                                                             const CloudVolumeRequest& request) {
  if (setup.geometry.topDown)
    inputError(
        "export-volume: camera.mode geographic_topdown has no camera to export the "
        "clouds around (use camera.mode observer)");
  const glm::vec2 maxCover = setup.weather->maxCover();
  if (maxCover.x <= 0.0f && maxCover.y <= 0.0f)
    inputError("export-volume: the scene has no low or mid clouds (weather cover is 0 everywhere)");
  std::vector<CloudVolumePart> parts = request.parts;
  if (parts.empty())
    parts.push_back({defaultCloudVolumeBox(setup.cloudScene, maxCover), request.defaultVoxelM});
  checkCloudVolumeParts(parts);
  std::vector<CloudVolumeGrid> grids;
  for (const CloudVolumePart& part : parts) grids.push_back(cloudVolumeGrid(part.box, part.voxelM));

  const shared::ViewState view =
      makeViewState(scene.camera, static_cast<uint32_t>(scene.output.width),
                    static_cast<uint32_t>(scene.output.height));
  std::vector<CloudVolume> volumes;
  for (size_t k = 0; k < parts.size(); ++k) {
    CloudVolumeGrid& grid = grids[k];
    setCloudVolumeFootprint(grid, request.lod, view);
    // One graph a part, so only one part's 3D image is alive at a time.
    FrameGraph graph(mRuntime);
    // The raymarch's own parameters, so the grid holds the very field it marches through.
    const CloudFieldFrame field = cloudFieldFrame(graph, mWeather, setup, time, view);
    CloudVolumeExportPass::Inputs in;
    in.params = field.params;
    in.variant = field.variant;
    in.box = grid.params;
    in.textures = field.frame.textures;
    graph.requestOutput(graph.add(mVolumeExport, in).grid, "cloud_volume");
    FrameResult result = graph.execute();
    std::vector<float> density = std::move(result.output("cloud_volume").pixels);
    if (parts.size() > 1) {
      // Each part keeps its share of the field, so the parts add up to it once.
      size_t i = 0;
      const glm::uvec4 n = grid.params.voxels;
      const glm::dvec3 first = grid.box.minM + 0.5 * grid.voxelM;
      for (uint32_t z = 0; z < n.z; ++z)
        for (uint32_t y = 0; y < n.y; ++y)
          for (uint32_t x = 0; x < n.x; ++x, ++i)
            if (density[i] != 0.0f)
              density[i] *= static_cast<float>(
                  cloudVolumeShare(parts, k, first + glm::dvec3(x, y, z) * grid.voxelM));
    }
    volumes.push_back(makeCloudVolume(setup.cloudScene, setup.lighting, time, view, grid,
                                      std::move(density), parts.front().box));
  }
  if (parts.size() > 1) nameCloudVolumeParts(volumes, parts);
  return volumes;
}

CloudField VolumetricCloudLayer::field(const Scene& scene, const FrameSetup& setup,
                                       const IsoTime& time) {
  if (setup.geometry.topDown)
    inputError(
        "cloud queries: camera.mode geographic_topdown has no observer to place the clouds "
        "around (use camera.mode observer)");
  CloudFieldInputs in;
  in.camera = {setup.geometry.latDeg, setup.geometry.lonDeg, setup.geometry.altitudeM};
  in.weather = *setup.weather;
  in.air = atmosphereParams(physicalAtmosphere(scene));
  const glm::vec2 maxCover = setup.weather->maxCover();
  in.anyCover = maxCover.x > 0.0f || maxCover.y > 0.0f;
  if (in.anyCover) {
    // As exportCloudVolume: the textures and tables a frame would import, then the
    // raymarch's own uniforms.
    FrameGraph graph(mRuntime);
    const shared::ViewState view =
        makeViewState(scene.camera, static_cast<uint32_t>(scene.output.width),
                      static_cast<uint32_t>(scene.output.height));
    const CloudFieldFrame field = cloudFieldFrame(graph, mWeather, setup, time, view);
    in.params = field.params;
    in.tang = field.variant.model == CloudModel::Tang2019;
    in.calibrated = field.variant.coverage == CloudCoverageMode::Calibrated;
    in.rolls = field.variant.rolls == CloudRolls::On;
    in.cumulus = field.variant.cumulus == CloudCumulus::On;
    in.shape = mWeather.noise().shapeVolume();
    in.detail = mWeather.noise().detailVolume();
    in.curl = mWeather.noise().curlPlane();
  }
  return CloudField(std::move(in));
}

}  // namespace sky
