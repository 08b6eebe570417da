#include "engine/scene/scene.h"

#include <cmath>

namespace sky {

int64_t TimeSettings::frameCount() const {
  if (!end) return 1;
  // A frame lands on `end` when the range is a whole number of steps; the tolerance keeps
  // 24h / 15m from losing its last frame to rounding.
  double steps = end->secondsSince(start) / stepSeconds;
  return static_cast<int64_t>(std::floor(steps + 1e-9)) + 1;
}

IsoTime TimeSettings::frame(int64_t index) const {
  return index == 0 ? start : start.plusSeconds(static_cast<double>(index) * stepSeconds);
}

std::vector<PaletteKey> defaultPalette() {
  // Authored against the physical twilight (docs/lighting.md): the sky's luminance after the
  // default night adaptation (0.8) falls about 1.6 stops by the end of civil twilight, 3.3 by
  // nautical and 4 by astronomical night, relative to sunset. From sunset up the colours
  // follow sky.model physical (turbidity 0.1) at the same sun elevation, with the default
  // glow (s 0.5, n 8) and haze (hmax 0.7): the sky is its chromaticity 45 degrees up and 90
  // degrees from the sun, at the luminance the foundation shipped; the haze makes the
  // horizon there 3.5-4 times the zenith, as the physical sky's; the glow makes the sky 15
  // degrees above the sun its colour and 5-9 times the zenith (sun 0-30 degrees). Derived in
  // docs/lighting.md ("The default palette").
  using v = glm::vec3;
  return {
      // sun_elevation, sky, fog, glow, cloud_lit, cloud_dark, ambient_top, ambient_bottom
      {-90, v{0.0022f, 0.0035f, 0.008f}, v{0.003f, 0.0033f, 0.004f}, v{0.0f},
       v{0.003f, 0.0032f, 0.004f}, v{0.0015f, 0.0016f, 0.002f}, v{0.002f, 0.0025f, 0.004f},
       v{0.0012f}},
      {-18, v{0.0022f, 0.0035f, 0.008f}, v{0.003f, 0.0033f, 0.004f}, v{0.0f},
       v{0.003f, 0.0032f, 0.004f}, v{0.0015f, 0.0016f, 0.002f}, v{0.002f, 0.0025f, 0.004f},
       v{0.0012f}},
      {-12, v{0.004f, 0.008f, 0.022f}, v{0.006f, 0.007f, 0.012f}, v{0.004f, 0.003f, 0.004f},
       v{0.01f, 0.01f, 0.015f}, v{0.004f, 0.005f, 0.008f}, v{0.004f, 0.006f, 0.014f},
       v{0.002f, 0.002f, 0.003f}},
      {-6, v{0.015f, 0.028f, 0.08f}, v{0.06f, 0.045f, 0.05f}, v{0.12f, 0.05f, 0.03f},
       v{0.15f, 0.08f, 0.08f}, v{0.03f, 0.03f, 0.05f}, v{0.02f, 0.03f, 0.06f},
       v{0.01f, 0.01f, 0.012f}},
      {0, v{0.075f, 0.078f, 0.141f}, v{0.5f, 0.3f, 0.15f}, v{2.0f, 1.0f, 0.8f},
       v{0.9f, 0.45f, 0.2f}, v{0.15f, 0.12f, 0.15f}, v{0.08f, 0.1f, 0.18f}, v{0.04f, 0.03f, 0.03f}},
      {10, v{0.096f, 0.155f, 0.290f}, v{0.68f, 0.76f, 0.72f}, v{3.4f, 3.2f, 2.9f},
       v{1.0f, 0.75f, 0.5f}, v{0.35f, 0.35f, 0.45f}, v{0.2f, 0.25f, 0.4f}, v{0.1f, 0.08f, 0.07f}},
      // By day the light from below, as a cloud base a kilometre up sees it, is the sunlit
      // ground (albedo 0.15-0.2) behind a kilometre of blue airlight: about a third of the sky's
      // luminance, and bluish. Grey-brown ground light alone made cloud bases brown.
      {30, v{0.115f, 0.209f, 0.418f}, v{0.66f, 0.94f, 1.08f}, v{1.8f, 2.1f, 2.6f},
       v{0.9f, 0.9f, 0.92f}, v{0.45f, 0.5f, 0.6f}, v{0.3f, 0.4f, 0.6f}, v{0.2f, 0.23f, 0.28f}},
      {90, v{0.120f, 0.211f, 0.397f}, v{0.66f, 0.94f, 1.08f}, v{0.95f, 1.2f, 1.6f},
       v{0.9f, 0.9f, 0.92f}, v{0.45f, 0.5f, 0.6f}, v{0.3f, 0.4f, 0.6f}, v{0.2f, 0.23f, 0.28f}},
  };
}

std::filesystem::path Scene::resolvePath(const std::string& path) const {
  std::filesystem::path p(path);
  return p.is_relative() && !baseDir.empty() ? baseDir / p : p;
}

Scene Scene::withAbsolutePaths() const {
  Scene out = *this;
  for (std::string* key : {&out.highClouds.coverMap, &out.highClouds.coefficients,
                           &out.highClouds.normals, &out.weather.image, &out.weather.file}) {
    if (key->empty()) continue;
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::absolute(resolvePath(*key), ec);
    if (!ec) *key = p.lexically_normal().string();
  }
  return out;
}

std::vector<SceneInputFile> sceneInputFiles(const Scene& scene) {
  std::vector<SceneInputFile> files;
  auto add = [&](const char* key, const std::string& written) {
    if (!written.empty()) files.push_back({key, written, scene.resolvePath(written)});
  };
  const HighCloudSettings& h = scene.highClouds;
  if (h.source == HighCloudSource::Image) {
    add("high_clouds.coefficients", h.coefficients);
    add("high_clouds.normals", h.normals);
  } else {
    add("high_clouds.cover_map", h.coverMap);
  }
  const WeatherSettings& w = scene.weather;
  if (w.source == WeatherMapSource::Image) add("weather.image", w.image);
  if (w.source == WeatherMapSource::File && w.file.find_first_of("*?") == std::string::npos)
    add("weather.file", w.file);
  return files;
}

glm::dvec2 windEastNorthMs(const CloudSettings& clouds) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const double toward = (clouds.windFrom + 180.0) * kDeg;
  return clouds.windSpeedMs * glm::dvec2(std::sin(toward), std::cos(toward));
}

WeatherInputs weatherInputs(const Scene& scene) {
  WeatherInputs in;
  in.settings = scene.weather;
  if (!scene.weather.image.empty()) in.image = scene.resolvePath(scene.weather.image);
  if (!scene.weather.file.empty()) in.file = scene.resolvePath(scene.weather.file);
  in.cameraLatLonDeg = {scene.camera.latitude, scene.camera.longitude};
  in.windMs = windEastNorthMs(scene.clouds);
  in.start = scene.time.start;
  return in;
}

}  // namespace sky
