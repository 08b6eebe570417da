#include "engine/weather/cloud_layers_from_fields.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <unordered_map>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "engine/core/error.h"
#include "engine/weather/geo.h"

namespace sky {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ICAO standard atmosphere (Doc 7488): sea-level pressure and temperature, the tropospheric
// lapse rate, the tropopause at 11 km and the gas constant of dry air.
constexpr double kP0Hpa = 1013.25;
constexpr double kT0K = 288.15;
constexpr double kLapseKPerM = 0.0065;
constexpr double kTropopauseM = 11000.0;
constexpr double kGravity = 9.80665;
constexpr double kGasConstant = 287.05287;  // J / (kg K)

// The size of the sample map whose mean stands for a field's region mean: enough texels to
// see every data cell of a continental region, few enough to cost nothing.
constexpr uint32_t kMeanMapSize = 48;

std::string fileName(const WeatherFields& fields) {
  const std::string name = fields.file.filename().string();
  return name.empty() ? std::string("the weather file") : name;
}

std::string formatNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::string formatLevels(const std::vector<double>& levels) {
  std::string out;
  for (double p : levels) out += (out.empty() ? "" : ", ") + formatNumber(p);
  return out;
}

// Runs body(row) for rows [0, rows) on a few threads.
void forEachRow(uint32_t rows, const std::function<void(uint32_t)>& body) {
  const uint32_t workers =
      std::clamp(std::thread::hardware_concurrency(), 1u, std::max(1u, rows / 16u));
  if (workers == 1) {
    for (uint32_t row = 0; row < rows; ++row) body(row);
    return;
  }
  std::vector<std::thread> threads;
  for (uint32_t w = 0; w < workers; ++w)
    threads.emplace_back([=, &body] {
      for (uint32_t row = w; row < rows; row += workers) body(row);
    });
  for (std::thread& t : threads) t.join();
}

// The map's texel centres (row 0 north, column 0 west), as weather_map.h defines them.
double texelLat(const WeatherRegion& r, uint32_t y, uint32_t height) {
  return r.lat[1] - (y + 0.5) / height * (r.lat[1] - r.lat[0]);
}
double texelLon(const WeatherRegion& r, uint32_t x, uint32_t width) {
  return r.lon[0] + (x + 0.5) / width * (r.lon[1] - r.lon[0]);
}

[[noreturn]] void outsideData(double lat0, double lat1, double lon0, double lon1) {
  inputError("weather.region: lies outside the data (grid covers lat " + formatNumber(lat0) + ".." +
             formatNumber(lat1) + ", lon " + formatNumber(lon0) + ".." + formatNumber(lon1) + ")");
}

// Catmull-Rom weights of the four samples around a point at fraction t past the second.
std::array<double, 4> catmullRom(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {0.5 * (-t3 + 2.0 * t2 - t), 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
          0.5 * (-3.0 * t3 + 4.0 * t2 + t), 0.5 * (t3 - t2)};
}

// The four source indices and weights of one map row or column.
struct Taps {
  std::array<uint32_t, 4> index{};
  std::array<double, 4> weight{};
};

// Taps at fractional index f on an axis of n samples; `wrap` joins the ends (a global
// longitude axis), else indices clamp at the edges (the edge value repeats).
Taps axisTaps(double f, uint32_t n, bool wrap) {
  Taps taps;
  const double base = std::floor(f);
  const std::array<double, 4> w = catmullRom(f - base);
  for (int k = 0; k < 4; ++k) {
    auto i = static_cast<int64_t>(base) - 1 + k;
    if (wrap) {
      i %= static_cast<int64_t>(n);
      if (i < 0) i += n;
    } else {
      i = std::clamp<int64_t>(i, 0, int64_t(n) - 1);
    }
    taps.index[size_t(k)] = uint32_t(i);
    taps.weight[size_t(k)] = w[size_t(k)];
  }
  return taps;
}

// The fractional index of `v` on monotonic coordinates `c` (either direction), clamped to
// [0, n - 1].
double fractionalIndex(const std::vector<double>& c, double v) {
  const size_t n = c.size();
  if (n < 2) return 0.0;
  const bool ascending = c.back() > c.front();
  const auto before = [&](double a, double b) { return ascending ? a < b : a > b; };
  if (!before(c.front(), v)) return 0.0;
  if (!before(v, c.back())) return double(n - 1);
  // The last i with c[i] at or before v.
  size_t lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    if (before(v, c[mid]))
      hi = mid;
    else
      lo = mid;
  }
  return double(lo) + (v - c[lo]) / (c[lo + 1] - c[lo]);
}

