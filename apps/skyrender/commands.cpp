#include "commands.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>

#include "cli_args.h"
#include "default_scene.h"
#include "engine/color/ocio_output.h"
#include "engine/core/error.h"
#include "engine/gpu/context.h"
#include "engine/lighting/lighting_state.h"
#include "engine/render/render_files.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "engine/weather/coverage_metrics.h"

namespace sky {
namespace fs = std::filesystem;

const char* usageText() {
  return R"(skyrender - render skies and clouds with skylayers

usage:
  skyrender render [SCENE] [options]   render SCENE (YAML or JSON; the embedded default
                                       scene when absent) into DIR/NAME.exr, .png and .json
  skyrender validate SCENE [--set K=V]  check SCENE and print its effective settings
                                       (defaults filled in) in the same format; the printed
                                       file reproduces the render exactly
  skyrender ephemeris --lat D --lon D --time ISO8601 [--height-m M]
            [--pressure-hpa P] [--temperature-c T]
                                       print sun and moon positions, moon phase and the
                                       key light as JSON (defaults: 0 m, 1010 hPa, 10 C)
  skyrender schema                     print the JSON Schema of scene files
  skyrender devices                    list the Vulkan devices and which one is picked
  skyrender dsc RENDER.exr [--cell PX] [--threshold T]
                                       compare a camera.mode geographic_topdown render's
                                       cloud opacity with its weather map's cover over
                                       PX x PX blocks (default 8): Dice of the blocks
                                       above T (default 0.1; Lu (28)), mean absolute
                                       error, correlation, block count
  skyrender weather FILE [--scene SCENE] [--out DIR] [--set K=V]
                                       the cloud map a GRIB2/NetCDF forecast gives over
                                       the scene's weather.region (default scene: its
                                       region): DIR/STEM.weather.exr (cover_low, cover_mid,
                                       cover_high, type) and .png (low red, mid green,
                                       high blue); prints each layer's covered fraction,
                                       mean cover, altitudes and Dice against the file's
                                       own cloud cover (tcc) when it has one
  skyrender --help                     this text

render options:
  --out DIR            output folder, created if missing (default: out)
  --name NAME          file stem, same as --set output.name=NAME
  --width W            same as --set output.width=W
  --height H           same as --set output.height=H
  --time TIME          same as --set time=TIME: an instant (ISO 8601 with a zone, Z or
                       +HH:MM) or a time-lapse START/END/STEP, e.g.
                       2024-06-21T00:00Z/2024-06-22T00:00Z/15m
                       (a time-lapse writes NAME_0001.exr/.png/.json, ...)
  --set KEY.PATH=VALUE override any scene key; VALUE is read as a YAML scalar or flow
                       sequence (e.g. --set camera.heading=250); repeatable;
                       validated exactly like the file
  --dump-graph FILE    also write the compiled frame graph as Graphviz (dot -Tsvg FILE)
  --debug-output NAME  also write NAME.<name>.exr; repeatable or comma-separated:
                       coefficients, normals (high clouds); transmittance_lut,
                       multiscattering_lut, sky_view_sun_lut, sky_view_moon_lut,
                       aerial_perspective (sky.model physical); cloud_steps,
                       cloud_density_slice, weather_map (with low or mid clouds)
  --gpu NAME|INDEX     Vulkan device by index or name substring (default: a GPU if
                       present, else lavapipe)
  --ocio FILE          OpenColorIO config (default: $OCIO, else configs/ocio/config.ocio)

outputs:
  NAME.exr   scene-linear Rec.709, half float: R,G,B,A (beauty), layers sky.R/G/B
             (clear sky), high_clouds.R/G/B/A (premultiplied, A = coverage) and
             clouds.R/G/B/A/depth (volumetric clouds, premultiplied, A = opacity,
             depth in m); camera.mode geographic_topdown adds weather.cover_low/_mid
  NAME.png   8-bit display image through output.display / output.view, exposure applied
  NAME.json  settings, time, sun, moon and light (as `ephemeris` prints them),
             per-pass GPU milliseconds, total, device name

environment:
  SKY_VALIDATION=1   enable the Vulkan validation layers (messages go to stderr)
  SKY_DATA_DIR       folder holding shaders/ and configs/ (default: the source tree)
  SKY_CACHE_DIR      cache folder for SPIR-V, baked high-cloud textures and cloud noise
                     (default: ~/.cache/skylayers)
  OCIO               OpenColorIO config used when --ocio is absent

exit codes: 0 success, 2 bad input (scene, arguments, files), 1 internal or device error.
Every error is one line on stderr saying what and where.
)";
}

