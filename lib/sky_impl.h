#pragma once
// What the parts of the public API share (skylayers.cpp: making a Sky, its scene and its
// renders; sky_vulkan_host.cpp: record() into a host's images; sky_lighting.cpp: lights and
// ambient for the host; sky_queries.cpp: the CPU queries): a Sky's state and the helpers that
// make the engine's errors and scene edits the API's. Private to the library, not installed.
#include "skylayers/skylayers.h"
#include "skylayers/vulkan.h"

#include <array>
#include <cstdint>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/color/ocio_output.h"
#include "engine/core/error.h"
#include "engine/gpu/context.h"
#include "engine/render/cloud_field.h"
#include "engine/render/exposure.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene.h"
#include "engine/shader/shader_compiler.h"

namespace skylayers {
namespace detail {

// The engine's errors as the API's: the same one line, the same kind. Anything else a
// library underneath throws (a filesystem error, out of memory) is Internal, so a host
// catches skylayers::Error alone.
template <typename F>
auto translated(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const Error&) {
    throw;
  } catch (const sky::Error& e) {
    throw Error(
        e.kind() == sky::ErrorKind::BadInput ? Error::Kind::BadInput : Error::Kind::Internal,
        e.what());
  } catch (const std::exception& e) {
    throw Error(Error::Kind::Internal, e.what());
  }
}

// A Sky draws one instant at a time: a time-lapse scene keeps its first frame (set("time")
// moves it).
sky::Scene instant(sky::Scene scene);
// `scene` with `assignments` ("key.path=value") applied through the scene reader, checked as
// a file is.
sky::Scene with(const sky::Scene& scene, const std::vector<std::string>& assignments);
// "%.17g": a double written so that reading it back gives the same bits.
std::string exact(double v);
std::array<double, 3> array3(double x, double y, double z);
// The Sky's own device, or the host's (DeviceOptions::vulkan).
std::unique_ptr<sky::Context> makeContext(const sky::ContextOptions& options,
                                          const VulkanDevice* host);

}  // namespace detail

struct Sky::Impl {
  sky::Scene scene;
  std::unique_ptr<sky::Context> contextOwner;
  sky::Context& context;
  sky::ShaderCompiler compiler;
  sky::OcioOutput ocio;
  sky::Renderer renderer;
  sky::ExposureMeter exposure;  // a histogram exposure adapts from frame to frame
  // Counts the scene's changes (apply()); the queries' density field is made again when it
  // moves, and not on every query.
  uint64_t sceneRevision = 0;
  std::optional<sky::CloudField> field;
  uint64_t fieldRevision = 0;
  bool onHostDevice = false;  // made on the host's VkDevice (DeviceOptions::vulkan)
  // The host's images of the last record(), borrowed (a view each) until the next frame.
  std::optional<sky::PersistentImage> hostColour, hostDepth;

  const sky::CloudField& cloudField() {
    if (!field || fieldRevision != sceneRevision) {
      field.reset();
      field.emplace(renderer.cloudField(scene, scene.time.start));
      fieldRevision = sceneRevision;
    }
    return *field;
  }

  Impl(sky::Scene s, const sky::ContextOptions& options, const VulkanDevice* host,
       sky::OcioOutput o)
      : scene(detail::instant(std::move(s))),
        contextOwner(detail::makeContext(options, host)),
        context(*contextOwner),
        ocio(std::move(o)),
        renderer(context, compiler),
        onHostDevice(host != nullptr) {}

  // The scene with `assignments` applied through the scene reader; the current scene is
  // replaced only when the result is valid (and its display and view exist in the config).
  void apply(const std::vector<std::string>& assignments) {
    sky::Scene next = detail::with(scene, assignments);
    ocio.checkDisplayView(next.output.display, next.output.view);
    scene = std::move(next);
    ++sceneRevision;
  }
};

}  // namespace skylayers
