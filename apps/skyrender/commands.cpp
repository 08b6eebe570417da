#include "commands.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>

#include "apps/common/contact_sheet.h"
#include "apps/common/debug_outputs.h"
#include "apps/common/default_scene.h"
#include "apps/common/stop_signals.h"
#include "cli_args.h"
#include "command_support.h"
#include "engine/color/ocio_output.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/paths.h"
#include "engine/core/sha256.h"
#include "engine/dataset/dataset_manifest.h"
#include "engine/dataset/dataset_spec.h"
#include "engine/gpu/context.h"
#include "engine/io/png.h"
#include "engine/lighting/lighting_state.h"
#include "engine/render/render_files.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "engine/weather/coverage_metrics.h"

namespace sky {
namespace fs = std::filesystem;

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
  args.expectPositionals(required ? 1 : 0, 1, "one scene file");
  if (args.positional().empty()) {
    return loadSceneText(skyDefaultSceneText(), ConfigFormat::Yaml, "<default scene>",
                         overridesFrom(args));
  }
  return loadSceneFile(args.positional()[0], overridesFrom(args));
}

// Runs `check`, which may raise an error about a scene key found only after loading
// ("output.display: unknown OCIO display ..."), and says where that key was written: the
// file, line and column, or the --set that gave it (issue 31, 12).
void atSceneKey(const CliArgs& args, const std::function<void()>& check) {
  try {
    check();
  } catch (const Error& e) {
    const std::string what = e.what();
    const size_t colon = what.find(": ");
    const std::string key = what.substr(0, colon);
    if (colon == std::string::npos || key.find_first_of(" /") != std::string::npos) throw;
    const fs::path file = args.positional().empty() ? fs::path() : fs::path(args.positional()[0]);
    const std::string where = sceneKeySource(file, overridesFrom(args), key);
    if (where.empty()) throw;
    throw Error(e.kind(), (where.rfind("--set ", 0) == 0 ? "--set " : where + ": ") + what);
  }
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
    if (!fallback)
      inputError(option + " is required (see skyrender " + args.command() + " --help)");
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

// The frames a shard of a time-lapse writes, [begin, end), and the first it draws: with
// temporal reuse a frame is made from the ones before it, so a shard that starts inside the
// sequence first draws kShardWarmupCycles cycles of the march's blocks unwritten (a cycle,
// block^2 frames, marches every pixel once), and its first frame then holds the history an
// unsharded run holds there (docs/datasets.md, "Sharding a time-lapse").
constexpr int64_t kShardWarmupCycles = 2;
struct ShardFrames {
  int64_t warmFrom = 0, begin = 0, end = 0;
};
ShardFrames shardFrames(const Scene& scene, const Shard& shard, int64_t count) {
  ShardFrames f;
  f.begin = (shard.index - 1) * count / shard.count;
  f.end = shard.index * count / shard.count;
  int64_t warm = 0;
  if (scene.clouds.temporal.mode == CloudTemporalMode::On)
    warm = kShardWarmupCycles * int64_t(scene.clouds.temporal.block) * scene.clouds.temporal.block;
  f.warmFrom = std::max<int64_t>(0, f.begin - warm);
  return f;
}

// A sharded time-lapse's manifest line for frame `index`: what skyrender merge joins.
nlohmann::ordered_json frameManifestLine(int64_t index, int64_t count, const std::string& sceneSum,
                                         const IsoTime& time, const RenderFiles& files) {
  nlohmann::ordered_json f;
  for (const auto& [kind, path] :
       {std::pair<const char*, const fs::path*>{"exr", &files.exr}, {"png", &files.png},
        {"report", &files.report}})
    f[kind] = {{"name", path->filename().string()}, {"sha256", sha256File(*path)}};
  return {{"index", index}, {"count", count}, {"spec", sceneSum}, {"time", time.format()},
          {"files", f}};
}

}  // namespace

// "\r[#####.....] text" on stderr: one line that redraws itself.
void drawBar(double fraction, const std::string& text) {
  constexpr int kWidth = 30;
  int filled = std::clamp(static_cast<int>(kWidth * fraction), 0, kWidth);
  std::fprintf(stderr, "\r[%s%s] %s", std::string(filled, '#').c_str(),
               std::string(kWidth - filled, '.').c_str(), text.c_str());
  std::fflush(stderr);
}