namespace {

std::vector<std::string> overridesFrom(const CliArgs& args) {
  std::vector<std::string> o;
  if (auto v = args.value("--width")) o.push_back("output.width=" + *v);
  if (auto v = args.value("--height")) o.push_back("output.height=" + *v);
  if (auto v = args.value("--name")) o.push_back("output.name=" + *v);
  if (auto v = args.value("--time")) o.push_back("time=" + *v);
  for (const std::string& s : args.values("--set")) o.push_back(s);
  return o;
}

Scene loadScene(const CliArgs& args, bool required) {
  if (args.positional().size() > 1)
    inputError("more than one scene given: '" + args.positional()[1] + "'");
  if (args.positional().empty()) {
    if (required) inputError("no scene given (see --help)");
    return loadSceneText(skyDefaultSceneText(), ConfigFormat::Yaml, "<default scene>",
                         overridesFrom(args));
  }
  return loadSceneFile(args.positional()[0], overridesFrom(args));
}

// "\r[#####.....] text" on stderr: one line that redraws itself.
void drawBar(double fraction, const std::string& text) {
  constexpr int kWidth = 30;
  int filled = std::clamp(static_cast<int>(kWidth * fraction), 0, kWidth);
  std::fprintf(stderr, "\r[%s%s] %s", std::string(filled, '#').c_str(),
               std::string(kWidth - filled, '.').c_str(), text.c_str());
  std::fflush(stderr);
}

// A one-line progress bar on stderr for time-lapses, only when stderr is a terminal (logs and
// tests get the final summary line alone).
class Progress {
public:
  explicit Progress(int64_t count) : mCount(count), mEnabled(count > 1 && isatty(2)) {}
  void show(int64_t index, const IsoTime& time) const {
    if (!mEnabled) return;
    drawBar(static_cast<double>(index) / static_cast<double>(mCount),
            std::to_string(index + 1) + "/" + std::to_string(mCount) + " " + time.format());
  }
  void done() const {
    if (mEnabled) std::fprintf(stderr, "\r\033[K");  // clear the bar's line
  }

private:
  int64_t mCount;
  bool mEnabled;
};

// A number option, strictly: the whole text a finite number within [min, max].
double numberOption(const CliArgs& args, const std::string& option, double min, double max,
                    std::optional<double> fallback) {
  std::optional<std::string> text = args.value(option);
  if (!text) {
    if (!fallback) inputError(option + " is required (see --help)");
    return *fallback;
  }
  double v = 0.0;
  auto [end, ec] = std::from_chars(text->data(), text->data() + text->size(), v);
  if (ec != std::errc() || end != text->data() + text->size() || !std::isfinite(v))
    inputError(option + " '" + *text + "': expected a number");
  if (v < min || v > max) {
    char range[96];
    std::snprintf(range, sizeof range, "[%g, %g]", min, max);
    inputError(option + " " + *text + ": out of range " + range);
  }
  return v;
}

}  // namespace

