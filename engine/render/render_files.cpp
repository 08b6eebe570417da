#include "engine/render/render_files.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "engine/color/night_look.h"
#include "engine/color/ocio_output.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/paths.h"
#include "engine/io/png.h"
#include "engine/render/frame_layers.h"
#include "engine/scene/scene_io.h"

namespace sky {

std::vector<float> displayPixels(const RenderedFrame& frame, const Scene& scene,
                                 const FrameExposure& exposure, const OcioOutput& ocio) {
  const ImageLayer* beauty = frame.image.find("");
  if (!beauty || beauty->channels.size() != 4)
    internalError("rendered frame has no RGBA main layer");
  std::vector<float> rgba = beauty->pixels;
  if (scene.output.nightLook) applyNightLook(rgba);
  ocio.toDisplay(rgba, scene.output.display, scene.output.view, exposure.ev);
  return rgba;
}

namespace {

// The process's resident memory now and at its peak (VmRSS, VmHWM of /proc/self/status), MiB:
// a time-lapse's reports show whether memory stays flat over its frames.
nlohmann::ordered_json processMemoryJson() {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    for (const auto& [key, name] :
         {std::pair{"VmRSS:", "resident_mib"}, {"VmHWM:", "peak_resident_mib"}})
      if (line.rfind(key, 0) == 0) out[name] = std::stod(line.substr(std::strlen(key))) / 1024.0;
  }
  return out;
}

}  // namespace

std::string frameStem(const std::string& name, int64_t index, int64_t count, bool range) {
  if (!range) return name;
  std::string number = std::to_string(index + 1);
  size_t width = std::max<size_t>(4, std::to_string(count).size());
  return name + "_" + std::string(width - std::min(width, number.size()), '0') + number;
}

nlohmann::ordered_json renderReport(const Scene& scene, const RenderedFrame& frame,
                                    const FrameExposure& exposure, const OcioOutput& ocio,
                                    const std::string& deviceName,
                                    const std::vector<std::string>& debugFiles) {
  nlohmann::ordered_json report;
  report["skylayers_version"] = skylayersVersion();
  report["device"] = deviceName;
  report["size"] = {frame.image.width, frame.image.height};
  report["time"] = frame.lighting.time.format();
  const nlohmann::ordered_json lighting = lightingJson(frame.lighting);
  for (const char* key : {"time_utc", "sun", "moon", "light"}) report[key] = lighting.at(key);
  nlohmann::ordered_json passes = nlohmann::ordered_json::array();
  for (const PassTiming& t : frame.frame.passes)
    passes.push_back({{"name", t.name}, {"gpu_ms", t.gpuMs}});
  report["passes"] = passes;
  report["gpu_ms_total"] = frame.frame.gpuMs;
  report["frame_wall_ms"] = frame.frame.wallMs;
  // Where render() spent its wall time besides drawing: what a first frame pays once.
  report["render_costs"] = {{"renderer_ms", frame.costs.rendererMs},
                            {"renderer_pipelines_ms", frame.costs.rendererPipelinesMs},
                            {"render_ms", frame.costs.renderMs},
                            {"pipelines_ms", frame.costs.pipelinesMs},
                            {"textures_ms", frame.costs.texturesMs},
                            {"lut_bake_gpu_ms", frame.costs.lutBakeGpuMs},
                            {"setup_ms", frame.costs.setupMs()}};
  nlohmann::ordered_json exposureJson = {{"mode", enumName(exposure.mode)}, {"ev", exposure.ev}};
  if (exposure.mode == ExposureMode::Histogram) {
    exposureJson["metered_luminance"] = exposure.meteredLuminance;
    exposureJson["target_ev"] = exposure.targetEv;
  }
  report["exposure"] = exposureJson;
  report["ocio"] = {{"config", ocio.configPath().string()},
                    {"display", scene.output.display},
                    {"view", scene.output.view}};
  nlohmann::ordered_json layers = nlohmann::ordered_json::array();
  for (const ImageLayer& l : frame.image.layers) layers.push_back(frameLayerName(l));
  report["exr_layers"] = layers;
  if (const std::optional<PerceptionSummary>& p = frame.perception) {
    nlohmann::ordered_json shares;
    for (int k = 0; k < PERCEPTION_LABEL_COUNT; ++k)
      shares[perceptionLabelName(k)] = p->labelShares[size_t(k)];
    report["perception"] = {{"visibility_m", p->visibilityM},
                            {"sun_visible", p->sunVisible},
                            {"sun_cloud_transmittance", p->sunCloud},
                            {"label_shares", shares}};
  }
  nlohmann::ordered_json highClouds;
  highClouds["baked"] = frame.highClouds.baked;
  highClouds["loaded_cache"] = frame.highClouds.loadedCache;
  highClouds["loaded_images"] = frame.highClouds.loadedImages;
  // Only a cache entry that was read or written: an unwritable cache keeps nothing.
  if (!frame.highClouds.cacheFile.empty() &&
      (frame.highClouds.loadedCache || frame.highClouds.wroteCache))
    highClouds["cache_file"] = frame.highClouds.cacheFile.string();
  nlohmann::ordered_json bake = nlohmann::ordered_json::array();
  for (const PassTiming& t : frame.highClouds.bakeTimings)
    bake.push_back({{"name", t.name}, {"gpu_ms", t.gpuMs}});
  highClouds["bake_passes"] = bake;
  report["high_cloud_textures"] = highClouds;
  nlohmann::ordered_json clouds;
  clouds["present"] = frame.clouds;
  clouds["noise_baked"] = frame.cloudNoise.baked;
  clouds["noise_loaded_cache"] = frame.cloudNoise.loadedCache;
  if (!frame.cloudNoise.cacheFile.empty() &&
      (frame.cloudNoise.loadedCache || frame.cloudNoise.wroteCache))
    clouds["noise_cache_file"] = frame.cloudNoise.cacheFile.string();
  if (frame.cloudShadow.valid > 0.0f)
    clouds["cloud_shadow"] = {{"radius_m", frame.cloudShadow.radiusM},
                              {"light", frame.cloudShadow.lightIsSun > 0.5f ? "sun" : "moon"}};
  report["volumetric_clouds"] = clouds;
  const LocalWeather& local = frame.localWeather;
  report["local_weather"] = {{"radius_km", scene.weather.localRadiusKm},
                             {"cover_low", local.low},
                             {"cover_mid", local.mid},
                             {"cover_high", local.high},
                             {"overcast", local.overcast}};
  const WeatherRegion& region = frame.weatherRegion;
  report["weather_map"] = {
      {"region",
       {{"lat", {region.lat[0], region.lat[1]}}, {"lon", {region.lon[0], region.lon[1]}}}},
      {"given", scene.weather.region.has_value()},
      {"texels", {frame.weatherTexels.x, frame.weatherTexels.y}}};
  report["debug_outputs"] = debugFiles;
  const CacheStatus& cache = cacheStatus();
  report["cache"] = {{"folder", cache.folder.string()}, {"writable", cache.writable}};
  if (!cache.writable) report["cache"]["not_written_because"] = cache.reason;
  report["process"] = processMemoryJson();
  // Paths resolved, so the report's settings render the same from any folder.
  report["settings"] = sceneToJson(scene.withAbsolutePaths());

  return report;
}