// The Vulkan context options of the environment (SKY_VALIDATION, ...) with the device the
// command's --gpu picks ("" the default one).
ContextOptions contextOptions(const CliArgs& args) {
  ContextOptions options = ContextOptions::fromEnvironment();
  options.gpu = args.value("--gpu").value_or("");
  return options;
}

// Once per process: a cache that cannot be written makes every run bake and compile again.
// Called before the work (a folder that takes no probe) and after it (a write that failed on
// the way, such as a full disk).
void warnIfCacheUnwritable() {
  static bool warned = false;
  const CacheStatus cache = cacheStatus();
  if (cache.writable || warned) return;
  warned = true;
  std::fprintf(stderr,
               "warning: the cache folder %s cannot be written (%s): baked textures and "
               "compiled shaders are not kept, so the next run makes them again (set "
               "SKY_CACHE_DIR to a writable folder)\n",
               cache.folder.string().c_str(), cache.reason.c_str());
}

int ephemerisCommand(const std::vector<std::string>& argv) {
  CliArgs args("ephemeris", argv,
               {"--lat", "--lon", "--time", "--height-m", "--pressure-hpa", "--temperature-c"}, {},
               {});
  args.expectPositionals(0, 0, "");
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
  // First of all: a SIGINT or SIGTERM from here on stops the run cleanly (whole frames kept,
  // a folder it made and wrote nothing into removed, exit 128 + the signal). Installed after
  // the output folder was made, a signal in the first 0.7 s (the device and the pipelines)
  // killed the process with no word and left the empty folder (issue 31, 8).
  const StopSignals stop;
  CliArgs args("render", argv,
               {"--out", "--name", "--width", "--height", "--time", "--set", "--dump-graph",
                "--gpu", "--ocio", "--debug-output", "--debug-passes", "--shard"},
               {"--set", "--debug-output"}, {"--debug-passes"});
  Scene scene = loadScene(args, false);
  const Shard shard = args.value("--shard") ? parseShard(*args.value("--shard"), "--shard") : Shard{};
  if (!shard.all() && !scene.time.isRange())
    inputError("--shard " + shard.text() +
               ": the scene's time is one instant; a shard takes a share of a time-lapse's "
               "frames (time START/END/STEP)");
  const DebugRequest debug = parseDebugOutputs(args.values("--debug-output"));
  RenderOptions renderOptions;
  renderOptions.debugOutputs = debug.names;
  renderOptions.allDebugOutputs = args.flag("--debug-passes");
  if (debug.list) {
    // The images of the scene's first frame, each of which --debug-output can name.
    warnIfCacheUnwritable();
    Context ctx(contextOptions(args));
    ShaderCompiler compiler;
    Renderer renderer(ctx, compiler);
    std::fputs(debugImageTable(renderer.debugImages(scene, scene.time.start)).c_str(), stdout);
    return 0;
  }

  // Check everything the user controls before any GPU work, so bad input fails fast.
  std::optional<fs::path> ocioPath;
  if (auto v = args.value("--ocio")) ocioPath = *v;
  OcioOutput ocio = OcioOutput::load(ocioPath);
  atSceneKey(args, [&] { ocio.checkDisplayView(scene.output.display, scene.output.view); });

  // --dump-graph names a file whose folder exists: checked now, not after the frame was
  // rendered and written (issue 31, 3).
  std::optional<fs::path> graphPath;
  if (auto v = args.value("--dump-graph")) {
    graphPath = *v;
    std::error_code ec;
    if (fs::is_directory(*graphPath, ec))
      inputError("--dump-graph " + *v + ": is a directory; give a file name (out/graph.dot)");
    const fs::path parent = graphPath->parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec))
      inputError("--dump-graph " + *v + ": the folder " + parent.string() + " does not exist");
  }

  // Removed again, if the run made it, unless a frame was written into it.
  OutputFolder folder(args.value("--out").value_or("out"), "--out");
  const fs::path& outDir = folder.path();
  warnIfCacheUnwritable();

  Context ctx(contextOptions(args));
  ShaderCompiler compiler;
  Renderer renderer(ctx, compiler);
  renderer.setBakeProgress(bakeProgressBar());

  const int64_t count = scene.time.frameCount();
  // A shard of a time-lapse: a contiguous run of its frames (each frame of a sequence may
  // reuse the ones before it), with a manifest of what it wrote for `skyrender merge`.
  const ShardFrames frames = shardFrames(scene, shard, count);
  std::optional<ManifestWriter> manifest;
  if (!shard.all()) manifest.emplace(manifestPath(outDir, shard));
  const std::string sceneSum = shard.all() ? std::string() : sha256Hex(writeScene(scene, ConfigFormat::Json));
  Progress progress(frames.end - frames.begin);
  RenderFiles first, last;
  ExposureMeter exposure;  // carries a histogram exposure's adaptation from frame to frame
  double gpuMs = 0.0;
  int64_t written = 0;
  for (int64_t i = frames.warmFrom; i < frames.end && !stop.signal(); ++i) {
    const IsoTime time = scene.time.frame(i);
    if (i >= frames.begin) progress.show(i - frames.begin, time);
    RenderedFrame frame;
    renderOptions.sequenceFrame = static_cast<uint64_t>(i);
    try {
      frame = renderer.render(scene, time, renderOptions);
    } catch (const UnknownImageName& e) {
      debugOutputError(e, debug, "--debug-output");
    }
    if (i < frames.begin) {
      // A warm-up frame: drawn for the history and the exposure it leaves, not written.
      exposure.expose(scene, frame, time);
      continue;
    }
    const std::string stem = frameStem(scene.output.name, i, count, scene.time.isRange());
    std::optional<DisplayTile> sheet;
    if (renderOptions.allDebugOutputs) {
      sheet = contactSheet(frame.debug, stem + "  " + time.format() + "  " + ctx.deviceName());
      packDebugLayers(frame);
    }
    nameDebugImagesAsAsked(frame, debug);
    // The graph is the same every frame; the first one is written.
    RenderFiles files = writeRenderFiles(outDir, stem, scene, frame,
                                         exposure.expose(scene, frame, time), ocio,
                                         ctx.deviceName(),
                                         i == frames.begin ? graphPath : std::nullopt);
    if (sheet) {
      const fs::path path = outDir / (stem + ".passes.png");
      writePngCodes(path, static_cast<int>(sheet->width), static_cast<int>(sheet->height),
                    sheet->rgba);
      if (i == frames.begin)
        std::printf("wrote %s (every image of the frame)\n", path.string().c_str());
    }
    if (manifest) manifest->append(frameManifestLine(i, count, sceneSum, time, files));
    folder.keep();
    if (i == frames.begin) first = files;
    last = files;
    gpuMs += frame.frame.gpuMs;
    ++written;
  }
  progress.done();
  warnIfCacheUnwritable();  // a cache write that failed during the frames
  const int64_t mine = frames.end - frames.begin;
  if (const int signal = stop.signal()) {
    std::fprintf(stderr, "interrupted after %lld of %lld frames (%s)\n",
                 static_cast<long long>(written), static_cast<long long>(mine),
                 signal == SIGINT ? "SIGINT" : "SIGTERM");
    return 128 + signal;
  }

  if (count == 1) {
    std::printf("wrote %s, %s, %s (%dx%d, %.2f ms GPU on %s)\n", first.exr.string().c_str(),
                first.png.string().c_str(), first.report.string().c_str(), scene.output.width,
                scene.output.height, gpuMs, ctx.deviceName().c_str());
  } else {
    std::printf(
        "wrote %lld frames %s ... %s with .exr, .png, .json (%dx%d, %.2f ms GPU per "
        "frame on %s)%s\n",
        static_cast<long long>(mine), first.png.stem().string().c_str(),
        last.png.stem().string().c_str(), scene.output.width, scene.output.height,
        gpuMs / static_cast<double>(std::max<int64_t>(mine, 1)), ctx.deviceName().c_str(),
        shard.all() ? ""
                    : (" (shard " + shard.text() + ", " + std::to_string(frames.begin - frames.warmFrom) +
                       " warm-up frames)").c_str());
  }
  if (first.graph) std::printf("wrote %s\n", first.graph->string().c_str());
  return 0;
}