int ephemerisCommand(const std::vector<std::string>& argv) {
  CliArgs args(argv,
               {"--lat", "--lon", "--time", "--height-m", "--pressure-hpa", "--temperature-c"}, {},
               {});
  if (!args.positional().empty())
    inputError("ephemeris takes no positional arguments: '" + args.positional()[0] + "'");
  // The same lighting model a render uses, for a scene that is only a place and an instant.
  Scene scene;
  scene.camera.latitude = numberOption(args, "--lat", -90, 90, std::nullopt);
  scene.camera.longitude = numberOption(args, "--lon", -180, 180, std::nullopt);
  scene.camera.altitudeM = numberOption(args, "--height-m", -500, 100000, 0.0);
  scene.lighting.pressureHpa = numberOption(args, "--pressure-hpa", 0, 1200, 1010.0);
  scene.lighting.temperatureC = numberOption(args, "--temperature-c", -100, 100, 10.0);
  std::optional<std::string> timeText = args.value("--time");
  if (!timeText) inputError("--time is required (ISO 8601 with a zone, e.g. 2024-06-21T12:00Z)");
  std::string why;
  std::optional<IsoTime> time = IsoTime::parse(*timeText, &why);
  if (!time) inputError("--time '" + *timeText + "' is not a valid time: " + why);
  std::cout << lightingJson(computeLighting(scene, *time)).dump(2) << "\n";
  return 0;
}

// A bar for a high-cloud bake, on a terminal only and only once the bake has taken a
// noticeable time (a quick bake draws nothing); it clears its line when the bake ends.
std::function<void(double)> bakeProgressBar() {
  if (!isatty(2)) return {};
  auto start = std::make_shared<std::chrono::steady_clock::time_point>();
  auto shown = std::make_shared<bool>(false);
  return [start, shown](double fraction) {
    auto now = std::chrono::steady_clock::now();
    if (fraction <= 0.0) *start = now;
    if (fraction >= 1.0) {
      if (*shown) std::fprintf(stderr, "\r\033[K");
      *shown = false;
      return;
    }
    if (now - *start < std::chrono::milliseconds(300)) return;
    *shown = true;
    drawBar(fraction,
            "baking high clouds " + std::to_string(static_cast<int>(fraction * 100)) + "%");
  };
}

int renderCommand(const std::vector<std::string>& argv) {
  CliArgs args(argv,
               {"--out", "--name", "--width", "--height", "--time", "--set", "--dump-graph",
                "--gpu", "--ocio", "--debug-output"},
               {"--set", "--debug-output"}, {});
  Scene scene = loadScene(args, false);
  RenderOptions renderOptions;
  for (const std::string& v : args.values("--debug-output")) {
    // Accepts "--debug-output a,b" as well as repeats.
    size_t start = 0;
    while (start <= v.size()) {
      size_t comma = v.find(',', start);
      if (comma == std::string::npos) comma = v.size();
      renderOptions.debugOutputs.push_back(v.substr(start, comma - start));
      start = comma + 1;
    }
  }
  checkDebugOutputs(scene, renderOptions.debugOutputs);

  // Check everything the user controls before any GPU work, so bad input fails fast.
  std::optional<fs::path> ocioPath;
  if (auto v = args.value("--ocio")) ocioPath = *v;
  OcioOutput ocio = OcioOutput::load(ocioPath);
  ocio.checkDisplayView(scene.output.display, scene.output.view);

  fs::path outDir = args.value("--out").value_or("out");
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec || !fs::is_directory(outDir))
    inputError("--out " + outDir.string() + ": cannot create folder" +
               (ec ? ": " + ec.message() : ""));
  std::optional<fs::path> graphPath;
  if (auto v = args.value("--dump-graph")) graphPath = *v;

  ContextOptions options = ContextOptions::fromEnvironment();
  options.gpu = args.value("--gpu").value_or("");
  Context ctx(options);
  ShaderCompiler compiler;
  Renderer renderer(ctx, compiler);
  renderer.setBakeProgress(bakeProgressBar());

  const int64_t count = scene.time.frameCount();
  Progress progress(count);
  RenderFiles first, last;
  double gpuMs = 0.0;
  for (int64_t i = 0; i < count; ++i) {
    const IsoTime time = scene.time.frame(i);
    progress.show(i, time);
    RenderedFrame frame = renderer.render(scene, time, renderOptions);
    // The graph is the same every frame; the first one is written.
    RenderFiles files =
        writeRenderFiles(outDir, frameStem(scene.output.name, i, count), scene, frame, ocio,
                         ctx.deviceName(), i == 0 ? graphPath : std::nullopt);
    if (i == 0) first = files;
    last = files;
    gpuMs += frame.frame.gpuMs;
  }
  progress.done();

  if (count == 1) {
    std::printf("wrote %s, %s, %s (%dx%d, %.2f ms GPU on %s)\n", first.exr.string().c_str(),
                first.png.string().c_str(), first.report.string().c_str(), scene.output.width,
                scene.output.height, gpuMs, ctx.deviceName().c_str());
  } else {
    std::printf(
        "wrote %lld frames %s ... %s with .exr, .png, .json (%dx%d, %.2f ms GPU per "
        "frame on %s)\n",
        static_cast<long long>(count), first.png.stem().string().c_str(),
        last.png.stem().string().c_str(), scene.output.width, scene.output.height,
        gpuMs / static_cast<double>(count), ctx.deviceName().c_str());
  }
  if (first.graph) std::printf("wrote %s\n", first.graph->string().c_str());
  return 0;
}

