#include "engine/render/renderer.h"

#include <algorithm>

#include "engine/core/error.h"
#include "engine/core/paths.h"
#include "engine/gpu/context.h"
#include "engine/render/camera.h"

namespace sky {
namespace {

// Splits interleaved read-back into a layer with the first `channels` channels. A 3D image
// is laid out with its depth slices side by side (width * depth across).
ImageLayer toLayer(const ReadbackImage& img, std::string name, std::vector<std::string> channels) {
  ImageLayer layer{std::move(name), std::move(channels), {}};
  const size_t w = img.width, h = img.height, d = img.depth, c = layer.channels.size();
  layer.pixels.resize(w * h * d * c);
  for (size_t z = 0; z < d; ++z)
    for (size_t y = 0; y < h; ++y)
      for (size_t x = 0; x < w; ++x) {
        const size_t src = ((z * h + y) * w + x) * img.channels;
        const size_t dst = (y * w * d + z * w + x) * c;
        for (size_t k = 0; k < c; ++k) layer.pixels[dst + k] = img.pixels[src + k];
      }
  return layer;
}

const std::vector<std::string> kRgb = {"R", "G", "B"};
const std::vector<std::string> kRgba = {"R", "G", "B", "A"};

}  // namespace

const std::vector<DebugOutputInfo>& debugOutputs() {
  static const std::vector<DebugOutputInfo> outputs = {
      {"coefficients", "high-cloud coefficient texture (R thin lit, G dense, B clear, A edges)",
       false},
      {"normals", "high-cloud tangent-space normal map (xyz in -1..1)", false},
      {"transmittance_lut", "transmittance to the top of the atmosphere, 256x64", true},
      {"multiscattering_lut", "multiple-scattering contribution Psi_ms, 32x32", true},
      {"sky_view_sun_lut", "sky radiance lit by the sun, 192x108", true},
      {"sky_view_moon_lut", "sky radiance lit by the moon, 192x108", true},
      {"aerial_perspective",
       "in-scattering (rgb) and transmittance (a), 32x32x32, slices "
       "side by side",
       true},
  };
  return outputs;
}

void checkDebugOutputs(const Scene& scene, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    auto it = std::find_if(debugOutputs().begin(), debugOutputs().end(),
                           [&](const DebugOutputInfo& o) { return name == o.name; });
    if (it == debugOutputs().end()) {
      std::string known;
      for (const DebugOutputInfo& o : debugOutputs())
        known += (known.empty() ? "" : ", ") + std::string(o.name);
      inputError("--debug-output " + name + ": unknown (known: " + known + ")");
    }
    if (it->physicalOnly && scene.sky.model != "physical")
      inputError("--debug-output " + name + ": needs sky.model physical (the scene uses " +
                 scene.sky.model + ")");
  }
}

Renderer::Renderer(const Context& ctx, ShaderCompiler& compiler)
    : mRuntime(ctx),
      mStars(ctx, compiler, loadStarCatalog(configDir() / "stars" / "bright_star_catalogue.txt")),
      mHighCloudTextures(ctx, compiler, mRuntime),
      mAtmosphere(ctx, compiler),
      mSky(ctx, compiler),
      mComposite(ctx, compiler) {}

void Renderer::setBakeProgress(std::function<void(double)> progress) {
  mHighCloudTextures.setProgress(std::move(progress));
}