namespace {

// --box E0,N0,U0,E1,N1,U1: the minimum and maximum corners in metres east, north and up of
// the camera.
CloudVolumeBox boxOption(const std::string& text) {
  const std::string expected =
      "--box '" + text +
      "': expected six numbers E0,N0,U0,E1,N1,U1 (metres east, north and up of the camera: "
      "the minimum corner, then the maximum)";
  double v[6];
  size_t start = 0;
  for (int i = 0; i < 6; ++i) {
    size_t end = text.find(',', start);
    if ((end == std::string::npos) != (i == 5)) inputError(expected);
    if (end == std::string::npos) end = text.size();
    const char* first = text.data() + start;
    const char* last = text.data() + end;
    auto [stop, ec] = std::from_chars(first, last, v[i]);
    if (ec != std::errc() || stop != last || !std::isfinite(v[i])) inputError(expected);
    start = end + 1;
  }
  const char* axes[3] = {"east", "north", "up"};
  for (int a = 0; a < 3; ++a)
    if (v[a + 3] <= v[a]) {
      char why[160];
      std::snprintf(why, sizeof why,
                    "--box '%s': the maximum %s (%g) must lie above the minimum (%g)", text.c_str(),
                    axes[a], v[a + 3], v[a]);
      inputError(why);
    }
  return {glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5])};
}