bool strictlyMonotonic(const std::vector<double>& c) {
  if (c.size() < 2) return true;
  const bool ascending = c[1] > c[0];
  for (size_t i = 1; i < c.size(); ++i)
    if (ascending ? !(c[i] > c[i - 1]) : !(c[i] < c[i - 1])) return false;
  return true;
}

glm::dvec3 unitVector(double latDeg, double lonDeg) {
  return enuToEcefRotation(latDeg, lonDeg)[2];
}

// Resamples fields on one grid onto one map; built once, applied to every field.
class GridResampler {
public:
  GridResampler(const GridGeometry& grid, const WeatherRegion& region, uint32_t width,
                uint32_t height)
      : mGrid(grid), mRegion(region), mWidth(width), mHeight(height) {
    if (width == 0 || height == 0) internalError("resampling onto an empty map");
    if (grid.size() == 0 || grid.lonDeg.size() != grid.size())
      internalError("resampling a grid without points");
    if (!(grid.regularLatLon && grid.nx * size_t(grid.ny) == grid.size() && setUpRegular()))
      setUpScattered();
  }

  std::vector<float> apply(std::span<const float> values, bool clampUnit) const {
    if (values.size() != mGrid.size())
      internalError("field of " + std::to_string(values.size()) + " values on a grid of " +
                    std::to_string(mGrid.size()) + " points");
    std::vector<float> out(size_t(mWidth) * mHeight);
    forEachRow(mHeight, [&](uint32_t y) {
      for (uint32_t x = 0; x < mWidth; ++x) {
        const double v = mRegular ? regularValue(values, x, y) : scatteredValue(values, x, y);
        out[size_t(y) * mWidth + x] = float(clampUnit ? std::clamp(v, 0.0, 1.0) : v);
      }
    });
    return out;
  }

private:
  // Index-space Catmull-Rom: the taps of every map column and row, once. Returns false when
  // the coordinates are not monotonic after all (the scattered method then takes over).
  bool setUpRegular() {
    const uint32_t nx = mGrid.nx, ny = mGrid.ny;
    std::vector<double> lats(ny), lons(nx);
    for (uint32_t j = 0; j < ny; ++j) lats[j] = mGrid.latDeg[size_t(j) * nx];
    for (uint32_t i = 0; i < nx; ++i) lons[i] = mGrid.lonDeg[i];
    if (!strictlyMonotonic(lats) || !strictlyMonotonic(lons)) return false;

    const double latMin = std::min(lats.front(), lats.back());
    const double latMax = std::max(lats.front(), lats.back());
    const double lonMin = std::min(lons.front(), lons.back());
    const double lonMax = std::max(lons.front(), lons.back());
    // Global in longitude: uniform ascending columns whose spacing closes the circle.
    const double dLon = nx > 1 ? (lons.back() - lons.front()) / (nx - 1) : 0.0;
    const bool global = nx > 2 && dLon > 0.0 && std::fabs(nx * dLon - 360.0) < 1e-3 * dLon;
    constexpr double kEps = 1e-6;

    // Latitude cover: a global grid also covers the caps beyond its outermost rows when they
    // lie within a row or two of the pole (cell-centred grids stop short of 90).
    double coverSouth = latMin, coverNorth = latMax;
    if (global && ny > 1) {
      const double dLat = (latMax - latMin) / (ny - 1);
      if (latMax >= 90.0 - 1.5 * dLat) coverNorth = 90.0;
      if (latMin <= -90.0 + 1.5 * dLat) coverSouth = -90.0;
    }
    if (mRegion.lat[0] < coverSouth - kEps || mRegion.lat[1] > coverNorth + kEps)
      outsideData(latMin, latMax, lonMin, global ? lonMin + 360.0 : lonMax);
    // A non-global grid's columns, shifted by whole turns to hold the region.
    double shift = 0.0;
    if (!global) {
      bool inside = false;
      for (double k : {0.0, -360.0, 360.0, -720.0, 720.0}) {
        if (mRegion.lon[0] + k >= lonMin - kEps && mRegion.lon[1] + k <= lonMax + kEps) {
          shift = k;
          inside = true;
          break;
        }
      }
      if (!inside) outsideData(latMin, latMax, lonMin, lonMax);
    }

    mRows.resize(mHeight);
    for (uint32_t y = 0; y < mHeight; ++y)
      mRows[y] = axisTaps(fractionalIndex(lats, texelLat(mRegion, y, mHeight)), ny, false);
    mColumns.resize(mWidth);
    for (uint32_t x = 0; x < mWidth; ++x) {
      const double lon = texelLon(mRegion, x, mWidth) + shift;
      double f;
      if (global) {
        const double east = lon - lons.front();
        f = (east - 360.0 * std::floor(east / 360.0)) / dLon;
      } else {
        f = fractionalIndex(lons, lon);
      }
      mColumns[x] = axisTaps(f, nx, global);
    }
    mRegular = true;
    return true;
  }