RenderedFrame Renderer::render(const Scene& scene, const IsoTime& time,
                               const RenderOptions& options) {
  checkDebugOutputs(scene, options.debugOutputs);
  RenderedFrame out;
  out.lighting = computeLighting(scene, time);
  const uint32_t width = static_cast<uint32_t>(scene.output.width);
  const uint32_t height = static_cast<uint32_t>(scene.output.height);
  const shared::ViewState view = makeViewState(scene.camera, width, height);
  const bool physical = scene.sky.model == "physical";

  FrameGraph graph(mRuntime);
  StarFieldPass::Frame stars;
  stars.view = view;
  stars.j2000ToEnu = glm::mat3(out.lighting.ephemeris.equatorialJ2000ToEnu);
  stars.extinction = static_cast<float>(scene.lighting.starExtinction);
  StarFieldPass::Outputs starOut = mStars.addTo(graph, stars);

  // The high-cloud textures: kept from the last frame, loaded, or baked (before this graph).
  const HighCloudTextures::Outputs textures = mHighCloudTextures.addTo(graph, scene);
  out.highClouds = mHighCloudTextures.lastActivity();

  SkyHighCloudsPass::Inputs sky{};
  const bool cloudsPresent = scene.highClouds.source == "image" || scene.highClouds.cover > 0.0;
  const ImageDesc& fine = graph.desc().resources[textures.coefficients.id].image;
  const ImageDesc& coarse = graph.desc().resources[textures.coarse.id].image;
  sky.params = skyHighCloudsParams(scene, out.lighting, time, view, cloudsPresent, fine.width,
                                   coarse.width, textures.mean);
  sky.lighting = out.lighting.gpu;
  sky.textures = {textures.coefficients, textures.normals, textures.coarse,
                  &mHighCloudTextures.sampler()};
  AtmosphereLuts::Outputs luts{};
  if (physical) {
    AtmosphereLuts::Frame f;
    f.atmosphere = scene.atmosphere;
    f.cameraAltitudeM = scene.camera.altitudeM;
    f.view = view;
    f.sunDirection = glm::vec3(out.lighting.sun.direction);
    f.moonDirection = glm::vec3(out.lighting.moon.direction);
    f.sunIlluminance = glm::vec3(out.lighting.gpu.sunSpace);
    f.moonIlluminance = glm::vec3(out.lighting.gpu.moonSpace);
    luts = mAtmosphere.addTo(graph, f);
    sky.physical = true;
    sky.atmosphere = {mAtmosphere.params(), luts.transmittance, luts.skyViewSun, luts.skyViewMoon,
                      &mAtmosphere.sampler()};
  }
  const SkyHighCloudsPass::Outputs skyOut = graph.add(mSky, sky);

  AtmosphereCompositePass::Inputs composite{};
  composite.params.view = view;
  composite.lighting = out.lighting.gpu;
  composite.starFlux = starOut.flux;
  composite.sky = skyOut.sky;
  composite.highClouds = skyOut.highClouds;
  AtmosphereCompositePass::Outputs composited = graph.add(mComposite, composite);
  graph.requestOutput(composited.beauty, "beauty");
  graph.requestOutput(skyOut.sky, "sky");
  graph.requestOutput(skyOut.highClouds, "high_clouds");

  struct DebugSource {
    const char* name;
    ImageId image;
    const std::vector<std::string>* channels;
  };
  const DebugSource sources[] = {
      {"coefficients", textures.coefficients, &kRgba},
      {"normals", textures.normals, &kRgb},
      {"transmittance_lut", luts.transmittance, &kRgb},
      {"multiscattering_lut", luts.multiScattering, &kRgb},
      {"sky_view_sun_lut", luts.skyViewSun, &kRgb},
      {"sky_view_moon_lut", luts.skyViewMoon, &kRgb},
      {"aerial_perspective", luts.aerialPerspective, &kRgba},
  };
  for (const std::string& name : options.debugOutputs)
    for (const DebugSource& s : sources)
      if (name == s.name) graph.requestOutput(s.image, "debug:" + name);

  out.frame = graph.execute();
  out.graphDot = graph.toDot(&out.frame);

  out.image.width = static_cast<int>(width);
  out.image.height = static_cast<int>(height);
  out.image.layers.push_back(toLayer(out.frame.output("beauty"), "", kRgba));
  out.image.layers.push_back(toLayer(out.frame.output("sky"), "sky", kRgb));
  out.image.layers.push_back(toLayer(out.frame.output("high_clouds"), "high_clouds", kRgba));
  for (const std::string& name : options.debugOutputs)
    for (const DebugSource& s : sources)
      if (name == s.name) {
        const ReadbackImage& img = out.frame.output("debug:" + name);
        DebugImage d{name, {}};
        d.image.width = static_cast<int>(img.width * img.depth);
        d.image.height = static_cast<int>(img.height);
        d.image.layers.push_back(toLayer(img, "", *s.channels));
        out.debug.push_back(std::move(d));
      }
  for (ReadbackImage& o : out.frame.outputs) o.pixels = {};  // the layers hold the data now
  return out;
}

}  // namespace sky
