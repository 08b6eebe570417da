// skybench: the benchmark harness's frame server. benchmarks/run.py drives it; a person rarely
// runs it by hand. It reads one JSON request per line on stdin and answers each with one JSON
// line on stdout, so the driver can keep a build's GPU context, pipelines and caches warm
// across cases and alternate frame by frame between two variants or two builds (compare
// mode) without either paying the other's start-up. benchmarks/README.md has the protocol:
//
//   {"op":"open","case":"a","scene":"configs/default.yaml","set":["k=v"],"width":640,
//    "height":360,"heading_deg_per_frame":0.2,"seconds_per_frame":0.1,"first_frame":0,
//    "views":4,"views_mode":"one_frame"}   (views: a rig of N cameras 360/N degrees apart,
//                                           in one frame graph or as N separate renders)
//   {"op":"frame","case":"a"}      renders the case's next frame: timings per pass
//   {"op":"quality","case":"a","reference":"r"}   PSNR and max error of the display images
//   {"op":"save","case":"a","png":"out.png"}      the last frame's display image
//   {"op":"close","case":"a"}
//   {"op":"empty","width":1280,"height":720,"frames":5}   an empty full-screen pass, timed
//   {"op":"quit"}
//
// Each case has its own Renderer (its own temporal history); all share one Vulkan context,
// shader compiler and OCIO config. A bad request is answered {"ok":false,"error":"..."} and
// the server goes on; only a device error ends it (exit 1).
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/color/ocio_output.h"
#include "engine/core/error.h"
#include "engine/core/paths.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/context.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/pass_context.h"
#include "engine/io/image_metrics.h"
#include "engine/io/png.h"
#include "engine/render/exposure.h"
#include "engine/render/render_files.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "shaders/common/empty_pass_shared.h"

namespace sky {
namespace {

using Json = nlohmann::ordered_json;

// One benchmark case: a scene, a camera path and the renderer that walks it.
struct Case {
  Scene scene;
  std::unique_ptr<Renderer> renderer;
  ExposureMeter exposure;
  double headingDegPerFrame = 0.0;  // the camera pans by this much each frame
  double secondsPerFrame = 0.0;     // and the scene's time advances by this much
  int64_t next = 0;                 // the frame the next "frame" request renders
  int views = 1;                    // cameras in a rig, 360 / views degrees apart
  bool oneFrame = true;             // the views in one frame graph, or rendered one by one
  std::vector<float> display;       // the last frame's display-referred RGBA
  bool quantized = false;           // display came as 8-bit codes (the GPU display path)
  int width = 0, height = 0;
};

double elapsedMs(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
      .count();
}

class Server {
public:
  explicit Server(const ContextOptions& options) : mCtx(options), mOcio(OcioOutput::load()) {}

  Json handle(const Json& request) {
    const std::string op = request.value("op", "");
    if (op == "open") return open(request);
    if (op == "frame") return frame(caseOf(request, "case"));
    if (op == "quality") return quality(caseOf(request, "case"), caseOf(request, "reference"));
    if (op == "save") return save(caseOf(request, "case"), request);
    if (op == "close") {
      mCases.erase(request.value("case", ""));
      return {{"ok", true}};
    }
    if (op == "empty") return empty(request);
    if (op == "hello")
      return {{"ok", true}, {"device", mCtx.deviceName()}, {"version", skylayersVersion()}};
    inputError("unknown op '" + op + "' (open, frame, quality, save, close, empty, hello, quit)");
  }

private:
  Case& caseOf(const Json& request, const char* key) {
    const std::string name = request.value(key, "");
    auto it = mCases.find(name);
    if (it == mCases.end()) inputError(std::string(key) + " '" + name + "' is not open");
    return it->second;
  }