  double regularValue(std::span<const float> values, uint32_t x, uint32_t y) const {
    const Taps& row = mRows[y];
    const Taps& col = mColumns[x];
    double sum = 0.0;
    for (size_t a = 0; a < 4; ++a) {
      const size_t rowStart = size_t(row.index[a]) * mGrid.nx;
      double line = 0.0;
      for (size_t b = 0; b < 4; ++b) line += col.weight[b] * values[rowStart + col.index[b]];
      sum += row.weight[a] * line;
    }
    return sum;
  }

  // Any grid: the points in a uniform 3D hash of their unit vectors; a texel takes modified
  // Shepard (Franke and Little) weights ((R - d) / (R d))^2 of the points within R, which
  // reproduce every data value exactly where a texel centre falls on its point and fall
  // smoothly (with their slope) to 0 at R, so nothing jumps as points enter or leave.
  void setUpScattered() {
    const size_t n = mGrid.size();
    mUnit.resize(n);
    double latMin = 90.0, latMax = -90.0, lonMin = 360.0, lonMax = -180.0;
    for (size_t k = 0; k < n; ++k) {
      const double lat = mGrid.latDeg[k], lon = mGrid.lonDeg[k];
      if (!std::isfinite(lat) || !std::isfinite(lon)) {
        mUnit[k] = glm::dvec3(kNaN);
        continue;
      }
      mUnit[k] = unitVector(lat, lon);
      latMin = std::min(latMin, lat);
      latMax = std::max(latMax, lat);
      lonMin = std::min(lonMin, lon);
      lonMax = std::max(lonMax, lon);
    }
    // A first hash with the spacing the points would have spread over the whole sphere
    // (never smaller than their real spacing): the typical distance to a point's fourth
    // neighbour, which on a quadrilateral grid is the spacing along the sparser axis.
    buildHash(std::sqrt(4.0 * 3.14159265358979 / double(n)));
    std::vector<double> fourth;
    const size_t stride = std::max<size_t>(1, n / 512);
    for (size_t k = 0; k < n; k += stride) {
      if (std::isnan(mUnit[k].x)) continue;
      std::vector<double> d;
      visitNear(mUnit[k], mCell, [&](size_t other, double dist) {
        if (other != k && dist > 1e-12) d.push_back(dist);
      });
      if (d.size() >= 4) {
        std::nth_element(d.begin(), d.begin() + 3, d.end());
        fourth.push_back(d[3]);
      }
    }
    double spacing = mCell;
    if (!fourth.empty()) {
      std::nth_element(fourth.begin(), fourth.begin() + fourth.size() / 2, fourth.end());
      spacing = fourth[fourth.size() / 2];
    }
    // Two and a half spacings: about twenty points per texel on a square grid.
    mRadius = 2.5 * spacing;
    buildHash(mRadius);
    mRegular = false;

    // Every texel centre needs a point within the radius: the region lies on the data.
    bool covered = true;
    for (uint32_t y = 0; y < mHeight && covered; ++y)
      for (uint32_t x = 0; x < mWidth && covered; ++x) {
        bool any = false;
        visitNear(unitVector(texelLat(mRegion, y, mHeight), texelLon(mRegion, x, mWidth)), mRadius,
                  [&](size_t, double) { any = true; });
        covered = any;
      }
    if (!covered) outsideData(latMin, latMax, lonMin, lonMax);
  }