RenderFiles writeRenderFiles(const std::filesystem::path& dir, const std::string& stem,
                             const Scene& scene, const RenderedFrame& frame,
                             const FrameExposure& exposure, const OcioOutput& ocio,
                             const std::string& deviceName,
                             const std::optional<std::filesystem::path>& graphPath) {
  RenderFiles files;
  files.exr = dir / (stem + ".exr");
  files.png = dir / (stem + ".png");
  files.report = dir / (stem + ".json");
  files.graph = graphPath;

  // Everything that can fail runs before the first rename.
  std::vector<float> display = displayPixels(frame, scene, exposure, ocio);

  for (const DebugImage& d : frame.debug)
    files.debug.push_back(dir / (stem + "." + d.info.name + ".exr"));
  std::vector<std::string> debugFiles;
  for (const std::filesystem::path& p : files.debug) debugFiles.push_back(p.filename().string());
  const nlohmann::ordered_json report =
      renderReport(scene, frame, exposure, ocio, deviceName, debugFiles);

  LayeredImage exr = frame.image;
  exr.attributes["skylayers:device"] = deviceName;
  // The stops the PNG was exposed by: the EXR itself is physical (docs/outputs.md).
  exr.attributes["skylayers:exposure_ev"] = std::to_string(exposure.ev);
  if (frame.perception) {
    exr.attributes["skylayers:visibility_m"] = std::to_string(frame.perception->visibilityM);
    exr.attributes["skylayers:sun_visible"] = std::to_string(frame.perception->sunVisible);
  }

  AtomicFileSet set;
  set.stage(files.exr, [&](const std::filesystem::path& tmp) { writeExr(tmp, exr); });
  set.stage(files.png, [&](const std::filesystem::path& tmp) {
    writePng8(tmp, frame.image.width, frame.image.height, display,
              scene.output.dither ? PngQuantize::Dither : PngQuantize::Nearest);
  });
  for (size_t i = 0; i < frame.debug.size(); ++i)
    set.stage(files.debug[i], [&frame, i](const std::filesystem::path& tmp) {
      writeExr(tmp, frame.debug[i].image);
    });
  if (graphPath)
    set.stage(*graphPath,
              [&](const std::filesystem::path& tmp) { writeFileAtomic(tmp, frame.graphDot); });
  // The report last: the set commits in the order staged, so a report in the folder means its
  // images are whole, even after a crash between two renames (docs/outputs.md).
  set.stage(files.report,
            [&](const std::filesystem::path& tmp) { writeFileAtomic(tmp, report.dump(2) + "\n"); });
  set.commit();
  return files;
}

}  // namespace sky