  Json open(const Json& r) {
    const std::string name = r.value("case", "");
    if (name.empty()) inputError("open: 'case' is required");
    std::vector<std::string> sets = r.value("set", std::vector<std::string>{});
    if (r.contains("width"))
      sets.push_back("output.width=" + std::to_string(r["width"].get<int>()));
    if (r.contains("height"))
      sets.push_back("output.height=" + std::to_string(r["height"].get<int>()));
    Case c;
    c.scene = loadSceneFile(r.value("scene", std::string(configDir() / "default.yaml")), sets);
    c.headingDegPerFrame = r.value("heading_deg_per_frame", 0.0);
    c.secondsPerFrame = r.value("seconds_per_frame", 0.0);
    c.next = r.value("first_frame", int64_t{0});
    c.views = r.value("views", 1);
    if (c.views < 1 || c.views > 16) inputError("open: views must be 1..16");
    const std::string mode = r.value("views_mode", std::string("one_frame"));
    if (mode != "one_frame" && mode != "separate")
      inputError("open: views_mode must be one_frame or separate");
    c.oneFrame = mode == "one_frame";
    c.renderer = std::make_unique<Renderer>(mCtx, mCompiler);
    mCases.erase(name);
    mCases.emplace(name, std::move(c));
    return {{"ok", true}, {"case", name}};
  }

  Json frame(Case& c) {
    const int64_t index = c.next++;
    Scene scene = c.scene;
    // The pan: heading wrapped into the scene's range, time moved on (the wind drifts).
    double heading = std::fmod(scene.camera.heading + c.headingDegPerFrame * index, 360.0);
    scene.camera.heading = heading;
    const IsoTime time = scene.time.start.plusSeconds(c.secondsPerFrame * index);
    // A viewer's frame: the display image alone, through the GPU display path (a histogram
    // exposure meters the beauty on the CPU, so such a scene reads the beauty back instead).
    RenderOptions options;
    const bool gpu = scene.output.exposure != ExposureMode::Histogram && c.views == 1;
    options.readBack = gpu ? ReadBack::Display : ReadBack::Beauty;
    if (gpu) options.gpuDisplay = &mOcio;
    const auto start = std::chrono::steady_clock::now();
    RenderedFrame f;
    if (c.views == 1) {
      f = c.renderer->render(scene, time, options);
    } else {
      // A rig: the beauty of each view (the first is shown), in one frame or one by one.
      options = {};
      options.readBack = ReadBack::Beauty;
      std::vector<FrameView> views;
      for (int k = 0; k < c.views; ++k)
        views.push_back({std::fmod(heading + 360.0 * k / c.views, 360.0), scene.camera.pitch,
                         scene.camera.roll, scene.camera.verticalFov, scene.camera.projection,
                         uint32_t(scene.output.width), uint32_t(scene.output.height)});
      if (c.oneFrame) {
        f = std::move(c.renderer->render(scene, time, views, options).front());
      } else {
        for (int k = 0; k < c.views; ++k) {
          Scene one = scene;
          one.camera.heading = views[k].headingDeg;
          RenderedFrame v = c.renderer->render(one, time, options);
          if (k == 0) {
            f = std::move(v);
            continue;
          }
          f.frame.gpuMs += v.frame.gpuMs;
          f.frame.wallMs += v.frame.wallMs;
          f.frame.passes.insert(f.frame.passes.end(), v.frame.passes.begin(), v.frame.passes.end());
        }
      }
    }
    const double renderMs = elapsedMs(start);
    const auto displayStart = std::chrono::steady_clock::now();
    if (gpu) {
      c.display.resize(f.display.size());
      for (size_t i = 0; i < f.display.size(); ++i) c.display[i] = f.display[i] / 255.0f;
    } else {
      c.display = displayPixels(f, scene, c.exposure.expose(scene, f, time), mOcio);
    }
    const double displayMs = elapsedMs(displayStart);
    c.quantized = gpu;
    c.width = scene.output.width;
    c.height = scene.output.height;
    Json passes = Json::array();
    for (const PassTiming& p : f.frame.passes)
      passes.push_back({{"name", p.name}, {"gpu_ms", p.gpuMs}, {"texels", p.texels}});
    return {{"ok", true},
            {"frame", index},
            {"gpu_ms", f.frame.gpuMs},
            {"graph_wall_ms", f.frame.wallMs},
            {"render_ms", renderMs},
            {"display_ms", displayMs},
            {"frame_ms", renderMs + displayMs},
            {"passes", passes},
            {"costs",
             {{"renderer_ms", f.costs.rendererMs},
              {"renderer_pipelines_ms", f.costs.rendererPipelinesMs},
              {"pipelines_ms", f.costs.pipelinesMs},
              {"textures_ms", f.costs.texturesMs},
              {"lut_bake_gpu_ms", f.costs.lutBakeGpuMs},
              {"setup_ms", f.costs.setupMs()}}}};
  }