  static int64_t cellOf(double c, double size) { return int64_t(std::floor(c / size)); }
  static uint64_t key(int64_t x, int64_t y, int64_t z) {
    constexpr int64_t kBias = int64_t(1) << 20;
    return (uint64_t(x + kBias) << 42) | (uint64_t(y + kBias) << 21) | uint64_t(z + kBias);
  }

  void buildHash(double cell) {
    // A unit vector's coordinates need 2 / cell cells per axis; 21 bits hold 2^20 cells each
    // way, which is a point spacing of about 12 m on the Earth.
    mCell = std::max(cell, 4.0 / double(int64_t(1) << 20));
    mHash.clear();
    for (size_t k = 0; k < mUnit.size(); ++k) {
      const glm::dvec3& u = mUnit[k];
      if (std::isnan(u.x)) continue;
      mHash[key(cellOf(u.x, mCell), cellOf(u.y, mCell), cellOf(u.z, mCell))].push_back(uint32_t(k));
    }
  }

  // Calls f(point, chord distance) for every point within `radius` (<= the cell size) of q.
  template <class F>
  void visitNear(const glm::dvec3& q, double radius, F&& f) const {
    const int64_t cx = cellOf(q.x, mCell), cy = cellOf(q.y, mCell), cz = cellOf(q.z, mCell);
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = mHash.find(key(cx + dx, cy + dy, cz + dz));
          if (it == mHash.end()) continue;
          for (uint32_t k : it->second) {
            const double d = glm::length(mUnit[k] - q);
            if (d <= radius) f(size_t(k), d);
          }
        }
  }

  double scatteredValue(std::span<const float> values, uint32_t x, uint32_t y) const {
    const glm::dvec3 q = unitVector(texelLat(mRegion, y, mHeight), texelLon(mRegion, x, mWidth));
    double sum = 0.0, weights = 0.0, exact = kNaN;
    visitNear(q, mRadius, [&](size_t k, double d) {
      // On a data point (closer than a millimetre on the Earth): its value, exactly.
      if (d < 1e-10) {
        exact = values[k];
        return;
      }
      const double w = (mRadius - d) / (mRadius * d);
      sum += w * w * values[k];
      weights += w * w;
    });
    if (!std::isnan(exact)) return exact;
    return weights > 0.0 ? sum / weights : 0.0;
  }

  const GridGeometry& mGrid;
  WeatherRegion mRegion;
  uint32_t mWidth, mHeight;
  bool mRegular = false;
  std::vector<Taps> mRows, mColumns;  // regular
  std::vector<glm::dvec3> mUnit;      // scattered
  std::unordered_map<uint64_t, std::vector<uint32_t>> mHash;
  double mCell = 0.0, mRadius = 0.0;
};

// The steps around `timeUnix` and the weight of the second.
struct Bracket {
  size_t first = 0, second = 0;
  double weight = 0.0;
};

Bracket bracketTime(const std::vector<WeatherStep>& steps, double timeUnix) {
  if (timeUnix <= steps.front().validTimeUnix) return {0, 0, 0.0};
  if (timeUnix >= steps.back().validTimeUnix) return {steps.size() - 1, steps.size() - 1, 0.0};
  size_t i = 0;
  while (steps[i + 1].validTimeUnix <= timeUnix) ++i;
  const double span = steps[i + 1].validTimeUnix - steps[i].validTimeUnix;
  const double w = span > 0.0 ? (timeUnix - steps[i].validTimeUnix) / span : 0.0;
  return w > 0.0 ? Bracket{i, i + 1, w} : Bracket{i, i, 0.0};
}

struct LayerSpec {
  const char* key;      // weather.<key>
  FieldKind tcc;        // the model's own cover of the layer
  const WeatherLevelSettings* levels;
};

// A field's values with NaN replaced: `fill` (clear sky for cover).
std::vector<float> withoutNaN(const std::vector<float>& values, float fill) {
  std::vector<float> out(values);
  for (float& v : out)
    if (std::isnan(v)) v = fill;
  return out;
}

