// skyrender weather FILE [--scene SCENE] [--out DIR]: the cloud map a forecast file gives
// (Lu (1)(2) per layer, or the model's own cover), as an EXR and a PNG preview, with the
// per-layer figures a meteorologist checks first.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_args.h"
#include "commands.h"
#include "default_scene.h"
#include "engine/core/error.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"
#include "engine/scene/scene_io.h"
#include "engine/weather/cloud_layers_from_fields.h"
#include "engine/weather/coverage_metrics.h"
#include "engine/weather/weather_map.h"

namespace sky {
namespace fs = std::filesystem;
namespace {

// A map texel is "covered" above this cover, as skyrender dsc counts blocks.
constexpr float kCovered = 0.1f;

struct LayerFigures {
  double coveredFraction = 0.0;
  double meanCover = 0.0;
};

LayerFigures figures(const std::vector<float>& cover) {
  LayerFigures f;
  if (cover.empty()) return f;
  for (float c : cover) {
    f.meanCover += c;
    if (c > kCovered) f.coveredFraction += 1.0;
  }
  f.meanCover /= double(cover.size());
  f.coveredFraction /= double(cover.size());
  return f;
}

std::vector<float> channel(const WeatherMap& map, int c) {
  std::vector<float> out(map.texels.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = map.texels[i][c];
  return out;
}

bool hasTcc(const WeatherFields& fields) {
  for (const WeatherStep& step : fields.steps)
    if (step.find("tcc_low") && step.find("tcc_mid") && step.find("tcc_high")) return true;
  return false;
}

}  // namespace

int weatherCommand(const std::vector<std::string>& argv) {
  CliArgs args(argv, {"--scene", "--out", "--set"}, {"--set"}, {});
  if (args.positional().size() != 1)
    inputError(
        "weather needs one forecast file (skyrender weather FILE [--scene SCENE] "
        "[--out DIR])");
  const fs::path file = fs::absolute(args.positional()[0]);
  std::vector<std::string> overrides = args.values("--set");
  overrides.push_back("weather.source=file");
  // Quoted so any path reads as a YAML string.
  std::string quoted;
  for (char c : file.string())
    quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  overrides.push_back("weather.file=\"" + quoted + "\"");
  Scene scene;
  if (auto scenePath = args.value("--scene")) {
    scene = loadSceneFile(*scenePath, overrides);
  } else {
    scene = loadSceneText(skyDefaultSceneText(), ConfigFormat::Yaml, "<default scene>", overrides);
  }
  const fs::path outDir = args.value("--out").value_or("out");
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec || !fs::is_directory(outDir))
    inputError("--out " + outDir.string() + ": cannot create folder");

  const WeatherFields fields = readWeatherFile(scene);
  const double time = double(scene.time.start.unixSeconds);
  const WeatherMap map = weatherMapFromFields(fields, time, scene.weather);
  const int w = int(map.width), h = int(map.height);

  // The map: cover per layer, type and density; layer altitudes as header attributes (the
  // region means the renderer uses).
  LayeredImage image;
  image.width = w;
  image.height = h;
  ImageLayer layer{"", {"cover_low", "cover_mid", "cover_high", "type"}, {}};
  layer.pixels.resize(size_t(w) * h * 4);
  for (size_t i = 0; i < map.texels.size(); ++i) {
    layer.pixels[i * 4 + 0] = map.texels[i].r;
    layer.pixels[i * 4 + 1] = map.texels[i].g;
    layer.pixels[i * 4 + 2] = map.coverHigh.empty() ? 0.0f : map.coverHigh[i];
    layer.pixels[i * 4 + 3] = map.texels[i].b;
  }
  image.layers.push_back(std::move(layer));
  if (map.layerAltitudesM) {
    const glm::dvec4& a = *map.layerAltitudesM;
    const char* names[] = {"low_base_m", "low_top_m", "mid_base_m", "mid_top_m"};
    for (int i = 0; i < 4; ++i)
      image.attributes["skylayers:" + std::string(names[i])] = std::to_string(a[i]);
  }
  const std::string stem = file.stem().string();
  const fs::path exrPath = outDir / (stem + ".weather.exr");
  const fs::path pngPath = outDir / (stem + ".weather.png");
  writeExr(exrPath, image);
  // Preview: low cover red, mid green, high blue.
  std::vector<float> rgba(size_t(w) * h * 4);
  for (size_t i = 0; i < map.texels.size(); ++i) {
    rgba[i * 4 + 0] = map.texels[i].r;
    rgba[i * 4 + 1] = map.texels[i].g;
    rgba[i * 4 + 2] = map.coverHigh.empty() ? 0.0f : map.coverHigh[i];
    rgba[i * 4 + 3] = 1.0f;
  }
  writePng8(pngPath, w, h, rgba);

  std::printf("%s: %dx%d map over lat [%g, %g], lon [%g, %g], cover from %s\n",
              file.filename().string().c_str(), w, h, scene.weather.region.lat[0],
              scene.weather.region.lat[1], scene.weather.region.lon[0], scene.weather.region.lon[1],
              scene.weather.cover.c_str());
  const std::vector<float> layers[3] = {channel(map, 0), channel(map, 1), map.coverHigh};
  const char* names[3] = {"low", "mid", "high"};
  // The tcc map for comparison, when the file has the model's own cover and rh was used.
  std::optional<WeatherMap> tcc;
  if (scene.weather.cover == "rh" && hasTcc(fields)) {
    WeatherSettings settings = scene.weather;
    settings.cover = "tcc";
    tcc = weatherMapFromFields(fields, time, settings);
  }
  for (int l = 0; l < 3; ++l) {
    const LayerFigures f = figures(layers[l]);
    std::printf("%-4s covered %.3f  mean cover %.3f", names[l], f.coveredFraction, f.meanCover);
    if (map.layerAltitudesM && l < 2) {
      const glm::dvec4& a = *map.layerAltitudesM;
      std::printf("  altitude %.0f-%.0f m", l == 0 ? a.x : a.z, l == 0 ? a.y : a.w);
    }
    if (tcc) {
      const std::vector<float> other = l == 2 ? tcc->coverHigh : channel(*tcc, l);
      CoverageOptions options;
      options.cell = 1;
      options.threshold = kCovered;
      const CoverageMetrics m = compareCoverage(layers[l], other, w, h, options);
      std::printf("  dsc vs tcc %.3f", m.dice);
    }
    std::printf("\n");
  }
  std::printf("wrote %s, %s\n", exrPath.string().c_str(), pngPath.string().c_str());
  return 0;
}

}  // namespace sky
