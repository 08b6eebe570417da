#include "engine/dataset/dataset_spec.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/sha256.h"
#include "engine/scene/config_tree.h"
#include "engine/scene/detail/scene_reader.h"
#include "engine/scene/detail/scene_writer.h"
#include "engine/scene/detail/schema_builder.h"
#include "engine/scene/scene_io.h"

namespace sky {
namespace {

// A spec is a few dozen lines; a cap keeps a wrong path (a huge file, a device) from taking
// all memory in the YAML parser.
constexpr std::uintmax_t kMaxSpecBytes = 1u << 20;

// SplitMix64's finaliser (Steele, Lea & Flood 2014): a bijection that spreads every input bit.
uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// The draw of `key` for sample `index`: uniform in [0, 1), from (seed, index, key) alone.
// Counter-based, so any sample's draws are made without the ones before it, and each key has
// its own stream (a range added to the spec leaves the other keys' draws as they were).
class Draws {
public:
  Draws(int seed, int64_t index) : mBase(mix(mix(uint64_t(uint32_t(seed))) ^ uint64_t(index))) {}
  double uniform(std::string_view key) const {
    return double(mix(mBase ^ hash64(key)) >> 11) * 0x1.0p-53;
  }
  double in(std::string_view key, const glm::dvec2& range) const {
    return range.x + uniform(key) * (range.y - range.x);
  }
  // A whole number in [range.x, range.y] (rounded inward), each equally likely.
  int64_t integer(std::string_view key, const glm::dvec2& range) const {
    const auto lo = static_cast<int64_t>(std::ceil(std::min(range.x, range.y)));
    const auto hi = static_cast<int64_t>(std::floor(std::max(range.x, range.y)));
    if (hi <= lo) return lo;
    return lo + std::min<int64_t>(static_cast<int64_t>(uniform(key) * double(hi - lo + 1)), hi - lo);
  }
  template <class T>
  const T& choice(std::string_view key, const std::vector<T>& options) const {
    const auto n = static_cast<int64_t>(options.size());
    return options[size_t(std::min<int64_t>(static_cast<int64_t>(uniform(key) * double(n)), n - 1))];
  }

private:
  uint64_t mBase;
};

void draw(const Draws& d, std::string_view key, const std::optional<glm::dvec2>& range,
          double& value) {
  if (range) value = d.in(key, *range);
}

}  // namespace

DatasetSpec loadDatasetSpec(const std::filesystem::path& path) {
  const ConfigFormat format = formatForPath(path);
  const std::string text = readTextFile(path, kMaxSpecBytes);
  const ConfigNode root = format == ConfigFormat::Yaml ? parseYamlTree(text, path.string())
                                                       : parseJsonTree(text, path.string());
  if (!root.isMap())
    inputError(path.string() + ": a dataset spec is a map of keys (count, seed, camera, ...)");
  DatasetSpec spec;
  detail::SceneReader::read(root, "", spec);
  spec.baseDir = path.parent_path();
  return spec;
}

Scene datasetBaseScene(const DatasetSpec& spec, const Scene& builtIn) {
  if (spec.scene.empty()) return builtIn.withAbsolutePaths();
  const std::filesystem::path file = spec.baseDir / spec.scene;
  return loadSceneFile(file).withAbsolutePaths();
}

Scene datasetSampleScene(const DatasetSpec& spec, const Scene& base, int64_t index) {
  if (index < 0 || index >= spec.count)
    internalError("dataset: sample " + std::to_string(index) + " outside the spec's count");
  const Draws d(spec.seed, index);
  Scene s = base;
  char name[32];
  std::snprintf(name, sizeof name, "sample_%06lld", static_cast<long long>(index));
  s.output.name = name;
  s.output.width = spec.output.width;
  s.output.height = spec.output.height;
  s.output.perception = spec.output.perception;

  const DatasetCamera& c = spec.camera;
  draw(d, "camera.latitude", c.latitude, s.camera.latitude);
  draw(d, "camera.longitude", c.longitude, s.camera.longitude);
  draw(d, "camera.altitude_m", c.altitudeM, s.camera.altitudeM);
  draw(d, "camera.heading", c.heading, s.camera.heading);
  draw(d, "camera.pitch", c.pitch, s.camera.pitch);
  draw(d, "camera.vertical_fov", c.verticalFov, s.camera.verticalFov);

  // One instant: a sample is a still, never a time-lapse.
  IsoTime instant = base.time.start;
  if (spec.time.from && spec.time.to) {
    const double span = spec.time.to->secondsSince(*spec.time.from);
    instant = spec.time.from->plusSeconds(std::round(d.uniform("time") * span));
  }
  s.time = TimeSettings{};
  s.time.start = instant;

  const DatasetWeather& w = spec.weather;
  if (!w.files.empty()) {
    s.weather.source = WeatherMapSource::File;
    s.weather.file = (spec.baseDir / d.choice("weather.file", w.files)).lexically_normal().string();
    if (!s.weather.file.empty() && std::filesystem::path(s.weather.file).is_relative())
      s.weather.file = std::filesystem::absolute(s.weather.file).lexically_normal().string();
  } else if (w.coverLow || w.coverMid || w.seed || !w.cloudTypes.empty()) {
    s.weather.source = WeatherMapSource::Procedural;
    draw(d, "weather.cover_low", w.coverLow, s.weather.coverLow);
    draw(d, "weather.cover_mid", w.coverMid, s.weather.coverMid);
    if (w.seed) s.weather.seed = static_cast<int>(d.integer("weather.seed", *w.seed));
    if (!w.cloudTypes.empty()) s.weather.cloudType = d.choice("weather.cloud_type", w.cloudTypes);
  }
  return s;
}

std::string datasetSpecChecksum(const DatasetSpec& spec, const Scene& base) {
  DatasetSpec copy = spec;  // the description takes mutable references
  ConfigNode root = ConfigNode::makeMap({});
  detail::SceneWriter::write(root, copy);
  return sha256Hex(detail::toJsonText(root) + "\n" + writeScene(base, ConfigFormat::Json));
}

std::string datasetJsonSchema() {
  return detail::SchemaBuilder::documentText<DatasetSpec>(
      "skylayers dataset spec",
      "A dataset spec for skyrender dataset (YAML or JSON): a base scene, the ranges and "
      "choices each sample draws from (seed, index), the size and outputs, a count and a "
      "seed (docs/datasets.md).");
}

}  // namespace sky