// Cover of one layer at one step, per grid point.
std::vector<float> stepLayerCover(const WeatherFields& fields, const WeatherStep& step,
                                  const WeatherSettings& weather, const LayerSpec& layer) {
  const size_t n = fields.grid.size();
  const auto checkSize = [&](const LevelField& f) {
    if (f.values.size() != n)
      internalError(fileName(fields) + ": field " + fieldName(f.kind) + " has " +
                    std::to_string(f.values.size()) + " values on a grid of " + std::to_string(n));
  };
  if (weather.cover == WeatherCover::Tcc) {
    const LevelField* f = step.find(layer.tcc, 0.0);
    if (!f)
      inputError(std::string("weather.cover: tcc needs ") + fieldName(layer.tcc) +
                 " (the model's cloud cover of its " + layer.key + " layer), which " +
                 fileName(fields) + " does not have; use cover rh");
    checkSize(*f);
    std::vector<float> cover = withoutNaN(f->values, 0.0f);
    for (float& c : cover) c = std::clamp(c, 0.0f, 1.0f);
    return cover;
  }

  // Lu (1)(2) at every r level of the layer, combined by the maximum: a cloud at any level
  // of the layer hides the column from below and above (maximum overlap), so the layer is at
  // least as covered as its most covered level. Lu use a single level (400 hPa); summing
  // or a random-overlap product would count one deep cloud several times.
  const WeatherLevelSettings& s = *layer.levels;
  if (!(s.topHpa < s.bottomHpa))
    inputError(std::string("weather.") + layer.key + ".top_hpa: must be below bottom_hpa");
  const std::vector<double> all = step.levels(FieldKind::RelativeHumidity);
  std::vector<double> used;
  for (double p : all)
    if (p >= s.topHpa - 0.01 && p <= s.bottomHpa + 0.01) used.push_back(p);
  if (used.empty())
    inputError(std::string("weather.") + layer.key + ": " + fileName(fields) +
               " has no relative humidity (r) between " + formatNumber(s.topHpa) + " and " +
               formatNumber(s.bottomHpa) + " hPa (" +
               (all.empty() ? std::string("it has no r at all")
                            : "r levels: " + formatLevels(all) + " hPa") +
               ")");
  std::vector<float> cover(n, 0.0f);
  const auto rhCritical = float(s.rhCritical);
  for (double p : used) {
    const LevelField& f = *step.find(FieldKind::RelativeHumidity, p);
    checkSize(f);
    for (size_t k = 0; k < n; ++k)
      cover[k] = std::max(cover[k], humidityCover(f.values[k], rhCritical));
  }
  return cover;
}

// The region means of gh at one step, per level, found once and shared by the six bounds.
class HeightMeans {
public:
  HeightMeans(const WeatherFields& fields, const WeatherStep& step, const WeatherRegion& region)
      : mFields(fields), mStep(step), mRegion(region) {
    for (double p : step.levels(FieldKind::GeopotentialHeight)) {
      const LevelField& f = *step.find(FieldKind::GeopotentialHeight, p);
      if (f.values.size() == fields.grid.size() &&
          std::any_of(f.values.begin(), f.values.end(), [](float v) { return std::isfinite(v); }))
        mLevels.push_back(p);  // descending: surface first
    }
  }

  // Altitude of pressure p, m: gh interpolated in log pressure between the file's levels
  // (the hypsometric equation with a constant mean temperature between two levels); beyond
  // them the standard atmosphere's thickness from the nearest level.
  double altitude(double p) {
    if (mLevels.empty()) return standardAtmosphereAltitudeM(p);
    if (p >= mLevels.front())
      return mean(mLevels.front()) + standardAtmosphereAltitudeM(p) -
             standardAtmosphereAltitudeM(mLevels.front());
    if (p <= mLevels.back())
      return mean(mLevels.back()) + standardAtmosphereAltitudeM(p) -
             standardAtmosphereAltitudeM(mLevels.back());
    size_t i = 0;
    while (mLevels[i + 1] > p) ++i;
    const double a = mLevels[i], b = mLevels[i + 1];
    const double t = std::log(a / p) / std::log(a / b);
    return mean(a) + t * (mean(b) - mean(a));
  }

private:
  double mean(double p) {
    const auto found = mMeans.find(p);
    if (found != mMeans.end()) return found->second;
    if (!mResampler) {
      const glm::uvec2 size = meanMapSize();
      mResampler.emplace(mFields.grid, mRegion, size.x, size.y);
    }
    const LevelField& f = *mStep.find(FieldKind::GeopotentialHeight, p);
    // Missing heights take the level's own mean: a hole must not pull the layer to 0 m.
    double finiteSum = 0.0;
    size_t finite = 0;
    for (float v : f.values)
      if (std::isfinite(v)) finiteSum += v, ++finite;
    const std::vector<float> filled = withoutNaN(f.values, float(finiteSum / double(finite)));
    const std::vector<float> map = mResampler->apply(filled, false);
    double sum = 0.0;
    for (float v : map) sum += v;
    return mMeans[p] = sum / double(map.size());
  }

