#include "engine/weather/weather_map.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include <glm/common.hpp>
#include <glm/trigonometric.hpp>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"
#include "engine/weather/cloud_layers_from_fields.h"
#include "engine/weather/detail/cover_noise.h"
#include "engine/weather/geo.h"
#include "engine/weather/grib_reader.h"
#include "engine/weather/netcdf_reader.h"
#include "engine/weather/weather_region.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using namespace weather_detail;

// Cover = clamp(s + kSpreadAmplitude * spread * z, 0, 1) with z the standardised fbm: at
// spread 1 a mean-0.5 map runs from 0 to 1 over z in [-1, 1] (about two thirds of the map)
// and is clamped beyond, so it holds clear sky, overcast and everything between.
constexpr double kSpreadAmplitude = 0.5;

// Noise streams of the two layers: decorrelated fields from one seed.
constexpr uint32_t kLowStream = 0x4c4f57u;  // "LOW"
constexpr uint32_t kMidStream = 0x4d4944u;  // "MID"

[[noreturn]] void imageError(const std::string& written, const std::string& what) {
  inputError("weather.image: " + written + ": " + what);
}

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

WeatherMap readImageMap(const WeatherInputs& in, const WeatherRegion& region) {
  const std::string& written = in.settings.image;
  if (written.empty()) inputError("weather.image: is required when source is image");
  const fs::path& path = in.image;
  if (const std::string why = notARegularFile(path); !why.empty())
    imageError(written, why + " (" + path.string() + ")");
  const std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".exr") imageError(written, "must be a PNG or EXR file");

  WeatherMap map;
  map.region = region;
  std::vector<float> pixels;
  size_t channels = 0;
  try {
    if (ext == ".png") {
      const Image8 png = readPng(path);
      map.width = uint32_t(png.width);
      map.height = uint32_t(png.height);
      channels = size_t(png.channels);
      pixels.resize(png.pixels.size());
      for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = float(png.pixels[i]) / 255.0f;
    } else {
      LayeredImage exr = readExr(path);
      // The main layer (R, G, B, A), or the only layer of a file written with a prefix.
      const ImageLayer* layer = exr.find("");
      if (!layer && exr.layers.size() == 1) layer = &exr.layers.front();
      if (!layer) imageError(written, "has no main layer (channels R, G, B, A)");
      map.width = uint32_t(exr.width);
      map.height = uint32_t(exr.height);
      channels = layer->channels.size();
      pixels = layer->pixels;
    }
  } catch (const Error& e) {
    // The reader names the resolved path; keep one short line that names the key instead.
    std::string what = e.what();
    const std::string prefix = path.string() + ": ";
    if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
    imageError(written, what);
  }
  if (channels != 4)
    imageError(written,
               "must be RGBA (4 channels: low cover, mid cover, type, density "
               "scale), has " +
                   std::to_string(channels));
  if (map.width == 0 || map.height == 0) imageError(written, "is empty");

  static const char* kNames[4] = {"R (low cover)", "G (mid cover)", "B (cloud type)",
                                  "A (density scale)"};
  map.texels.resize(size_t(map.width) * map.height);
  for (size_t i = 0; i < map.texels.size(); ++i) {
    for (int c = 0; c < 4; ++c) {
      const float v = pixels[i * 4 + size_t(c)];
      const bool bad = !std::isfinite(v) || v < 0.0f || (c < 3 && v > 1.0f);
      if (bad) {
        char text[160];
        std::snprintf(text, sizeof text, "%s value %g at pixel (%zu, %zu) is outside %s", kNames[c],
                      double(v), i % map.width, i / map.width, c < 3 ? "[0, 1]" : "[0, inf)");
        imageError(written, text);
      }
      map.texels[i][c] = v;
    }
  }
  return map;
}

// Runs body(row) for every row on a few threads: a large map's fbm takes seconds on one.
template <class F>
void forEachRow(uint32_t rows, F body) {
  const uint32_t workers =
      std::clamp(std::thread::hardware_concurrency(), 1u, std::max(1u, rows / 16u));
  std::vector<std::thread> threads;
  for (uint32_t w = 0; w < workers; ++w)
    threads.emplace_back([=, &body] {
      for (uint32_t row = w; row < rows; row += workers) body(row);
    });
  for (std::thread& t : threads) t.join();
}

