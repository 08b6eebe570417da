// The public API (lib/include/skylayers/skylayers.h) over the engine: a Sky is a scene, a
// Vulkan context, the shader compiler, a Renderer (which keeps the bakes, LUTs, noise and
// weather map between frames) and the OCIO config. Every change to the scene goes through
// the scene file's own reader, so a key set here is checked exactly as a file's or
// skyrender's --set is, and errors name the key the same way.
#include "skylayers/skylayers.h"
#include "skylayers/vulkan.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>
#include <utility>

#include "apps/common/default_scene.h"
#include "engine/color/ocio_output.h"
#include "engine/core/error.h"
#include "engine/core/paths.h"
#include "engine/gpu/context.h"
#include "engine/io/png.h"
#include "engine/lighting/lighting_state.h"
#include "engine/render/camera.h"
#include "engine/render/cloud_field.h"
#include "engine/render/exposure.h"
#include "engine/render/render_files.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "engine/weather/forecast_map.h"
#include "engine/weather/geo.h"

namespace skylayers {

namespace {

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

sky::ConfigFormat formatNamed(const std::string& format) {
  if (format == "yaml" || format == "yml") return sky::ConfigFormat::Yaml;
  if (format == "json") return sky::ConfigFormat::Json;
  sky::inputError("scene format '" + format + "': expected yaml or json");
}

// A Sky draws one instant at a time: a time-lapse scene keeps its first frame (set("time")
// moves it).
sky::Scene instant(sky::Scene scene) {
  scene.time.end.reset();
  scene.time.stepSeconds = 0.0;
  return scene;
}

// `scene` with `assignments` ("key.path=value") applied through the scene reader, checked as
// a file is.
sky::Scene with(const sky::Scene& scene, const std::vector<std::string>& assignments) {
  sky::Scene next;
  try {
    next = sky::loadSceneText(sky::writeScene(scene.withAbsolutePaths(), sky::ConfigFormat::Yaml),
                              sky::ConfigFormat::Yaml, "set", assignments);
  } catch (const sky::Error& e) {
    // The reader names an override as skyrender's option ("--set KEY=VALUE: ..."); here it
    // came from set().
    std::string message = e.what();
    if (message.rfind("--set ", 0) == 0) message = "set " + message.substr(6);
    throw sky::Error(e.kind(), message);
  }
  next.baseDir = scene.baseDir;
  return instant(std::move(next));
}

// "%.17g": a double written so that reading it back gives the same bits.
std::string exact(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

Image imageOf(const std::string& name, const sky::LayeredImage& frame,
              const sky::ImageLayer& layer) {
  Image image;
  image.name = name;
  image.width = frame.width;
  image.height = frame.height;
  image.channels = layer.channels;
  image.pixels = layer.pixels;
  return image;
}

std::array<double, 3> array3(double x, double y, double z) {
  return {x, y, z};
}

// Illuminance in the renderer's units (1 = pi * 10^4 lux, shaders/common/lighting_shared.h)
// to lux.
constexpr double kLuxPerUnit = 3.14159265358979323846 * 1.0e4;

Light lightOf(const sky::BodyLight& body, const sky::shared::DirectionalLight& gpu) {
  Light light;
  light.direction = array3(body.direction.x, body.direction.y, body.direction.z);
  light.azimuthDeg = body.azimuthDeg;
  light.elevationDeg = body.elevationDeg;
  light.illuminanceLux = array3(gpu.illuminance.x * kLuxPerUnit, gpu.illuminance.y * kLuxPerUnit,
                                gpu.illuminance.z * kLuxPerUnit);
  return light;
}

}  // namespace

const char* version() {
  return sky::skylayersVersion();
}

std::string dataDirectory() {
  return sky::dataRoot().string();
}

WeatherGrid weatherMap(const std::string& file, const std::vector<std::string>& overrides) {
  return translated([&] {
    std::vector<std::string> keys = overrides;
    for (std::string& k : sky::forecastFileOverrides(file)) keys.push_back(std::move(k));
    const sky::Scene scene =
        sky::loadSceneText(skyDefaultSceneText(), sky::ConfigFormat::Yaml, "<default scene>", keys);
    sky::WeatherSource source;
    const sky::ForecastMap forecast = sky::forecastMap(scene, source);
    WeatherGrid grid;
    grid.image = imageOf("weather", forecast.image, forecast.image.layers.at(0));
    grid.southDeg = forecast.map.region.lat[0];
    grid.northDeg = forecast.map.region.lat[1];
    grid.westDeg = forecast.map.region.lon[0];
    grid.eastDeg = forecast.map.region.lon[1];
    return grid;
  });
}

float Image::at(int x, int y, const std::string& channel) const {
  const auto c = std::find(channels.begin(), channels.end(), channel);
  if (c == channels.end())
    throw std::out_of_range("image '" + name + "' has no channel '" + channel + "'");
  if (x < 0 || y < 0 || x >= width || y >= height)
    throw std::out_of_range("image '" + name + "': pixel (" + std::to_string(x) + ", " +
                            std::to_string(y) + ") outside " + std::to_string(width) + "x" +
                            std::to_string(height));
  const size_t n = channels.size();
  return pixels[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * n +
                static_cast<size_t>(c - channels.begin())];
}

const Image& Frame::layer(const std::string& name) const {
  if (name == "beauty" || name.empty()) return beauty;
  for (const Image& image : layers)
    if (image.name == name) return image;
  throw std::out_of_range("the frame has no layer '" + name +
                          "' (RenderRequest::layers reads back sky, high_clouds and clouds)");
}

namespace {

std::unique_ptr<sky::Context> makeContext(const sky::ContextOptions& options,
                                          const VulkanDevice* host) {
  if (!host) return std::make_unique<sky::Context>(options);
  return std::make_unique<sky::Context>(sky::ExternalDevice{
      host->instance, host->physicalDevice, host->device, host->queueFamily, host->queueIndex});
}

}  // namespace

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
      : scene(instant(std::move(s))),
        contextOwner(makeContext(options, host)),
        context(*contextOwner),
        ocio(std::move(o)),
        renderer(context, compiler),
        onHostDevice(host != nullptr) {}