  // The yardstick of the per-pass goals: shaders/empty_pass.comp over a width x height
  // RGBA32F image in a graph of its own, `frames` times; each frame's GPU time.
  Json empty(const Json& r) {
    const int width = r.value("width", 0), height = r.value("height", 0);
    const int frames = r.value("frames", 5);
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
      inputError("empty: width and height must be 1..16384");
    if (frames < 1 || frames > 1000) inputError("empty: frames must be 1..1000");
    Json ms = Json::array();
    for (int k = 0; k < frames; ++k) {
      FrameGraph graph(mRuntime);
      ImageId out;
      GraphBuilder b = graph.addPass("empty_pass", [&](PassContext& pc) {
        pc.dispatch(mEmpty, {Binding::of(EMPTY_PASS_BINDING_OUT, out)},
                    mEmpty.groupsX(uint32_t(width)), mEmpty.groupsY(uint32_t(height)));
      });
      ImageDesc d;
      d.name = "empty_pass";
      d.about = "a constant: the benchmark's empty full-screen pass";
      d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
      d.width = uint32_t(width);
      d.height = uint32_t(height);
      out = b.write(b.create(d), Access::StorageWriteCompute);
      b.sideEffect();
      const FrameResult f = graph.execute();
      ms.push_back(f.passes.empty() ? 0.0 : f.passes.front().gpuMs);
    }
    return {{"ok", true}, {"width", width}, {"height", height}, {"gpu_ms", ms}};
  }

  Json quality(const Case& a, const Case& ref) {
    if (a.display.empty() || ref.display.empty())
      inputError("quality: render a frame of both first");
    if (a.width != ref.width || a.height != ref.height) inputError("quality: the sizes differ");
    // The display-referred image as a viewer sees it (before the PNG's dither), RGB only.
    std::vector<float> x, y;
    x.reserve(a.display.size());
    y.reserve(a.display.size());
    for (size_t i = 0; i < a.display.size(); ++i)
      if (i % 4 != 3) {
        x.push_back(std::clamp(a.display[i], 0.0f, 1.0f));
        y.push_back(std::clamp(ref.display[i], 0.0f, 1.0f));
      }
    const double db = psnr(x, y, 1.0);
    return {{"ok", true},
            {"psnr_db", std::isfinite(db) ? db : 999.0},
            {"max_error", maxAbsError(x, y)},
            {"mean_error", meanAbsError(x, y)}};
  }

  Json save(const Case& c, const Json& r) {
    if (c.display.empty()) inputError("save: no frame rendered yet");
    const std::string png = r.value("png", "");
    if (png.empty()) inputError("save: 'png' is required");
    writePng8(png, c.width, c.height, c.display,
              c.quantized ? PngQuantize::Nearest : PngQuantize::Dither);
    return {{"ok", true}, {"png", png}};
  }

  Context mCtx;
  ShaderCompiler mCompiler;
  OcioOutput mOcio;
  GraphRuntime mRuntime{mCtx};  // the empty pass's graphs
  ComputePipeline mEmpty{buildComputePipeline(mCtx, mCompiler, "empty_pass.comp", "empty_pass")};
  std::map<std::string, Case> mCases;
};

}  // namespace
}  // namespace sky

int main(int argc, char** argv) {
  sky::ContextOptions options = sky::ContextOptions::fromEnvironment();
  for (int i = 1; i + 1 < argc; i += 2)
    if (std::string(argv[i]) == "--gpu") options.gpu = argv[i + 1];
  std::unique_ptr<sky::Server> server;
  try {
    server = std::make_unique<sky::Server>(options);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  std::string line;
  while (std::getline(std::cin, line)) {
    if (line.empty()) continue;
    sky::Json reply;
    try {
      const sky::Json request = sky::Json::parse(line);
      if (request.value("op", "") == "quit") break;
      reply = server->handle(request);
    } catch (const sky::Error& e) {
      if (e.kind() == sky::ErrorKind::Internal) {
        std::cout << sky::Json{{"ok", false}, {"error", e.what()}}.dump() << std::endl;
        return 1;
      }
      reply = {{"ok", false}, {"error", e.what()}};
    } catch (const std::exception& e) {
      reply = {{"ok", false}, {"error", e.what()}};
    }
    std::cout << reply.dump() << std::endl;
  }
  return 0;
}