WeatherMap proceduralMap(const WeatherSettings& w, const WeatherRegion& region) {
  if (!(w.scaleKm > 0.0)) inputError("weather.scale_km: must be above 0");
  const glm::uvec2 size = proceduralMapSize(w, region);
  WeatherMap map;
  map.region = region;
  map.width = size.x;
  map.height = size.y;
  const size_t count = size_t(size.x) * size.y;
  const float type = cloudTypeValue(w.cloudType);

  // Standardised fbm per layer at every texel centre, then calibrated to the asked mean.
  std::vector<float> low(count, 0.0f), mid(count, 0.0f);
  const bool needLow = w.coverLow > 0.0 && w.coverLow < 1.0 && w.spread > 0.0;
  const bool needMid = w.coverMid > 0.0 && w.coverMid < 1.0 && w.spread > 0.0;
  if (needLow || needMid) {
    const uint32_t lowSeed = hashIntegers({uint32_t(w.seed), kLowStream});
    const uint32_t midSeed = hashIntegers({uint32_t(w.seed), kMidStream});
    forEachRow(size.y, [&](uint32_t y) {
      const double lat = region.lat[1] - (y + 0.5) / size.y * (region.lat[1] - region.lat[0]);
      for (uint32_t x = 0; x < size.x; ++x) {
        const double lon = region.lon[0] + (x + 0.5) / size.x * (region.lon[1] - region.lon[0]);
        const glm::dvec3 unit = enuToEcefRotation(lat, lon)[2];
        const size_t i = size_t(y) * size.x + x;
        if (needLow) low[i] = float(standardFbmOnEarth(unit, w.scaleKm, lowSeed));
        if (needMid) mid[i] = float(standardFbmOnEarth(unit, w.scaleKm, midSeed));
      }
    });
  }
  const double amplitude = kSpreadAmplitude * w.spread;
  calibrateCover(low, w.coverLow, amplitude);
  calibrateCover(mid, w.coverMid, amplitude);

  map.texels.resize(count);
  for (size_t i = 0; i < count; ++i) map.texels[i] = glm::vec4(low[i], mid[i], type, 1.0f);
  return map;
}

}  // namespace

// GRIB by its extension or its "GRIB" magic, NetCDF by ".nc"/".nc4" or the classic
// ("CDF\1", "CDF\2", "CDF\5") or HDF5 (NetCDF-4) signature.
namespace {

// One forecast file, by its extension or signature. `written` is how the scene names it.
WeatherFields readOneWeatherFile(const fs::path& path, const std::string& written) {
  if (const std::string why = notARegularFile(path); !why.empty())
    inputError("weather.file: " + written + ": " + why + " (" + path.string() + ")");
  const std::string ext = lowerExtension(path);
  char magic[8] = {};
  std::ifstream(path, std::ios::binary).read(magic, sizeof magic);
  const std::string head(magic, sizeof magic);
  const bool grib = ext == ".grib2" || ext == ".grb2" || ext == ".grib" || ext == ".grb" ||
                    head.compare(0, 4, "GRIB") == 0;
  const bool netcdf = ext == ".nc" || ext == ".nc4" || head.compare(0, 3, "CDF") == 0 ||
                      head.compare(0, 8, "\x89HDF\r\n\x1a\n") == 0;
  if (!grib && !netcdf)
    inputError("weather.file: " + written +
               ": not a GRIB or NetCDF file (extension .grib2/.grb2/.grib/.grb or .nc/.nc4, or "
               "the format's signature)");
  try {
    return grib ? readGrib2(path) : readNetcdf(path);
  } catch (const Error& e) {
    // The readers name the file; say which key it came from.
    if (e.kind() == ErrorKind::BadInput) inputError(std::string("weather.file: ") + e.what());
    throw;
  }
}

bool isPattern(const std::string& name) {
  return name.find_first_of("*?") != std::string::npos;
}

// Shell-style match of '*' (any run) and '?' (one character), as fnmatch without flags.
bool matches(std::string_view pattern, std::string_view name) {
  size_t p = 0, n = 0, starP = std::string_view::npos, starN = 0;
  while (n < name.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == name[n])) {
      ++p, ++n;
    } else if (p < pattern.size() && pattern[p] == '*') {
      starP = p++, starN = n;
    } else if (starP != std::string_view::npos) {
      p = starP + 1, n = ++starN;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

}  // namespace

std::vector<fs::path> weatherFiles(const WeatherInputs& in) {
  const fs::path& path = in.file;
  const std::string name = path.filename().string();
  if (!isPattern(name)) return {path};
  if (isPattern(path.parent_path().string()))
    inputError("weather.file: " + in.settings.file +
               ": only the file name may hold '*' or '?', not its folder");
  std::vector<fs::path> found;
  std::error_code ec;
  for (fs::directory_iterator it(path.parent_path(), ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec) && matches(name, it->path().filename().string()))
      found.push_back(it->path());
  std::sort(found.begin(), found.end());
  return found;
}

WeatherFields readWeatherFile(const WeatherInputs& in) {
  const std::string& written = in.settings.file;
  if (written.empty()) inputError("weather.file: is required when source is file");
  const std::vector<fs::path> files = weatherFiles(in);
  if (files.empty())
    inputError("weather.file: " + written + ": no file matches (" + in.file.string() + ")");
  if (files.size() == 1)
    return readOneWeatherFile(files[0], isPattern(written) ? files[0].string() : written);

  // Several files (one per forecast step, as GFS ships them): one grid, steps merged in time.
  WeatherFields all = readOneWeatherFile(files[0], files[0].string());
  all.file = written;
  for (size_t i = 1; i < files.size(); ++i) {
    WeatherFields more = readOneWeatherFile(files[i], files[i].string());
    if (more.grid.nx != all.grid.nx || more.grid.ny != all.grid.ny ||
        more.grid.latDeg != all.grid.latDeg || more.grid.lonDeg != all.grid.lonDeg)
      inputError("weather.file: " + files[i].filename().string() + " is on a different grid (" +
                 std::to_string(more.grid.nx) + " x " + std::to_string(more.grid.ny) + ") than " +
                 files[0].filename().string() + " (" + std::to_string(all.grid.nx) + " x " +
                 std::to_string(all.grid.ny) + "); the files of one pattern must share a grid");
    for (WeatherStep& step : more.steps) {
      for (const WeatherStep& have : all.steps)
        if (have.validTimeUnix == step.validTimeUnix)
          inputError("weather.file: " + files[i].filename().string() +
                     " repeats a valid time another matching file has (" +
                     IsoTime{int64_t(step.validTimeUnix), 0.0, 0}.format() + ")");
      all.steps.push_back(std::move(step));
    }
  }
  std::sort(all.steps.begin(), all.steps.end(), [](const WeatherStep& a, const WeatherStep& b) {
    return a.validTimeUnix < b.validTimeUnix;
  });
  return all;
}

glm::vec4 WeatherMap::sample(double latDeg, double lonDeg) const {
  if (width == 0 || height == 0 || texels.size() != size_t(width) * height) return glm::vec4(0.0f);
  glm::dvec2 uv;
  regionUv(region, latDeg, lonDeg, uv);
  // Texel centres at (i + 0.5) / size: the continuous texel coordinate is uv * size - 0.5,
  // clamped like a clamp-to-edge sampler.
  const double fx = std::clamp(uv.x * width - 0.5, 0.0, double(width - 1));
  const double fy = std::clamp(uv.y * height - 0.5, 0.0, double(height - 1));
  const uint32_t x0 = uint32_t(fx), y0 = uint32_t(fy);
  const uint32_t x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
  const float tx = float(fx - x0), ty = float(fy - y0);
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), tx), glm::mix(at(x0, y1), at(x1, y1), tx), ty);
}

