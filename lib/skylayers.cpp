// The public API (lib/include/skylayers/skylayers.h) over the engine: a Sky is a scene, a
// Vulkan context, the shader compiler, a Renderer (which keeps the bakes, LUTs, noise and
// weather map between frames) and the OCIO config. Every change to the scene goes through
// the scene file's own reader, so a key set here is checked exactly as a file's or
// skyrender's --set is, and errors name the key the same way.
#include "sky_impl.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <utility>

#include "apps/common/default_scene.h"
#include "engine/color/ocio_output.h"
#include "engine/core/error.h"
#include "engine/core/paths.h"
#include "engine/gpu/context.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"
#include "engine/render/camera.h"
#include "engine/render/exposure.h"
#include "engine/render/frame_layers.h"
#include "engine/render/render_files.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "engine/weather/forecast_map.h"

namespace skylayers {

using namespace detail;

namespace {

sky::ConfigFormat formatNamed(const std::string& format) {
  if (format == "yaml" || format == "yml") return sky::ConfigFormat::Yaml;
  if (format == "json") return sky::ConfigFormat::Json;
  sky::inputError("scene format '" + format + "': expected yaml or json");
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

// Channel `c` of `layer` as an image of its own, named after the channel: the main layer's
// label and cloud type, which the EXR holds as top-level channels beside the beauty.
Image channelImage(const sky::LayeredImage& frame, const sky::ImageLayer& layer, size_t c) {
  const size_t n = layer.channels.size();
  Image image{layer.channels[c], frame.width, frame.height, {layer.channels[c]}, {}};
  image.pixels.resize(layer.pixels.size() / n);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = layer.pixels[i * n + c];
  return image;
}

}  // namespace

namespace detail {

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

std::array<double, 3> array3(double x, double y, double z) {
  return {x, y, z};
}

std::unique_ptr<sky::Context> makeContext(const sky::ContextOptions& options,
                                          const VulkanDevice* host) {
  if (!host) return std::make_unique<sky::Context>(options);
  return std::make_unique<sky::Context>(sky::ExternalDevice{
      host->instance, host->physicalDevice, host->device, host->queueFamily, host->queueIndex});
}

}  // namespace detail

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

std::vector<Image> readExr(const std::string& path) {
  return translated([&] {
    const sky::LayeredImage exr = sky::readExr(path);
    std::vector<Image> images;
    for (const sky::ImageLayer& layer : exr.layers) {
      if (!layer.name.empty()) {
        images.push_back(imageOf(layer.name, exr, layer));
        continue;
      }
      // The main layer holds the beauty and the labels: an image each, as a frame gives them.
      const size_t n = layer.channels.size();
      const size_t count = layer.pixels.size() / n;
      std::vector<size_t> colour;  // R, G, B, A first (readExr's order)
      for (size_t c = 0; c < n; ++c) {
        const std::string& name = layer.channels[c];
        if (name == "R" || name == "G" || name == "B" || name == "A") {
          colour.push_back(c);
          continue;
        }
        images.push_back(channelImage(exr, layer, c));
      }
      if (!colour.empty()) {
        Image beauty{"beauty", exr.width, exr.height, {}, {}};
        for (size_t c : colour) beauty.channels.push_back(layer.channels[c]);
        beauty.pixels.resize(count * colour.size());
        for (size_t i = 0; i < count; ++i)
          for (size_t k = 0; k < colour.size(); ++k)
            beauty.pixels[i * colour.size() + k] = layer.pixels[i * n + colour[k]];
        images.insert(images.begin(), std::move(beauty));
      }
    }
    return images;
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

namespace {

constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;

// Heading, pitch and roll (degrees) of a camera whose forward and up vectors are `forward` and
// `up` in its east-north-up frame; `who` names the call in errors.
glm::dvec3 headingPitchRoll(const glm::dvec3& forward, const glm::dvec3& up, const char* who) {
  if (!(glm::length(forward) > 0.0) || !(glm::length(up) > 0.0))
    sky::inputError(std::string(who) + ": forward and up must be non-zero vectors");
  const glm::dvec3 fn = glm::normalize(forward);
  // Up with its part along forward taken off: the camera's true up.
  const glm::dvec3 ortho = up - glm::dot(up, fn) * fn;
  if (glm::length(ortho) < 1e-9 * glm::length(up))
    sky::inputError(std::string(who) + ": up lies along forward");
  const glm::dvec3 un = glm::normalize(ortho);
  const double heading = std::atan2(fn.x, fn.y) * kDegPerRad;
  const double pitch = std::asin(std::clamp(fn.z, -1.0, 1.0)) * kDegPerRad;
  // makeViewState's unrolled axes for that heading and pitch, then the roll between them
  // (engine/render/camera.cpp: up = sin(roll) level + cos(roll) levelUp).
  const glm::dvec3 level(sky::directionFromAzEl(heading + 90.0, 0.0));
  const glm::dvec3 levelUp = glm::normalize(glm::cross(level, fn));
  const double roll = std::atan2(glm::dot(un, level), glm::dot(un, levelUp)) * kDegPerRad;
  return {heading, pitch, roll};
}

std::vector<std::string> orientationKeys(const glm::dvec3& hpr) {
  return {"camera.heading=" + exact(hpr.x), "camera.pitch=" + exact(hpr.y),
          "camera.roll=" + exact(hpr.z)};
}

// WGS84: the semi-major axis (m) and the first eccentricity squared.
constexpr double kWgs84A = 6378137.0;
constexpr double kWgs84E2 = 6.69437999014e-3;

// Geodetic latitude, longitude (degrees) and height above the WGS84 ellipsoid (m) of an ECEF
// point: Bowring's iteration from the geocentric guess, to well under a millimetre in a few
// steps anywhere outside the Earth's core.
glm::dvec3 geodeticFromEcef(const glm::dvec3& p) {
  const double lon = std::atan2(p.y, p.x);
  const double r = std::hypot(p.x, p.y);
  double lat = std::atan2(p.z, r * (1.0 - kWgs84E2));
  double h = 0.0;
  for (int i = 0; i < 8; ++i) {
    const double s = std::sin(lat);
    const double n = kWgs84A / std::sqrt(1.0 - kWgs84E2 * s * s);
    // Far from the poles height from the equatorial distance, near them from z.
    h = std::abs(std::cos(lat)) > 0.1 ? r / std::cos(lat) - n : p.z / s - n * (1.0 - kWgs84E2);
    lat = std::atan2(p.z, r * (1.0 - kWgs84E2 * n / (n + h)));
  }
  return {lat * kDegPerRad, lon * kDegPerRad, h};
}

}  // namespace

void Sky::setCameraAxes(const std::array<double, 3>& forward, const std::array<double, 3>& up) {
  translated([&] {
    mImpl->apply(
        orientationKeys(headingPitchRoll(glm::dvec3(forward[0], forward[1], forward[2]),
                                         glm::dvec3(up[0], up[1], up[2]), "setCameraAxes")));
  });
}

void Sky::setCameraEcef(const std::array<double, 3>& position, const std::array<double, 3>& forward,
                        const std::array<double, 3>& up) {
  translated([&] {
    const glm::dvec3 p(position[0], position[1], position[2]);
    if (!(glm::length(p) > 1.0e6) || !std::isfinite(glm::length(p)))
      sky::inputError("setCameraEcef: the position (" + exact(p.x) + ", " + exact(p.y) + ", " +
                      exact(p.z) + ") m is not near the Earth's surface (ECEF, metres)");
    const glm::dvec3 g = geodeticFromEcef(p);
    // The local east-north-up frame there (the ellipsoid's normal up).
    const double lat = g.x / kDegPerRad, lon = g.y / kDegPerRad;
    const glm::dvec3 east(-std::sin(lon), std::cos(lon), 0.0);
    const glm::dvec3 north(-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon),
                           std::cos(lat));
    const glm::dvec3 upAxis(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon),
                            std::sin(lat));
    const auto enu = [&](const std::array<double, 3>& v) {
      const glm::dvec3 e(v[0], v[1], v[2]);
      return glm::dvec3(glm::dot(e, east), glm::dot(e, north), glm::dot(e, upAxis));
    };
    std::vector<std::string> keys =
        orientationKeys(headingPitchRoll(enu(forward), enu(up), "setCameraEcef"));
    keys.insert(keys.end(), {"camera.latitude=" + exact(g.x), "camera.longitude=" + exact(g.y),
                             "camera.altitude_m=" + exact(g.z)});
    mImpl->apply(keys);
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
    const std::string name = sky::frameLayerName(layer);
    if (name == "beauty") {
      frame.beauty = imageOf(name, rendered.image, layer);
    } else if (layer.integer && request.layers) {
      // The label and the cloud type: one image each, as the EXR's top-level channels.
      for (size_t c = 0; c < layer.channels.size(); ++c)
        frame.layers.push_back(channelImage(rendered.image, layer, c));
    } else if (request.layers) {
      frame.layers.push_back(imageOf(name, rendered.image, layer));
    }
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

std::string Sky::deviceName() const {
  return mImpl->context.deviceName();
}

uint64_t Sky::validationMessages() const {
  return mImpl->context.validationMessageCount();
}

}  // namespace skylayers