// A number given as `option`'s value, strictly: the whole text a finite number within
// [min, max] (numberOption for a repeated option's each value).
double numberText(const std::string& option, const std::string& text, double min, double max) {
  double v = 0.0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    inputError(option + " '" + text + "': expected a number");
  if (v < min || v > max) {
    char range[96];
    std::snprintf(range, sizeof range, "[%g, %g]", min, max);
    inputError(option + " " + text + ": out of range " + range);
  }
  return v;
}

}  // namespace

int exportVolumeCommand(const std::vector<std::string>& argv) {
  CliArgs args(
      "export-volume", argv,
      {"--box", "--voxel-m", "--lod", "--out", "--width", "--height", "--time", "--set", "--gpu"},
      {"--set", "--box", "--voxel-m"}, {});
  Scene scene = loadScene(args, false);
  if (scene.time.frameCount() != 1)
    inputError("export-volume: the scene's time is a time-lapse; give one instant (--time)");
  // Several boxes are the parts of one field, nested, finest first, each with its own voxel
  // (one --voxel-m for all, or one per --box in order).
  const std::vector<std::string>& boxes = args.values("--box");
  const std::vector<std::string>& voxels = args.values("--voxel-m");
  if (voxels.size() > 1 && voxels.size() != boxes.size())
    inputError("--voxel-m is given " + std::to_string(voxels.size()) + " times for " +
               std::to_string(boxes.size()) +
               " --box: give one voxel for every box, or one for each box in order");
  std::vector<double> voxelM;
  for (const std::string& v : voxels) voxelM.push_back(numberText("--voxel-m", v, 0.1, 10000));
  CloudVolumeRequest request;
  request.defaultVoxelM = voxelM.empty() ? 50.0 : voxelM.front();
  for (size_t k = 0; k < boxes.size(); ++k)
    request.parts.push_back(
        {boxOption(boxes[k]), voxelM.empty() ? 50.0 : voxelM[std::min(k, voxelM.size() - 1)]});
  if (auto v = args.value("--lod")) {
    const std::optional<CloudVolumeLod> lod = enumValue<CloudVolumeLod>(*v);
    if (!lod) inputError("--lod '" + *v + "': expected full or view");
    request.lod = *lod;
  }
  std::optional<std::string> out = args.value("--out");
  if (!out) inputError("--out FILE.vdb is required (see skyrender export-volume --help)");
  const fs::path outPath = *out;
  if (outPath.extension() != ".vdb") inputError("--out " + *out + ": expected a .vdb file");
  const fs::path folder = outPath.parent_path().empty() ? fs::path(".") : outPath.parent_path();
  if (!fs::is_directory(folder))
    inputError("--out " + *out + ": the folder " + folder.string() + " does not exist");
  // The grids' sizes and the boxes' nesting are checked before any GPU work.
  for (const CloudVolumePart& part : request.parts) cloudVolumeGrid(part.box, part.voxelM);
  checkCloudVolumeParts(request.parts);
  warnIfCacheUnwritable();

  Context ctx(contextOptions(args));
  ShaderCompiler compiler;
  Renderer renderer(ctx, compiler);
  const std::vector<CloudVolume> volumes =
      renderer.exportCloudVolumes(scene, scene.time.start, request);
  writeCloudVolumes(outPath, volumes);
  for (const CloudVolume& volume : volumes) {
    const VdbGrid& g = volume.extinction;
    float maxExtinction = 0.0f;
    size_t cloudy = 0;
    for (float e : g.values) {
      maxExtinction = std::max(maxExtinction, e);
      cloudy += e > 0.0f;
    }
    const std::string grid = volumes.size() > 1 ? " grid " + g.name : "";
    std::printf("wrote %s%s (%ux%ux%u voxels of %g m, %zu cloudy, extinction up to %.4g /m)\n",
                outPath.string().c_str(), grid.c_str(), g.size.x, g.size.y, g.size.z, g.voxelSize,
                cloudy, maxExtinction);
  }
  return 0;
}