glm::vec2 WeatherMap::maxCover() const {
  glm::vec2 m(0.0f);
  for (const glm::vec4& t : texels) m = glm::max(m, glm::vec2(t));
  return m;
}

float cloudTypeValue(CloudType type) {
  switch (type) {
    case CloudType::Stratus:
    case CloudType::Altostratus:
      return 0.0f;
    case CloudType::Stratocumulus:
    case CloudType::Altocumulus:
      return 0.5f;
    case CloudType::Cumulus:
      return 1.0f;
  }
  internalError("weather map: no cloud type " + std::to_string(static_cast<int>(type)));
}

glm::uvec2 proceduralMapSize(const WeatherSettings& weather, const WeatherRegion& region) {
  if (weather.resolution < 2) inputError("weather.resolution: must be at least 2");
  const glm::dvec2 km = regionSizeKm(region);
  const double longer = std::max(km.x, km.y), shorter = std::min(km.x, km.y);
  const auto n = uint32_t(weather.resolution);
  const auto other = uint32_t(std::max(2.0, std::round(n * shorter / longer)));
  return km.x >= km.y ? glm::uvec2(n, other) : glm::uvec2(other, n);
}

WeatherMap makeWeatherMap(const WeatherInputs& in, const WeatherRegion& r) {
  const WeatherSettings& w = in.settings;
  if (!(r.lat[0] < r.lat[1]) || r.lat[0] < -90.0 || r.lat[1] > 90.0)
    inputError("weather.region.lat: [south, north] must rise within [-90, 90]");
  if (!(r.lon[0] < r.lon[1]) || r.lon[1] - r.lon[0] > 360.0)
    inputError("weather.region.lon: [west, east] must rise and span at most 360 degrees");
  switch (w.source) {
    case WeatherMapSource::Image:
      return readImageMap(in, r);
    case WeatherMapSource::Procedural:
      return proceduralMap(w, r);
    case WeatherMapSource::File:
      break;
  }
  const WeatherFields fields = readWeatherFile(in);
  // The forecast valid at the scene's time (its start for a time-lapse).
  return weatherMapFromFields(fields, double(in.start.unixSeconds), w, r);
}

WeatherMap makeWeatherMap(const WeatherInputs& in) {
  if (in.settings.source != WeatherMapSource::File) return makeWeatherMap(in, mapRegion(in));
  const WeatherFields fields = readWeatherFile(in);
  const WeatherRegion data = dataRegion(fields.grid);
  return weatherMapFromFields(fields, double(in.start.unixSeconds), in.settings,
                              mapRegion(in, &data));
}

}  // namespace sky