int validateCommand(const std::vector<std::string>& argv) {
  CliArgs args(argv, {"--set", "--ocio"}, {"--set"}, {});
  Scene scene = loadScene(args, true);
  // Display and view are names in the OCIO config, so the config takes part in validation.
  std::optional<fs::path> ocioPath;
  if (auto v = args.value("--ocio")) ocioPath = *v;
  OcioOutput::load(ocioPath).checkDisplayView(scene.output.display, scene.output.view);
  std::cout << writeScene(scene, formatForPath(args.positional()[0]));
  return 0;
}

int schemaCommand(const std::vector<std::string>& argv) {
  CliArgs args(argv, {}, {}, {});
  if (!args.positional().empty()) inputError("schema takes no arguments");
  std::cout << sceneJsonSchema();
  return 0;
}

int devicesCommand(const std::vector<std::string>& argv) {
  CliArgs args(argv, {"--gpu"}, {}, {});
  ContextOptions options = ContextOptions::fromEnvironment();
  options.gpu = args.value("--gpu").value_or("");
  Context ctx(options);
  for (const PhysicalDeviceInfo& d : Context::enumerate(ctx.instance()))
    std::printf("%u: %s (Vulkan %u.%u)%s\n", d.index, d.name.c_str(),
                VK_API_VERSION_MAJOR(d.apiVersion), VK_API_VERSION_MINOR(d.apiVersion),
                d.name == ctx.deviceName() ? "  <- picked" : "");
  return 0;
}

int dscCommand(const std::vector<std::string>& argv) {
  CliArgs args(argv, {"--cell", "--threshold"}, {}, {});
  if (args.positional().empty())
    inputError("dsc needs the render's EXR (skyrender dsc RENDER.exr [--cell PX] [--threshold T])");
  if (args.positional().size() > 1)
    inputError("dsc takes one render EXR, got also '" + args.positional()[1] + "'");
  CoverageOptions options;
  const double cell = numberOption(args, "--cell", 1, 4096, options.cell);
  if (cell != std::floor(cell))
    inputError("--cell '" + *args.value("--cell") + "': expected a whole number");
  options.cell = static_cast<int>(cell);
  options.threshold = numberOption(args, "--threshold", 0, 1, options.threshold);
  if (options.threshold >= 1.0)
    inputError("--threshold " + *args.value("--threshold") +
               ": must be below 1 (no block could be cloudy)");
  const RenderCoverage render = readRenderCoverage(args.positional()[0]);
  const CoverageMetrics m =
      compareCoverage(render.opacity, render.cover, render.width, render.height, options);
  std::printf("dsc %.3f\nmae %.3f\ncorrelation %.3f\nblocks %llu\n", m.dice, m.meanAbsoluteError,
              m.correlation, static_cast<unsigned long long>(m.blocks));
  return 0;
}

}  // namespace sky
