// skyrender dataset SPEC --out DIR [--shard I/N] and skyrender merge DIR...: many samples, each
// reproducible from (seed, index), written atomically with a manifest line each, resumable
// after a kill, shardable over processes or a cluster (docs/datasets.md).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/common/default_scene.h"
#include "apps/common/stop_signals.h"
#include "cli_args.h"
#include "command_support.h"
#include "commands.h"
#include "engine/color/ocio_output.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/sha256.h"
#include "engine/dataset/dataset_manifest.h"
#include "engine/dataset/dataset_spec.h"
#include "engine/io/png.h"
#include "engine/render/exposure.h"
#include "engine/render/render_files.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"

namespace sky {
namespace fs = std::filesystem;
namespace {

using Json = nlohmann::ordered_json;

// What a sample's line says of its scene: the keys a spec can vary, as drawn.
Json sceneParameters(const Scene& s) {
  Json weather = {{"source", enumName(s.weather.source)}};
  if (s.weather.source == WeatherMapSource::File) {
    weather["file"] = s.weather.file;
  } else if (s.weather.source == WeatherMapSource::Procedural) {
    weather["cover_low"] = s.weather.coverLow;
    weather["cover_mid"] = s.weather.coverMid;
    weather["cloud_type"] = enumName(s.weather.cloudType);
    weather["seed"] = s.weather.seed;
  }
  return {{"time", s.time.start.format()},
          {"camera",
           {{"latitude", s.camera.latitude},
            {"longitude", s.camera.longitude},
            {"altitude_m", s.camera.altitudeM},
            {"heading", s.camera.heading},
            {"pitch", s.camera.pitch},
            {"vertical_fov", s.camera.verticalFov}}},
          {"weather", weather}};
}

Json fileEntry(const fs::path& path) {
  std::error_code ec;
  return {{"name", path.filename().string()},
          {"sha256", sha256File(path)},
          {"bytes", static_cast<uint64_t>(fs::file_size(path, ec))}};
}

// A sample's scene file must load back to the very scene: it is how a user renders the
// sample again; and loading it checks the scene as a file would be (its cross-key rules).
void checkSampleScene(const Scene& s, int64_t index) {
  Scene back =
      loadSceneText(writeScene(s, ConfigFormat::Yaml), ConfigFormat::Yaml, s.output.name + ".yaml");
  back.baseDir = s.baseDir;  // not a key: the paths are absolute already
  if (back != s)
    internalError("dataset: sample " + std::to_string(index) + "'s scene does not read back");
}

std::string duration(double seconds) {
  char text[32];
  if (seconds < 90.0)
    std::snprintf(text, sizeof text, "%.0fs", seconds);
  else if (seconds < 5400.0)
    std::snprintf(text, sizeof text, "%.0fm%02.0fs", std::floor(seconds / 60.0),
                  std::fmod(seconds, 60.0));
  else
    std::snprintf(text, sizeof text, "%.1fh", seconds / 3600.0);
  return text;
}

}  // namespace

int datasetCommand(const std::vector<std::string>& argv) {
  // First: a SIGINT or SIGTERM from here on finishes the sample being made, then stops.
  const StopSignals stop;
  CliArgs args("dataset", argv, {"--out", "--shard", "--gpu", "--ocio"}, {}, {});
  args.expectPositionals(1, 1, "one dataset spec (YAML or JSON)");
  const fs::path specPath = args.positional()[0];
  const DatasetSpec spec = loadDatasetSpec(specPath);
  const Scene base = datasetBaseScene(
      spec, loadSceneText(skyDefaultSceneText(), ConfigFormat::Yaml, "<default scene>"));
  const Shard shard = args.value("--shard") ? parseShard(*args.value("--shard"), "--shard") : Shard{};
  std::optional<fs::path> ocioPath;
  if (auto v = args.value("--ocio")) ocioPath = *v;
  const OcioOutput ocio = OcioOutput::load(ocioPath);
  ocio.checkDisplayView(base.output.display, base.output.view);
  const std::string specSum = datasetSpecChecksum(spec, base);
  // Up to a thousand of this shard's scenes are checked before any is drawn (a draw a scene
  // refuses, a range the spec allows that the base scene's other keys do not, fails now, not
  // hours in), and each again just before it is drawn (ten million checks up front would
  // take hours of their own).
  int64_t checked = 0;
  for (int64_t k = 0; k < spec.count && checked < 1000; ++k)
    if (shard.takes(k)) {
      checkSampleScene(datasetSampleScene(spec, base, k), k);
      ++checked;
    }

  OutputFolder folder(args.value("--out").value_or("out"), "--out");
  const fs::path& out = folder.path();
  // What is done already: the lines of every manifest in the folder (this shard's, other
  // shards', a merged one). A line of another spec means the folder is another dataset's.
  std::set<int64_t> done;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(out, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("manifest", 0) != 0 || e.path().extension() != ".jsonl") continue;
    const ManifestLines m = readManifest(e.path());
    for (size_t i = 0; i < m.lines.size(); ++i) {
      if (m.lines[i].value("spec", std::string()) != specSum)
        inputError(e.path().string() + ":" + std::to_string(m.lineNumbers[i]) +
                   ": --out holds samples of another dataset spec; give another folder");
      done.insert(m.lines[i]["index"].get<int64_t>());
    }
  }
  std::vector<int64_t> todo;
  int64_t mine = 0;
  for (int64_t k = 0; k < spec.count; ++k)
    if (shard.takes(k)) {
      ++mine;
      if (!done.count(k)) todo.push_back(k);
    }
  // Opened at the first finished sample: a run that fails before one leaves no empty
  // manifest behind (and a folder it made is removed again).
  std::optional<ManifestWriter> manifest;
  warnIfCacheUnwritable();

