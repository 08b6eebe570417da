#include "commands.h"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli_args.h"
#include "default_scene.h"
#include "engine/color/ocio_output.h"
#include "engine/core/error.h"
#include "engine/gpu/context.h"
#include "engine/render/render_files.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"

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
  skyrender schema                     print the JSON Schema of scene files
  skyrender devices                    list the Vulkan devices and which one is picked
  skyrender --help                     this text

render options:
  --out DIR            output folder, created if missing (default: out)
  --name NAME          file stem, same as --set output.name=NAME
  --width W            same as --set output.width=W
  --height H           same as --set output.height=H
  --time ISO8601       same as --set time=ISO8601 (with zone: Z or +HH:MM)
  --set KEY.PATH=VALUE override any scene key; VALUE is read as a YAML scalar or flow
                       sequence (e.g. --set sky.sky_color=[0.1,0.2,0.5]); repeatable;
                       validated exactly like the file
  --dump-graph FILE    also write the compiled frame graph as Graphviz (dot -Tsvg FILE)
  --gpu NAME|INDEX     Vulkan device by index or name substring (default: a GPU if
                       present, else lavapipe)
  --ocio FILE          OpenColorIO config (default: $OCIO, else configs/ocio/config.ocio)

outputs:
  NAME.exr   scene-linear Rec.709, half float: R,G,B,A (beauty) and layers sky.R/G/B
  NAME.png   8-bit display image through output.display / output.view, exposure applied
  NAME.json  settings, sun placement, per-pass GPU milliseconds, total, device name

environment:
  SKY_VALIDATION=1   enable the Vulkan validation layers (messages go to stderr)
  SKY_DATA_DIR       folder holding shaders/ and configs/ (default: the source tree)
  SKY_CACHE_DIR      SPIR-V cache folder (default: ~/.cache/skylayers)
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

}  // namespace

int renderCommand(const std::vector<std::string>& argv) {
  CliArgs args(argv,
               {"--out", "--name", "--width", "--height", "--time", "--set", "--dump-graph",
                "--gpu", "--ocio"},
               {"--set"}, {});
  Scene scene = loadScene(args, false);

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
  RenderedFrame frame = renderer.render(scene);
  RenderFiles files = writeRenderFiles(outDir, scene, frame, ocio, ctx.deviceName(), graphPath);

  std::printf("wrote %s, %s, %s (%dx%d, %.2f ms GPU on %s)\n", files.exr.string().c_str(),
              files.png.string().c_str(), files.report.string().c_str(), scene.output.width,
              scene.output.height, frame.frame.gpuMs, ctx.deviceName().c_str());
  if (files.graph) std::printf("wrote %s\n", files.graph->string().c_str());
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

}  // namespace sky