  // The scene with `assignments` applied through the scene reader; the current scene is
  // replaced only when the result is valid (and its display and view exist in the config).
  void apply(const std::vector<std::string>& assignments) {
    sky::Scene next = with(scene, assignments);
    ocio.checkDisplayView(next.output.display, next.output.view);
    scene = std::move(next);
    ++sceneRevision;
  }
};

namespace {

sky::ContextOptions contextOptions(const DeviceOptions& device) {
  sky::ContextOptions options = device.validationFromEnvironment
                                    ? sky::ContextOptions::fromEnvironment()
                                    : sky::ContextOptions{};
  if (device.validation) options.validation = true;
  options.gpu = device.gpu;
  return options;
}

sky::OcioOutput ocioFor(const DeviceOptions& device, const sky::Scene& scene) {
  std::optional<std::filesystem::path> path;
  if (!device.ocioConfig.empty()) path = device.ocioConfig;
  sky::OcioOutput ocio = sky::OcioOutput::load(path);
  ocio.checkDisplayView(scene.output.display, scene.output.view);
  return ocio;
}

}  // namespace

Sky::Sky(std::unique_ptr<Impl> impl) : mImpl(std::move(impl)) {}
Sky::Sky(Sky&&) noexcept = default;
Sky& Sky::operator=(Sky&&) noexcept = default;
Sky::~Sky() = default;

Sky Sky::fromFile(const std::string& path, const std::vector<std::string>& overrides,
                  const DeviceOptions& device) {
  return translated([&] {
    sky::Scene scene = sky::loadSceneFile(path, overrides);
    sky::OcioOutput ocio = ocioFor(device, scene);
    return Sky(std::make_unique<Impl>(std::move(scene), contextOptions(device), device.vulkan,
                                      std::move(ocio)));
  });
}

Sky Sky::fromText(const std::string& text, const std::string& format, const std::string& sourceName,
                  const std::vector<std::string>& overrides, const DeviceOptions& device) {
  return translated([&] {
    sky::Scene scene = sky::loadSceneText(text, formatNamed(format), sourceName, overrides);
    sky::OcioOutput ocio = ocioFor(device, scene);
    return Sky(std::make_unique<Impl>(std::move(scene), contextOptions(device), device.vulkan,
                                      std::move(ocio)));
  });
}

Sky Sky::fromDefault(const std::vector<std::string>& overrides, const DeviceOptions& device) {
  return fromText(skyDefaultSceneText(), "yaml", "<default scene>", overrides, device);
}

void Sky::set(const std::string& keyPath, const std::string& value) {
  set(std::vector<std::string>{keyPath + "=" + value});
}

void Sky::set(const std::vector<std::string>& assignments) {
  translated([&] { mImpl->apply(assignments); });
}

void Sky::setTime(const std::string& iso8601) {
  set("time", iso8601);
}

std::string Sky::time() const {
  return mImpl->scene.time.start.format();
}

void Sky::setCamera(const GeoPose& pose) {
  set({"camera.latitude=" + exact(pose.latitudeDeg), "camera.longitude=" + exact(pose.longitudeDeg),
       "camera.altitude_m=" + exact(pose.altitudeM), "camera.heading=" + exact(pose.headingDeg),
       "camera.pitch=" + exact(pose.pitchDeg), "camera.roll=" + exact(pose.rollDeg)});
}

GeoPose Sky::camera() const {
  const sky::CameraSettings& c = mImpl->scene.camera;
  return {c.latitude, c.longitude, c.altitudeM, c.heading, c.pitch, c.roll};
}

void Sky::setCameraAxes(const std::array<double, 3>& forward, const std::array<double, 3>& up) {
  translated([&] {
    constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;
    const glm::dvec3 f(forward[0], forward[1], forward[2]);
    const glm::dvec3 u(up[0], up[1], up[2]);
    if (!(glm::length(f) > 0.0) || !(glm::length(u) > 0.0))
      sky::inputError("setCameraAxes: forward and up must be non-zero vectors");
    const glm::dvec3 fn = glm::normalize(f);
    // Up with its part along forward taken off: the camera's true up.
    const glm::dvec3 ortho = u - glm::dot(u, fn) * fn;
    if (glm::length(ortho) < 1e-9 * glm::length(u))
      sky::inputError("setCameraAxes: up lies along forward");
    const glm::dvec3 un = glm::normalize(ortho);
    const double heading = std::atan2(fn.x, fn.y) * kDegPerRad;
    const double pitch = std::asin(std::clamp(fn.z, -1.0, 1.0)) * kDegPerRad;
    // makeViewState's unrolled axes for that heading and pitch, then the roll between them
    // (engine/render/camera.cpp: up = sin(roll) level + cos(roll) levelUp).
    const glm::dvec3 level(sky::directionFromAzEl(heading + 90.0, 0.0));
    const glm::dvec3 levelUp = glm::normalize(glm::cross(level, fn));
    const double roll = std::atan2(glm::dot(un, level), glm::dot(un, levelUp)) * kDegPerRad;
    mImpl->apply({"camera.heading=" + exact(heading), "camera.pitch=" + exact(pitch),
                  "camera.roll=" + exact(roll)});
  });
}

void Sky::setSize(int width, int height) {
  set({"output.width=" + std::to_string(width), "output.height=" + std::to_string(height)});
}

void Sky::setVerticalFov(double degrees) {
  set("camera.vertical_fov", exact(degrees));
}

void Sky::setProjectionMatrix(const std::array<double, 16>& m) {
  translated([&] {
    // m[c * 4 + r]: column c, row r. A symmetric perspective matrix has m[0][0], m[1][1] on
    // the diagonal, w = -z or z in the third column's last row, and no off-centre terms.
    const double sx = m[0], sy = m[5], offX = m[8], offY = m[9], w = m[11], last = m[15];
    if (!(std::abs(std::abs(w) - 1.0) < 1e-9) || last != 0.0)
      sky::inputError("setProjectionMatrix: not a perspective matrix (m[2][3] = " + exact(w) +
                      ", m[3][3] = " + exact(last) + ")");
    if (std::abs(offX) > 1e-9 || std::abs(offY) > 1e-9 || m[1] != 0.0 || m[4] != 0.0)
      sky::inputError(
          "setProjectionMatrix: an off-centre or skewed frustum is not supported (the camera "
          "is a symmetric pinhole: give the vertical field of view)");
    if (!(std::abs(sx) > 0.0) || !(std::abs(sy) > 0.0) || !std::isfinite(sx) || !std::isfinite(sy))
      sky::inputError("setProjectionMatrix: the matrix has no field of view");
    const sky::OutputSettings& out = mImpl->scene.output;
    const double aspect = std::abs(sy) / std::abs(sx);
    const double image = double(out.width) / double(out.height);
    if (std::abs(aspect / image - 1.0) > 1e-3)
      sky::inputError("setProjectionMatrix: its aspect " + exact(aspect) + " is not the image's " +
                      std::to_string(out.width) + "x" + std::to_string(out.height) +
                      " (setSize first)");
    constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;
    mImpl->apply({"camera.vertical_fov=" + exact(2.0 * std::atan(1.0 / std::abs(sy)) * kDegPerRad),
                  "camera.projection=perspective"});
  });
}

std::string Sky::sceneYaml() const {
  return translated(
      [&] { return sky::writeScene(mImpl->scene.withAbsolutePaths(), sky::ConfigFormat::Yaml); });
}

namespace {

// A rendered frame of `scene` as the API gives it: the PNG's path for the display
// (engine/render/render_files.h: the scene's exposure, then OCIO, then the PNG's
// quantisation) and skyrender's report.
Frame frameOf(sky::RenderedFrame& rendered, const sky::Scene& scene, const sky::IsoTime& time,
              const RenderRequest& request, sky::ExposureMeter& meter, const sky::OcioOutput& ocio,
              const std::string& device) {
  Frame frame;
  frame.time = time.format();
  frame.gpuMs = rendered.frame.gpuMs;
  for (const sky::ImageLayer& layer : rendered.image.layers) {
    if (layer.name.empty())
      frame.beauty = imageOf("beauty", rendered.image, layer);
    else if (request.layers)
      frame.layers.push_back(imageOf(layer.name, rendered.image, layer));
  }
  const sky::FrameExposure exposure = meter.expose(scene, rendered, time);
  frame.exposureEv = exposure.ev;
  if (request.display) {
    const std::vector<float> px = sky::displayPixels(rendered, scene, exposure, ocio);
    frame.display =
        sky::quantize8(rendered.image.width, rendered.image.height, px,
                       scene.output.dither ? sky::PngQuantize::Dither : sky::PngQuantize::Nearest);
  }
  frame.report = sky::renderReport(scene, rendered, exposure, ocio, device).dump(2);
  return frame;
}

sky::ReadBack readBackOf(const RenderRequest& request) {
  return request.layers ? sky::ReadBack::Layers : sky::ReadBack::Beauty;
}

}  // namespace

Frame Sky::render(const RenderRequest& request) {
  return translated([&] {
    Impl& m = *mImpl;
    sky::RenderOptions options;
    options.readBack = readBackOf(request);
    const sky::IsoTime& time = m.scene.time.start;
    sky::RenderedFrame rendered = m.renderer.render(m.scene, time, options);
    return frameOf(rendered, m.scene, time, request, m.exposure, m.ocio, m.context.deviceName());
  });
}

std::vector<Frame> Sky::renderViews(const std::vector<View>& views, const RenderRequest& request) {
  return translated([&] {
    Impl& m = *mImpl;
    std::vector<sky::FrameView> frameViews;
    std::vector<sky::Scene> scenes;
    for (size_t i = 0; i < views.size(); ++i) {
      const View& v = views[i];
      // Each view's scene, through the scene reader: its checks name the view.
      std::vector<std::string> keys = {"camera.heading=" + exact(v.headingDeg),
                                       "camera.pitch=" + exact(v.pitchDeg),
                                       "camera.roll=" + exact(v.rollDeg),
                                       "camera.vertical_fov=" + exact(v.verticalFovDeg),
                                       "output.width=" + std::to_string(v.width),
                                       "output.height=" + std::to_string(v.height)};
      try {
        scenes.push_back(with(m.scene, keys));
      } catch (const sky::Error& e) {
        throw Error(Error::Kind::BadInput, "render: view " + std::to_string(i) + ": " + e.what());
      }
      const sky::CameraSettings& c = scenes.back().camera;
      frameViews.push_back({c.heading, c.pitch, c.roll, c.verticalFov, c.projection,
                            static_cast<uint32_t>(v.width), static_cast<uint32_t>(v.height)});
    }
    sky::RenderOptions options;
    options.readBack = readBackOf(request);
    const sky::IsoTime& time = m.scene.time.start;
    std::vector<sky::RenderedFrame> rendered =
        m.renderer.render(m.scene, time, frameViews, options);
    std::vector<Frame> frames;
    for (size_t i = 0; i < rendered.size(); ++i) {
      sky::ExposureMeter meter;  // each view meters itself
      frames.push_back(
          frameOf(rendered[i], scenes[i], time, request, meter, m.ocio, m.context.deviceName()));
    }
    return frames;
  });
}

namespace {

bool hasStencil(VkFormat f) {
  return f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

// The host's depth values as distances (shaders/common/atmosphere_composite_shared.h).
sky::shared::HostDepth depthMapping(const DepthConvention& c) {
  sky::shared::HostDepth m{};
  const auto bad = [](const std::string& why) {
    throw Error(Error::Kind::BadInput, "record: HostFrame::depthConvention: " + why);
  };
  double a = 0.0, b = 0.0;
  if (c.useProjection) {
    a = c.projection[10];
    b = c.projection[14];
    if (c.projection[11] != -1.0 || c.projection[15] != 0.0 || b == 0.0 || !std::isfinite(a) ||
        !std::isfinite(b))
      bad("the projection is not a perspective one in Vulkan's clip space (m[11] = -1, "
          "m[15] = 0, m[14] != 0)");
    // Its far end: the depth (0 or 1) whose distance b / (d + a) is the larger or infinite.
    const double z0 = a == 0.0 ? INFINITY : b / a, z1 = a == -1.0 ? INFINITY : b / (1.0 + a);
    if (!(z0 > 0.0 || z1 > 0.0)) bad("the projection puts depths 0 and 1 behind the camera");
    m.emptyDepth = (z1 > 0.0 && (z0 <= 0.0 || z1 > z0)) ? 1.0f : 0.0f;
  } else {
    const double n = c.nearM, f = c.farM;
    if (!(n > 0.0) || !std::isfinite(n) || !(f > n))
      bad("near " + std::to_string(n) + " m and far " + std::to_string(f) +
          " m: need 0 < near < far (far may be infinite)");
    const bool infinite = std::isinf(f);
    if (c.reverseZ) {
      a = infinite ? 0.0 : n / (f - n);
      b = infinite ? n : n * f / (f - n);
    } else {
      a = infinite ? -1.0 : f / (n - f);
      b = infinite ? -n : n * f / (n - f);
    }
    m.emptyDepth = c.reverseZ ? 0.0f : 1.0f;
  }
  m.depthA = static_cast<float>(a);
  m.depthB = static_cast<float>(b);
  return m;
}

}  // namespace

Frame Sky::record(const HostFrame& host) {
  return translated([&] {
    Impl& m = *mImpl;
    const auto bad = [](const std::string& why) {
      throw Error(Error::Kind::BadInput, "record: " + why);
    };
    if (!m.onHostDevice)
      bad("the Sky is on its own device; record() draws into a host's images on the host's "
          "device (DeviceOptions::vulkan)");
    if (!host.commandBuffer) bad("HostFrame::commandBuffer is VK_NULL_HANDLE");
    const HostImage& c = host.colour;
    if (!c.image) bad("HostFrame::colour.image is VK_NULL_HANDLE");
    if (c.format != VK_FORMAT_R16G16B16A16_SFLOAT && c.format != VK_FORMAT_R32G32B32A32_SFLOAT)
      bad("HostFrame::colour.format " + std::to_string(c.format) +
          ": the colour must be R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT (scene-linear)");
    if (c.width == 0 || c.height == 0) bad("HostFrame::colour has no size");
    const HostImage& d = host.depth;
    if (d.image) {
      if (d.format != VK_FORMAT_D16_UNORM && d.format != VK_FORMAT_X8_D24_UNORM_PACK32 &&
          d.format != VK_FORMAT_D32_SFLOAT && !hasStencil(d.format))
        bad("HostFrame::depth.format " + std::to_string(d.format) + " is not a depth format");
      if (d.width != c.width || d.height != c.height)
        bad("HostFrame::depth is " + std::to_string(d.width) + "x" + std::to_string(d.height) +
            ", the colour " + std::to_string(c.width) + "x" + std::to_string(c.height));
      if (m.scene.camera.projection != sky::CameraProjection::Perspective ||
          m.scene.camera.mode != sky::CameraMode::Observer)
        bad("a host's depth needs a perspective observer camera");
    }
    const sky::shared::HostDepth mapping = depthMapping(host.depthConvention);
    if (m.scene.output.width != static_cast<int>(c.width) ||
        m.scene.output.height != static_cast<int>(c.height))
      m.apply(
          {"output.width=" + std::to_string(c.width), "output.height=" + std::to_string(c.height)});

    // The last frame's views go: the host has run it (the contract above).
    m.hostColour.reset();
    m.hostDepth.reset();
    sky::ImageDesc cd;
    cd.name = "host_colour";
    cd.format = c.format;
    cd.width = c.width;
    cd.height = c.height;
    cd.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    m.hostColour.emplace(sky::PersistentImage{sky::Image::borrow(m.context, cd, c.image), {}});
    sky::HostTarget target;
    target.cmd = host.commandBuffer;
    target.colour = &*m.hostColour;
    target.colourLayout = c.layout;
    if (d.image) {
      sky::ImageDesc dd = cd;
      dd.name = "host_depth";
      dd.format = d.format;
      dd.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
      dd.view = sky::DebugView::Depth;
      dd.aspect =
          VK_IMAGE_ASPECT_DEPTH_BIT | (hasStencil(d.format) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
      m.hostDepth.emplace(sky::PersistentImage{sky::Image::borrow(m.context, dd, d.image), {}});
      target.depth = &*m.hostDepth;
      target.depthLayout = d.layout;
    }
    target.depthMapping = mapping;
    sky::RenderOptions options;
    options.host = &target;
    const sky::IsoTime& time = m.scene.time.start;
    sky::RenderedFrame rendered = m.renderer.render(m.scene, time, options);

    Frame frame;
    frame.time = time.format();
    // The scene's exposure without metering (the frame is the host's, on its GPU).
    sky::FrameExposure exposure;
    exposure.mode = m.scene.output.exposure == sky::ExposureMode::Fixed ? sky::ExposureMode::Fixed
                                                                        : sky::ExposureMode::Auto;
    exposure.ev = (exposure.mode == sky::ExposureMode::Auto ? rendered.lighting.nightLiftEv : 0.0) +
                  m.scene.output.exposureEv;
    frame.exposureEv = exposure.ev;
    frame.report =
        sky::renderReport(m.scene, rendered, exposure, m.ocio, m.context.deviceName()).dump(2);
    return frame;
  });
}

void Sky::forgetHostImages() {
  mImpl->hostColour.reset();
  mImpl->hostDepth.reset();
}

namespace {

// The share of a body's light the clouds let through to the field's camera: the cloud
// optical depth along the line toward it, up past the top of the highest layer.
double cloudShadow(const sky::CloudField& field, const Light& light) {
  if (!field.anyCover() || light.elevationDeg < -2.0) return 1.0;
  const sky::shared::CloudParams& p = field.params();
  const double camera = field.latLonAltitudeOf(glm::dvec3(0.0)).z;
  const double top = std::max(p.lowTopM, p.midTopM);
  if (camera >= top) return 1.0;
  // Long enough to climb out of the layers (a low sun's line crosses them far away), and
  // no longer than the weather map's reach.
  const double rise = std::max(std::sin(light.elevationDeg * 3.14159265358979323846 / 180.0), 0.02);
  const double length = std::clamp((top - camera + 500.0) / rise, 1000.0, 200000.0);
  const glm::dvec3 d(light.direction[0], light.direction[1], light.direction[2]);
  return std::exp(-field.cloudOpticalDepth(glm::dvec3(0.0), d * length, Sky::kQueryStepM));
}

// The lights of `scene` at its camera and time; with `field` (made for that scene), behind
// the clouds there.
Lighting lightingOf(const sky::Scene& scene, const sky::CloudField* field) {
  const sky::LightingState state = sky::computeLighting(scene, scene.time.start);
  Lighting lighting;
  lighting.sun = lightOf(state.sun, state.gpu.sun);
  lighting.moon = lightOf(state.moon, state.gpu.moon);
  lighting.dayFactor = state.dayFactor;
  lighting.key = state.key;
  if (field)
    for (Light* light : {&lighting.sun, &lighting.moon}) {
      light->cloudTransmittance = cloudShadow(*field, *light);
      for (double& e : light->illuminanceLux) e *= light->cloudTransmittance;
    }
  return lighting;
}

std::vector<std::string> placeAndTime(const std::string& iso8601, double latitudeDeg,
                                      double longitudeDeg, double altitudeM) {
  return {"time=" + iso8601, "camera.latitude=" + exact(latitudeDeg),
          "camera.longitude=" + exact(longitudeDeg), "camera.altitude_m=" + exact(altitudeM)};
}

}  // namespace

Lighting lightingAt(double latitudeDeg, double longitudeDeg, double altitudeM,
                    const std::string& iso8601) {
  return translated([&] {
    return lightingOf(
        with(sky::loadSceneText(skyDefaultSceneText(), sky::ConfigFormat::Yaml, "<default scene>"),
             placeAndTime(iso8601, latitudeDeg, longitudeDeg, altitudeM)),
        nullptr);
  });
}

namespace {

// A top-down view has no observer under the clouds: its lights are the clear sky's.
bool observer(const sky::Scene& scene) {
  return scene.camera.mode != sky::CameraMode::GeographicTopdown;
}

}  // namespace

Lighting Sky::lighting() const {
  return translated([&] {
    return lightingOf(mImpl->scene, observer(mImpl->scene) ? &mImpl->cloudField() : nullptr);
  });
}

Lighting Sky::lighting(const std::string& iso8601) const {
  return lighting(iso8601, mImpl->scene.camera.latitude, mImpl->scene.camera.longitude,
                  mImpl->scene.camera.altitudeM);
}

Lighting Sky::lighting(const std::string& iso8601, double latitudeDeg, double longitudeDeg,
                       double altitudeM) const {
  return translated([&] {
    const sky::Scene scene =
        with(mImpl->scene, placeAndTime(iso8601, latitudeDeg, longitudeDeg, altitudeM));
    if (!observer(scene)) return lightingOf(scene, nullptr);
    const sky::CloudField field = mImpl->renderer.cloudField(scene, scene.time.start);
    return lightingOf(scene, &field);
  });
}

namespace {

glm::dvec3 enuOf(const sky::CloudField& field, const GeoPoint& p) {
  return field.enuOf(p.latitudeDeg, p.longitudeDeg, p.altitudeM);
}

// The lines' queries over the machine's cores: the field is read-only.
template <typename F>
void parallelFor(size_t count, F&& f) {
  const size_t threads =
      std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), (count + 7) / 8);
  if (threads <= 1) {
    for (size_t i = 0; i < count; ++i) f(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::vector<std::thread> pool;
  for (size_t t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (size_t i = next++; i < count; i = next++) f(i);
    });
  for (std::thread& t : pool) t.join();
}

Transmittance lineTransmittance(const sky::CloudField& field, const GeoPoint& from,
                                const GeoPoint& to) {
  const glm::dvec3 a = enuOf(field, from), b = enuOf(field, to);
  Transmittance t;
  t.cloudOpticalDepth = field.cloudOpticalDepth(a, b, Sky::kQueryStepM);
  t.cloud = std::exp(-t.cloudOpticalDepth);
  const glm::dvec3 air = field.airOpticalDepth(a, b);
  t.air = array3(std::exp(-air.x), std::exp(-air.y), std::exp(-air.z));
  return t;
}

}  // namespace

Transmittance Sky::transmittance(const GeoPoint& from, const GeoPoint& to) {
  return translated([&] { return lineTransmittance(mImpl->cloudField(), from, to); });
}

std::vector<Transmittance> Sky::transmittance(const std::vector<std::array<GeoPoint, 2>>& lines) {
  return translated([&] {
    const sky::CloudField& field = mImpl->cloudField();
    std::vector<Transmittance> out(lines.size());
    parallelFor(lines.size(),
                [&](size_t i) { out[i] = lineTransmittance(field, lines[i][0], lines[i][1]); });
    return out;
  });
}

double Sky::cloudExtinction(const GeoPoint& point) {
  return translated([&] {
    const sky::CloudField& field = mImpl->cloudField();
    return field.extinction(enuOf(field, point));
  });
}

CloudCover Sky::cover(double latitudeDeg, double longitudeDeg) {
  return translated([&] {
    const glm::vec4 w = mImpl->cloudField().weatherAt(latitudeDeg, longitudeDeg);
    return CloudCover{w.r, w.g, w.b};
  });
}

double Sky::firstCloud(const GeoPoint& from, const GeoPoint& to, double opticalDepth) {
  return translated([&] {
    const sky::CloudField& field = mImpl->cloudField();
    const glm::dvec3 a = enuOf(field, from), b = enuOf(field, to);
    const double length = glm::length(b - a);
    if (length <= 0.0) return -1.0;
    const std::optional<double> d =
        field.distanceToOpticalDepth(a, (b - a) / length, length, opticalDepth, kQueryStepM);
    return d.value_or(-1.0);
  });
}

GeoPoint Sky::pixelPoint(double x, double y, double distanceM) const {
  return translated([&] {
    const sky::Scene& scene = mImpl->scene;
    const sky::shared::ViewState view =
        sky::makeViewState(scene.camera, static_cast<uint32_t>(scene.output.width),
                           static_cast<uint32_t>(scene.output.height));
    const glm::dvec3 enu = sky::viewDirection(view, x, y) * distanceM;
    const glm::dvec3 lla = sky::latLonAltitude(
        {scene.camera.latitude, scene.camera.longitude, scene.camera.altitudeM}, enu);
    return GeoPoint{lla.x, lla.y, lla.z};
  });
}

namespace {

// The real SH basis of skylayers.h at unit direction d.
std::array<double, 9> shBasis(const glm::dvec3& d) {
  return {0.282095,
          0.488603 * d.y,
          0.488603 * d.z,
          0.488603 * d.x,
          1.092548 * d.x * d.y,
          1.092548 * d.y * d.z,
          0.315392 * (3.0 * d.z * d.z - 1.0),
          1.092548 * d.x * d.z,
          0.546274 * (d.x * d.x - d.y * d.y)};
}

// Radiance in the renderer's units (1 = 10^4 cd/m^2, docs/outputs.md) to cd/m^2.
constexpr double kNitsPerUnit = 1.0e4;
// The probe of ambient(): the whole sphere at this size.
constexpr int kProbeWidth = 64, kProbeHeight = 32;

}  // namespace

std::array<double, 3> irradiance(const SphericalHarmonics& sh,
                                 const std::array<double, 3>& normal) {
  const glm::dvec3 n = glm::normalize(glm::dvec3(normal[0], normal[1], normal[2]));
  const std::array<double, 9> y = shBasis(n);
  constexpr double kPi = 3.14159265358979323846;
  const double band[9] = {kPi,       2.0 * kPi / 3.0, 2.0 * kPi / 3.0, 2.0 * kPi / 3.0, kPi / 4.0,
                          kPi / 4.0, kPi / 4.0,       kPi / 4.0,       kPi / 4.0};
  std::array<double, 3> e{0.0, 0.0, 0.0};
  for (int i = 0; i < 9; ++i)
    for (int c = 0; c < 3; ++c) e[c] += band[i] * sh[i][c] * y[i];
  return e;
}

SphericalHarmonics Sky::ambient() {
  return translated([&] {
    Impl& m = *mImpl;
    // The sphere as the camera's scene shows it, the discs left out; without temporal reuse,
    // which would take this for a cut of the Sky's own sequence.
    const sky::Scene probe =
        with(m.scene, {"camera.projection=equirectangular", "camera.heading=0", "camera.pitch=0",
                       "output.width=" + std::to_string(kProbeWidth),
                       "output.height=" + std::to_string(kProbeHeight), "sun.disc_scale=0",
                       "moon.disc_scale=0", "clouds.temporal.mode=off"});
    sky::RenderOptions options;
    options.readBack = sky::ReadBack::Beauty;
    const sky::RenderedFrame frame = m.renderer.render(probe, probe.time.start, options);
    const sky::ImageLayer* beauty = frame.image.find("");
    if (!beauty) sky::internalError("ambient: the probe frame has no beauty");
    const sky::shared::ViewState view = sky::makeViewState(probe.camera, kProbeWidth, kProbeHeight);
    constexpr double kPi = 3.14159265358979323846;
    SphericalHarmonics sh{};
    const size_t channels = beauty->channels.size();
    for (int y = 0; y < kProbeHeight; ++y)
      for (int x = 0; x < kProbeWidth; ++x) {
        const glm::dvec3 d = sky::viewDirection(view, x + 0.5, y + 0.5);
        // An equirectangular pixel's solid angle: (2 pi / W) (pi / H) cos(elevation).
        const double omega = (2.0 * kPi / kProbeWidth) * (kPi / kProbeHeight) *
                             std::sqrt(std::max(0.0, 1.0 - d.z * d.z));
        const std::array<double, 9> basis = shBasis(d);
        const float* px = &beauty->pixels[(size_t(y) * kProbeWidth + x) * channels];
        for (int i = 0; i < 9; ++i)
          for (int c = 0; c < 3; ++c) sh[i][c] += double(px[c]) * kNitsPerUnit * basis[i] * omega;
      }
    return sh;
  });
}

std::string Sky::deviceName() const {
  return mImpl->context.deviceName();
}

uint64_t Sky::validationMessages() const {
  return mImpl->context.validationMessageCount();
}

}  // namespace skylayers