  glm::uvec2 meanMapSize() const {
    const glm::dvec2 km = regionSizeKm(mRegion);
    const double ratio = std::min(km.x, km.y) / std::max(km.x, km.y);
    const auto other = uint32_t(std::max(2.0, std::round(kMeanMapSize * ratio)));
    return km.x >= km.y ? glm::uvec2(kMeanMapSize, other) : glm::uvec2(other, kMeanMapSize);
  }

  const WeatherFields& mFields;
  const WeatherStep& mStep;
  WeatherRegion mRegion;
  std::vector<double> mLevels;
  std::map<double, double> mMeans;
  std::optional<GridResampler> mResampler;
};

LayerCover stepLayers(const WeatherFields& fields, const WeatherStep& step,
                      const WeatherSettings& weather, const WeatherRegion& region) {
  const LayerSpec specs[3] = {{"low", FieldKind::CloudCoverLow, &weather.low},
                              {"mid", FieldKind::CloudCoverMid, &weather.mid},
                              {"high", FieldKind::CloudCoverHigh, &weather.high}};
  LayerCover out;
  out.low = stepLayerCover(fields, step, weather, specs[0]);
  out.mid = stepLayerCover(fields, step, weather, specs[1]);
  out.high = stepLayerCover(fields, step, weather, specs[2]);
  HeightMeans heights(fields, step, region);
  const auto bounds = [&](const WeatherLevelSettings& s) {
    return glm::max(glm::dvec2(heights.altitude(s.bottomHpa), heights.altitude(s.topHpa)), 0.0);
  };
  out.lowAltM = bounds(weather.low);
  out.midAltM = bounds(weather.mid);
  out.highAltM = bounds(weather.high);
  return out;
}

// The altitude of pressure p (m above sea level) at every grid point of `step`: gh
// interpolated in log pressure between the point's levels, as HeightMeans does for the region
// mean; missing heights take their level's mean, and without gh the standard atmosphere.
std::vector<float> altitudeAtPressure(const WeatherFields& fields, const WeatherStep& step,
                                      double p) {
  const size_t n = fields.grid.size();
  std::vector<double> levels;
  std::vector<std::vector<float>> heights;
  for (double level : step.levels(FieldKind::GeopotentialHeight)) {
    const LevelField& f = *step.find(FieldKind::GeopotentialHeight, level);
    if (f.values.size() != n) continue;
    double sum = 0.0;
    size_t finite = 0;
    for (float v : f.values)
      if (std::isfinite(v)) sum += v, ++finite;
    if (finite == 0) continue;
    levels.push_back(level);  // descending: surface first
    heights.push_back(withoutNaN(f.values, float(sum / double(finite))));
  }
  if (levels.empty()) return std::vector<float>(n, float(standardAtmosphereAltitudeM(p)));
  std::vector<float> out(n);
  const auto beyond = [&](size_t i) {
    const double offset = standardAtmosphereAltitudeM(p) - standardAtmosphereAltitudeM(levels[i]);
    for (size_t k = 0; k < n; ++k) out[k] = float(heights[i][k] + offset);
  };
  if (p >= levels.front()) {
    beyond(0);
  } else if (p <= levels.back()) {
    beyond(levels.size() - 1);
  } else {
    size_t i = 0;
    while (levels[i + 1] > p) ++i;
    const double t = std::log(levels[i] / p) / std::log(levels[i] / levels[i + 1]);
    for (size_t k = 0; k < n; ++k)
      out[k] = float(heights[i][k] + t * (heights[i + 1][k] - heights[i][k]));
  }
  for (float& v : out) v = std::max(v, 0.0f);
  return out;
}

}  // namespace