int validateCommand(const std::vector<std::string>& argv) {
  CliArgs args("validate", argv, {"--set", "--ocio"}, {"--set"}, {});
  Scene scene = loadScene(args, true);
  // Display and view are names in the OCIO config, so the config takes part in validation.
  std::optional<fs::path> ocioPath;
  if (auto v = args.value("--ocio")) ocioPath = *v;
  const OcioOutput ocio = OcioOutput::load(ocioPath);
  atSceneKey(args, [&] { ocio.checkDisplayView(scene.output.display, scene.output.view); });
  // The files a render would read, so validate passes no scene that render rejects for a
  // missing one (issue 31, 11).
  for (const SceneInputFile& f : sceneInputFiles(scene))
    atSceneKey(args, [&] {
      if (const std::string why = notARegularFile(f.path); !why.empty())
        inputError(std::string(f.key) + ": " + f.written + ": " + why + " (" + f.path.string() + ")");
      if (::access(f.path.c_str(), R_OK) != 0)
        inputError(std::string(f.key) + ": " + f.written + ": cannot be read: " +
                   std::strerror(errno) + " (" + f.path.string() + ")");
    });
  // Paths printed resolved: the printed scene renders the same from any folder.
  std::cout << writeScene(scene.withAbsolutePaths(), formatForPath(args.positional()[0]));
  return 0;
}

int schemaCommand(const std::vector<std::string>& argv) {
  CliArgs args("schema", argv, {}, {}, {"--dataset"});
  args.expectPositionals(0, 0, "");
  std::cout << (args.flag("--dataset") ? datasetJsonSchema() : sceneJsonSchema());
  return 0;
}

int devicesCommand(const std::vector<std::string>& argv) {
  CliArgs args("devices", argv, {"--gpu"}, {}, {});
  args.expectPositionals(0, 0, "");
  Context ctx(contextOptions(args));
  for (const PhysicalDeviceInfo& d : Context::enumerate(ctx.instance()))
    std::printf("%u: %s (Vulkan %u.%u)%s\n", d.index, d.name.c_str(),
                VK_API_VERSION_MAJOR(d.apiVersion), VK_API_VERSION_MINOR(d.apiVersion),
                d.name == ctx.deviceName() ? "  <- picked" : "");
  return 0;
}

int dscCommand(const std::vector<std::string>& argv) {
  CliArgs args("dsc", argv, {"--cell", "--threshold"}, {}, {});
  args.expectPositionals(1, 1, "one render EXR");
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
  // A correlation over fewer than two blocks along a side says nothing (one block: 0).
  const int across = (render.width + options.cell - 1) / options.cell;
  const int down = (render.height + options.cell - 1) / options.cell;
  if (across < 2 || down < 2)
    inputError(
        "--cell " + std::to_string(options.cell) + ": the " + std::to_string(render.width) + "x" +
        std::to_string(render.height) + " render holds " + std::to_string(across) + " x " +
        std::to_string(down) + " blocks; the comparison needs at least 2 x 2 (use --cell " +
        std::to_string(std::max(1, (std::min(render.width, render.height) + 1) / 2)) + " or less)");
  const CoverageMetrics m =
      compareCoverage(render.opacity, render.cover, render.width, render.height, options);
  std::printf("dsc %.3f\nmae %.3f\ncorrelation %.3f\nblocks %llu\n", m.dice, m.meanAbsoluteError,
              m.correlation, static_cast<unsigned long long>(m.blocks));
  return 0;
}

}  // namespace sky