  // The device only when there is something to draw: a finished dataset run again says so
  // at once.
  std::optional<Context> ctx;
  ShaderCompiler compiler;
  std::optional<Renderer> renderer;
  if (!todo.empty()) {
    ctx.emplace(contextOptions(args));
    renderer.emplace(*ctx, compiler);
    renderer->setBakeProgress(bakeProgressBar());
  }
  const bool bar = isatty(2) && !todo.empty();
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  int64_t rendered = 0;
  for (int64_t k : todo) {
    if (stop.signal()) break;
    const Scene scene = datasetSampleScene(spec, base, k);
    checkSampleScene(scene, k);
    if (bar) {
      const double eta = rendered > 0 ? elapsed() / double(rendered) * double(todo.size() - rendered) : 0.0;
      drawBar(double(rendered) / double(todo.size()),
              std::to_string(rendered + 1) + "/" + std::to_string(todo.size()) + " " +
                  scene.output.name + (rendered > 0 ? "  eta " + duration(eta) : std::string()));
    }
    // Whatever the process drew before: sample k comes out the same in any run.
    renderer->startAfresh();
    RenderedFrame frame = renderer->render(scene, scene.time.start, RenderOptions{});
    ExposureMeter meter;
    const FrameExposure exposure = meter.expose(scene, frame, scene.time.start);

    const fs::path exr = out / (scene.output.name + ".exr");
    const fs::path png = out / (scene.output.name + ".png");
    const fs::path yaml = out / (scene.output.name + ".yaml");
    LayeredImage image = frame.image;
    image.attributes["skylayers:exposure_ev"] = std::to_string(exposure.ev);
    image.attributes["skylayers:scene"] = yaml.filename().string();
    if (frame.perception) {
      image.attributes["skylayers:visibility_m"] = std::to_string(frame.perception->visibilityM);
      image.attributes["skylayers:sun_visible"] = std::to_string(frame.perception->sunVisible);
    }
    {
      AtomicFileSet set;
      set.stage(exr, [&](const fs::path& tmp) { writeExr(tmp, image); });
      if (spec.output.png) {
        const std::vector<float> display = displayPixels(frame, scene, exposure, ocio);
        set.stage(png, [&](const fs::path& tmp) {
          writePng8(tmp, frame.image.width, frame.image.height, display,
                    scene.output.dither ? PngQuantize::Dither : PngQuantize::Nearest);
        });
      }
      set.stage(yaml,
                [&](const fs::path& tmp) { writeFileAtomic(tmp, writeScene(scene, ConfigFormat::Yaml)); });
      set.commit();
    }
    Json line;
    line["index"] = k;
    line["count"] = spec.count;
    line["seed"] = spec.seed;
    line["spec"] = specSum;
    line["scene"] = sceneParameters(scene);
    line["sun_elevation_deg"] = frame.lighting.sun.elevationDeg;
    line["moon_elevation_deg"] = frame.lighting.moon.elevationDeg;
    line["cover"] = {{"low", frame.localWeather.low},
                     {"mid", frame.localWeather.mid},
                     {"high", frame.localWeather.high}};
    if (const std::optional<PerceptionSummary>& p = frame.perception) {
      Json labels;
      for (int c = 0; c < PERCEPTION_LABEL_COUNT; ++c)
        labels[perceptionLabelName(c)] = p->labelShares[size_t(c)];
      line["labels"] = labels;
      line["visibility_m"] = p->visibilityM;
      line["sun_visible"] = p->sunVisible;
    }
    Json files = {{"exr", fileEntry(exr)}};
    if (spec.output.png) files["png"] = fileEntry(png);
    files["scene"] = fileEntry(yaml);
    line["files"] = files;
    // The line last: the sample is complete once it is there.
    if (!manifest) manifest.emplace(manifestPath(out, shard));
    manifest->append(line);
    folder.keep();
    ++rendered;
  }
  if (bar) std::fprintf(stderr, "\r\033[K");
  warnIfCacheUnwritable();
  const double seconds = elapsed();
  const std::string where = shard.all() ? std::string() : " (shard " + shard.text() + ")";
  if (const int signal = stop.signal()) {
    std::fprintf(stderr,
                 "interrupted after %lld of %lld samples%s (%s); run the same command again "
                 "to go on\n",
                 static_cast<long long>(rendered), static_cast<long long>(todo.size()),
                 where.c_str(), signal == SIGINT ? "SIGINT" : "SIGTERM");
    return 128 + signal;
  }
  const std::string device =
      ctx ? " on " + ctx->deviceName() : std::string(", nothing left to draw");
  std::printf("dataset %s%s: %lld samples, %lld rendered, %lld already there, %.1f s (%.2f s a "
              "sample)%s; manifest %s\n",
              out.string().c_str(), where.c_str(), static_cast<long long>(mine),
              static_cast<long long>(rendered), static_cast<long long>(mine - rendered), seconds,
              rendered > 0 ? seconds / double(rendered) : 0.0, device.c_str(),
              manifestPath(out, shard).string().c_str());
  return 0;
}

