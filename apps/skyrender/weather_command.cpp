// skyrender weather FILE [--scene SCENE] [--out DIR]: the cloud map a forecast file gives
// (Lu (1)(2) per layer, or the model's own cover), as an EXR and a PNG preview, with the
// per-layer figures a meteorologist checks first.
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "apps/common/default_scene.h"
#include "cli_args.h"
#include "commands.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"
#include "engine/scene/scene_io.h"
#include "engine/weather/cloud_layers_from_fields.h"
#include "engine/weather/coverage_metrics.h"
#include "engine/weather/forecast_map.h"
#include "engine/weather/weather_map.h"
#include "engine/weather/weather_source.h"

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
    if (step.find(FieldKind::CloudCoverLow) && step.find(FieldKind::CloudCoverMid) &&
        step.find(FieldKind::CloudCoverHigh))
      return true;
  return false;
}

}  // namespace

int weatherCommand(const std::vector<std::string>& argv) {
  CliArgs args("weather", argv, {"--scene", "--out", "--set"}, {"--set"}, {});
  args.expectPositionals(1, 1, "one forecast file");
  const fs::path file = fs::absolute(args.positional()[0]);
  std::vector<std::string> overrides = args.values("--set");
  for (std::string& o : forecastFileOverrides(file)) overrides.push_back(std::move(o));
  Scene scene;
  if (auto scenePath = args.value("--scene")) {
    scene = loadSceneFile(*scenePath, overrides);
  } else {
    scene = loadSceneText(skyDefaultSceneText(), ConfigFormat::Yaml, "<default scene>", overrides);
  }
  OutputFolder folder(args.value("--out").value_or("out"), "--out");
  const fs::path& outDir = folder.path();

  // The map the renderer would draw in the scene's first frame, with the layers' altitudes
  // (engine/weather/forecast_map.h).
  WeatherSource source;
  const ForecastMap forecast = forecastMap(scene, source);
  const WeatherMap& map = forecast.map;
  const WeatherInputs& inputs = forecast.inputs;
  const WeatherFields& fields = *source.fields();
  const double time = forecast.timeUnix;
  const std::array<std::vector<float>, 6>& altitudes = forecast.altitudes;
  const LayeredImage& image = forecast.image;
  const int w = int(map.width), h = int(map.height);
  const std::string stem = file.stem().string();
  const fs::path exrPath = outDir / (stem + ".weather.exr");
  const fs::path pngPath = outDir / (stem + ".weather.png");
  // Preview: low cover red, mid green, high blue.
  std::vector<float> rgba(size_t(w) * h * 4);
  for (size_t i = 0; i < map.texels.size(); ++i) {
    rgba[i * 4 + 0] = map.texels[i].r;
    rgba[i * 4 + 1] = map.texels[i].g;
    rgba[i * 4 + 2] = map.coverHigh.empty() ? 0.0f : map.coverHigh[i];
    rgba[i * 4 + 3] = 1.0f;
  }
  // Both or neither, as a render's files: on a full disk the PNG failed after the EXR was in
  // place (issue 31, 2).
  AtomicFileSet files;
  files.stage(exrPath, [&](const fs::path& tmp) { writeExr(tmp, image); });
  files.stage(pngPath, [&](const fs::path& tmp) {
    writePng8(tmp, w, h, rgba, PngQuantize::Nearest);  // a data image: exact codes
  });
  files.commit();
  folder.keep();

  std::printf("%s: %dx%d map over lat [%g, %g], lon [%g, %g], cover from %s\n",
              file.filename().string().c_str(), w, h, map.region.lat[0], map.region.lat[1],
              map.region.lon[0], map.region.lon[1], enumName(scene.weather.cover));
  const std::vector<float> layers[3] = {channel(map, 0), channel(map, 1), map.coverHigh};
  const char* names[3] = {"low", "mid", "high"};
  // The tcc map for comparison, when the file has the model's own cover and rh was used.
  std::optional<WeatherMap> tcc;
  if (scene.weather.cover == WeatherCover::Rh && hasTcc(fields)) {
    WeatherSettings settings = scene.weather;
    settings.cover = WeatherCover::Tcc;
    tcc = weatherMapFromFields(fields, time, settings, map.region, inputs.windMs);
  }
  for (int l = 0; l < 3; ++l) {
    const LayerFigures f = figures(layers[l]);
    std::printf("%-4s covered %.3f  mean cover %.3f", names[l], f.coveredFraction, f.meanCover);
    const auto [baseLo, baseHi] =
        std::minmax_element(altitudes[2 * l].begin(), altitudes[2 * l].end());
    const auto [topLo, topHi] =
        std::minmax_element(altitudes[2 * l + 1].begin(), altitudes[2 * l + 1].end());
    std::printf("  base %.0f to %.0f m  top %.0f to %.0f m", *baseLo, *baseHi, *topLo, *topHi);
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
