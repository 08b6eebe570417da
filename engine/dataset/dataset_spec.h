#pragma once
// A dataset spec (`skyrender dataset SPEC`, docs/datasets.md): a base scene, what varies from
// sample to sample (ranges and choices of place, time, weather and camera), the size and
// outputs, a sample count and a seed. Sample k's scene is made from (seed, k) alone
// (datasetSampleScene), so any process renders it bit for bit the same, alone or in a shard.
// Read strictly like a scene, by the same description (describe() below), with its own
// JSON Schema (configs/schema/dataset.schema.json).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "engine/scene/field_rules.h"
#include "engine/scene/scene.h"

namespace sky {

// Each range is [from, to], drawn uniformly; absent, the base scene's value stays.
struct DatasetCamera {
  std::optional<glm::dvec2> latitude, longitude, altitudeM, heading, pitch, verticalFov;
  bool operator==(const DatasetCamera&) const = default;
};

// An instant drawn uniformly in [from, to], to the whole second; absent, the base scene's.
struct DatasetTime {
  std::optional<IsoTime> from, to;
  bool operator==(const DatasetTime&) const = default;
};

struct DatasetWeather {
  // Forecast files, one chosen per sample (weather.source file); relative to the spec.
  std::vector<std::string> files;
  // Or the procedural map: covers drawn in ranges, a type chosen, a seed drawn (an integer).
  std::optional<glm::dvec2> coverLow, coverMid, seed;
  std::vector<CloudType> cloudTypes;
  bool operator==(const DatasetWeather&) const = default;
};

// What each sample writes: always its EXR and its scene; the PNG unless `png` is false; the
// perception layers unless `perception` is false.
struct DatasetOutput {
  int width = 64, height = 36;
  bool png = true;
  bool perception = true;
  bool operator==(const DatasetOutput&) const = default;
};

struct DatasetSpec {
  std::string scene;  // the base scene file, relative to the spec; "" the built-in scene
  int count = 1;      // samples
  int seed = 0;
  DatasetOutput output;
  DatasetCamera camera;
  DatasetTime time;
  DatasetWeather weather;
  std::filesystem::path baseDir;  // the spec's folder (not a key)
  bool operator==(const DatasetSpec&) const = default;
};

template <class V>
void describe(V& v, DatasetCamera& s) {
  v.field("latitude", s.latitude, NumberRange{-90, 90}, "[from, to] degrees north");
  v.field("longitude", s.longitude, NumberRange{-180, 180}, "[from, to] degrees east");
  v.field("altitude_m", s.altitudeM, NumberRange{-500, 100000},
          "[from, to] metres above sea level");
  v.field("heading", s.heading, NumberRange{-360, 360},
          "[from, to] degrees clockwise from north");
  v.field("pitch", s.pitch, NumberRange{-90, 90}, "[from, to] degrees above the horizon");
  v.field("vertical_fov", s.verticalFov, NumberRange{1, 179}, "[from, to] degrees");
}

template <class V>
void describe(V& v, DatasetTime& s) {
  v.field("from", s.from, "the earliest instant, ISO 8601 with a zone");
  v.field("to", s.to, "the latest instant, ISO 8601 with a zone");
  v.bothOrNeither("from", "to");
  v.check("to", !s.from || !s.to || s.to->secondsSince(*s.from) >= 0.0,
          "must not be before from");
}

template <class V>
void describe(V& v, DatasetWeather& s) {
  v.field("files", s.files, TextRule{1, 4096},
          "forecast files (GRIB2 or NetCDF), one chosen per sample, relative to the spec");
  v.field("cover_low", s.coverLow, NumberRange{0, 1}, "[from, to] procedural low-layer cover");
  v.field("cover_mid", s.coverMid, NumberRange{0, 1}, "[from, to] procedural mid-layer cover");
  v.field("cloud_types", s.cloudTypes, "procedural cloud types, one chosen per sample");
  v.field("seed", s.seed, NumberRange{0, 2147483647},
          "[from, to] procedural noise seeds, a whole number drawn per sample");
  v.check("files",
          s.files.empty() ||
              (!s.coverLow && !s.coverMid && !s.seed && s.cloudTypes.empty()),
          "a forecast file or the procedural map's ranges, not both");
}

template <class V>
void describe(V& v, DatasetOutput& s) {
  v.field("width", s.width, NumberRange{1, 16384}, "image width in pixels");
  v.field("height", s.height, NumberRange{1, 16384}, "image height in pixels");
  v.field("png", s.png, "also write each sample's display PNG");
  v.field("perception", s.perception,
          "the perception layers in each EXR (docs/outputs.md): labels, optical depth, ...");
}

template <class V>
void describe(V& v, DatasetSpec& s) {
  v.field("scene", s.scene, TextRule{0, 4096},
          "the base scene file (YAML or JSON), relative to the spec; absent: the built-in scene");
  v.field("count", s.count, NumberRange{1, 10000000}, "how many samples");
  v.field("seed", s.seed, NumberRange{0, 2147483647},
          "the dataset's seed: sample k's scene comes from (seed, k) alone");
  v.section("output", s.output, "each sample's size and files");
  v.section("camera", s.camera, "ranges of the camera's place and view");
  v.section("time", s.time, "the range of instants");
  v.section("weather", s.weather, "forecast files, or the procedural map's ranges");
}

// Loads a spec file (YAML or JSON; BadInput naming file, line and key path). The base scene
// is not read here (datasetBaseScene).
DatasetSpec loadDatasetSpec(const std::filesystem::path& path);
// The spec's base scene, with its paths made absolute: its `scene` file, or `builtIn` (the
// apps' embedded default scene) when it names none.
Scene datasetBaseScene(const DatasetSpec& spec, const Scene& builtIn);
// Sample `index`'s scene: the base with each range and choice drawn from (spec.seed, index)
// (a counter-based hash per key, so adding a range leaves the others' draws as they were),
// an instant (no time-lapse), the spec's size and perception, and no temporal reuse.
Scene datasetSampleScene(const DatasetSpec& spec, const Scene& base, int64_t index);
// A checksum of the spec as read (its keys written out, defaults filled in) and of its base
// scene: every manifest line carries it, so a folder never mixes two datasets' samples.
std::string datasetSpecChecksum(const DatasetSpec& spec, const Scene& base);
// JSON Schema text of the spec format (configs/schema/dataset.schema.json is a copy).
std::string datasetJsonSchema();

}  // namespace sky