int mergeCommand(const std::vector<std::string>& argv) {
  CliArgs args("merge", argv, {}, {}, {});
  if (args.positional().empty())
    inputError("merge needs the dataset's folders (see skyrender merge --help)");
  std::vector<fs::path> dirs(args.positional().begin(), args.positional().end());
  const MergeResult r = mergeManifests(dirs);
  if (r.manifests.empty())
    inputError(dirs[0].string() + ": no shard manifest (manifest.I-of-N.jsonl) to merge");
  std::string text;
  Json labels = Json::object();
  for (const auto& [index, line] : r.samples) {
    text += line.dump() + "\n";
    if (line.contains("labels") && line["labels"].is_object())
      for (const auto& [name, share] : line["labels"].items())
        if (share.is_number())
          labels[name] = labels.value(name, 0.0) + share.get<double>() / double(r.samples.size());
  }
  std::vector<int64_t> twice;
  for (const auto& [index, n] : r.duplicates) twice.push_back(index);
  Json manifests = Json::array();
  for (const fs::path& m : r.manifests) manifests.push_back(m.string());
  Json summary = {{"count", r.expected},
                  {"samples", r.samples.size()},
                  {"missing", r.missing},
                  {"present_twice", twice},
                  {"label_shares", labels},
                  {"manifests", manifests}};
  AtomicFileSet set;
  set.stage(dirs[0] / "manifest.jsonl", [&](const fs::path& tmp) { writeFileAtomic(tmp, text); });
  set.stage(dirs[0] / "dataset.json",
            [&](const fs::path& tmp) { writeFileAtomic(tmp, summary.dump(2) + "\n"); });
  set.commit();
  std::printf("merged %zu manifests into %s: %zu of %lld samples\n", r.manifests.size(),
              (dirs[0] / "manifest.jsonl").string().c_str(), r.samples.size(),
              static_cast<long long>(r.expected));
  bool complete = true;
  if (!r.missing.empty()) {
    std::fprintf(stderr, "missing %zu samples: %s\n", r.missing.size(),
                 indexRanges(r.missing).c_str());
    complete = false;
  }
  if (!twice.empty()) {
    std::fprintf(stderr, "present twice: %zu samples: %s\n", twice.size(),
                 indexRanges(twice).c_str());
    complete = false;
  }
  // 3: the dataset is not whole (a shard to run again); 2 stays bad input.
  return complete ? 0 : 3;
}

}  // namespace sky