float humidityCover(float rh, float rhCritical) {
  if (!(rh > rhCritical)) return 0.0f;  // also NaN: missing counts as clear
  const float c = (std::min(rh, 1.0f) - rhCritical) / (1.0f - rhCritical);  // Lu (1)
  return c * c;
}

double standardAtmosphereAltitudeM(double pressureHpa) {
  const double exponent = kGasConstant * kLapseKPerM / kGravity;
  const double tropopauseT = kT0K - kLapseKPerM * kTropopauseM;
  const double tropopauseP = kP0Hpa * std::pow(tropopauseT / kT0K, 1.0 / exponent);
  if (pressureHpa >= tropopauseP)
    return kT0K / kLapseKPerM * (1.0 - std::pow(pressureHpa / kP0Hpa, exponent));
  // Isothermal above the tropopause: a scale height of R T / g.
  return kTropopauseM + kGasConstant * tropopauseT / kGravity * std::log(tropopauseP / pressureHpa);
}

LayerCover layerCover(const WeatherFields& fields, double timeUnix, const WeatherSettings& weather,
                      const WeatherRegion& region) {
  if (fields.steps.empty()) inputError("weather.file: " + fileName(fields) + " holds no fields");
  const Bracket b = bracketTime(fields.steps, timeUnix);
  LayerCover out = stepLayers(fields, fields.steps[b.first], weather, region);
  if (b.weight == 0.0) return out;
  // Between two steps: cover and altitudes linearly in time.
  const LayerCover next = stepLayers(fields, fields.steps[b.second], weather, region);
  const auto w = float(b.weight);
  for (auto [a, c] : {std::pair{&out.low, &next.low}, std::pair{&out.mid, &next.mid},
                      std::pair{&out.high, &next.high}})
    for (size_t k = 0; k < a->size(); ++k) (*a)[k] += w * ((*c)[k] - (*a)[k]);
  out.lowAltM += b.weight * (next.lowAltM - out.lowAltM);
  out.midAltM += b.weight * (next.midAltM - out.midAltM);
  out.highAltM += b.weight * (next.highAltM - out.highAltM);
  return out;
}

std::vector<float> resampleToRegion(const GridGeometry& grid, std::span<const float> values,
                                    const WeatherRegion& region, uint32_t width, uint32_t height,
                                    bool clampUnit) {
  return GridResampler(grid, region, width, height).apply(values, clampUnit);
}

WeatherMap weatherMapFromFields(const WeatherFields& fields, double timeUnix,
                                const WeatherSettings& weather, const WeatherRegion& region,
                                glm::dvec2 sceneWindMs) {
  const float type = cloudTypeValue(weather.cloudType);
  const glm::uvec2 size = proceduralMapSize(weather, region);
  const LayerCover layers = layerCover(fields, timeUnix, weather, region);
  const GridResampler resampler(fields.grid, region, size.x, size.y);
  const std::vector<float> low = resampler.apply(layers.low, true);
  const std::vector<float> mid = resampler.apply(layers.mid, true);

  WeatherMap map;
  map.region = region;
  map.width = size.x;
  map.height = size.y;
  map.texels.resize(low.size());
  for (size_t i = 0; i < low.size(); ++i) map.texels[i] = glm::vec4(low[i], mid[i], type, 1.0f);
  map.coverHigh = resampler.apply(layers.high, true);
  map.layerAltitudesM = glm::dvec4(layers.lowAltM, layers.midAltM);
  map.highAltitudeM = layers.highAltM;

  // Outside the file's steps the nearest step's clouds drift with its wind (Kozlov section 5:
  // weather that moves); between steps the forecast itself says how they move.
  if (weather.advection == WeatherAdvection::None) return map;
  const Bracket b = bracketTime(fields.steps, timeUnix);
  if (b.weight != 0.0) return map;
  const WeatherStep& step = fields.steps[b.first];
  const double dt = timeUnix - step.validTimeUnix;
  if (dt == 0.0 || (timeUnix > fields.steps.front().validTimeUnix &&
                    timeUnix < fields.steps.back().validTimeUnix))
    return map;
  if (weather.advection == WeatherAdvection::Wind) {
    advectMap(map, sceneWindMs, dt);
    return map;
  }
  const LevelField* u = step.find(FieldKind::WindU, weather.steeringHpa);
  const LevelField* v = step.find(FieldKind::WindV, weather.steeringHpa);
  if (!u || !v) {
    const std::vector<double> levels = step.levels(u ? FieldKind::WindV : FieldKind::WindU);
    inputError("weather.advection: data needs the wind (u and v) at steering_hpa " +
               formatNumber(weather.steeringHpa) + " hPa; " + fileName(fields) +
               (levels.empty() ? std::string(" has no ") + (u ? "v" : "u") + " wind at any level"
                               : std::string(" has ") + (u ? "v" : "u") + " at " +
                                     formatLevels(levels) + " hPa"));
  }
  advectMap(map, resampler.apply(withoutNaN(u->values, 0.0f), false),
            resampler.apply(withoutNaN(v->values, 0.0f), false), dt);
  return map;
}

std::array<std::vector<float>, 6> layerAltitudeMaps(const WeatherFields& fields, double timeUnix,
                                                    const WeatherSettings& weather,
                                                    const WeatherRegion& region) {
  if (fields.steps.empty()) inputError("weather.file: " + fileName(fields) + " holds no fields");
  const glm::uvec2 size = proceduralMapSize(weather, region);
  const GridResampler resampler(fields.grid, region, size.x, size.y);
  const Bracket b = bracketTime(fields.steps, timeUnix);
  const double pressures[6] = {weather.low.bottomHpa, weather.low.topHpa,     weather.mid.bottomHpa,
                               weather.mid.topHpa,    weather.high.bottomHpa, weather.high.topHpa};
  std::array<std::vector<float>, 6> maps;
  for (size_t i = 0; i < 6; ++i) {
    std::vector<float> a = altitudeAtPressure(fields, fields.steps[b.first], pressures[i]);
    if (b.weight != 0.0) {
      const std::vector<float> c = altitudeAtPressure(fields, fields.steps[b.second], pressures[i]);
      for (size_t k = 0; k < a.size(); ++k) a[k] += float(b.weight) * (c[k] - a[k]);
    }
    maps[i] = resampler.apply(a, false);
  }
  return maps;
}

void advectMap(WeatherMap& map, glm::dvec2 windMs, double seconds) {
  const size_t n = map.texels.size();
  advectMap(map, std::vector<float>(n, float(windMs.x)), std::vector<float>(n, float(windMs.y)),
            seconds);
}

void advectMap(WeatherMap& map, std::span<const float> eastMs, std::span<const float> northMs,
               double seconds) {
  const WeatherRegion& r = map.region;
  constexpr double kDegPerRad = 57.29577951308232;
  const double metresPerDegLat = kEarthRadiusM / kDegPerRad;
  // The high cover rides along as a one-channel map sampled the same way.
  WeatherMap high;
  high.region = r;
  high.width = map.width;
  high.height = map.height;
  for (float c : map.coverHigh) high.texels.emplace_back(c);
  const WeatherMap before = map;
  // Semi-Lagrangian: each texel takes what the wind (at the texel, steady over the time)
  // brought from upstream `seconds` ago; negative seconds run it backward.
  forEachRow(map.height, [&](uint32_t y) {
    const double lat = texelLat(r, y, map.height);
    const double metresPerDegLon =
        std::max(std::cos(lat / kDegPerRad), 1e-3) * kEarthRadiusM / kDegPerRad;
    for (uint32_t x = 0; x < map.width; ++x) {
      const size_t i = size_t(y) * map.width + x;
      const double srcLat = lat - northMs[i] * seconds / metresPerDegLat;
      const double srcLon = texelLon(r, x, map.width) - eastMs[i] * seconds / metresPerDegLon;
      map.texels[i] = before.sample(srcLat, srcLon);
      if (!high.texels.empty()) map.coverHigh[i] = high.sample(srcLat, srcLon).r;
    }
  });
}

}  // namespace sky
