#include "engine/clouds/coverage_calibration.h"

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "engine/clouds/cloud_math.h"
#include "engine/core/error.h"
#include "shaders/common/volumetric_clouds_shared.h"

namespace sky::clouds {
namespace {

// 2048 columns through the tile, 32 heights each (62 m in a 2 km cumulus; the march steps
// 20-70 m there): on the baked noise the mean opacity of 16384 fresh columns at 96 heights
// is then within 0.007 of the cover, at the cost of the 48 x 48 x 24 grid before. With 24
// heights the thin fringes between samples went unseen and those fresh columns came out 0.01
// more opaque than the cover.
constexpr int kColumns = 2048;
constexpr int kHeights = 32;
// The threshold range searched. At -1 every sample's NSfinal (Lu (17)) is at least 0.5, above
// any erosion (Lu (15) <= 0.35), so nothing lower adds cover; 1 leaves no cloud.
constexpr float kLowestThreshold = -1.0f;
constexpr float kHighestThreshold = 1.0f;
// Solver stops: the opacity within 2e-4 of the cover, or the bracket below 1e-4 in threshold
// (far below what moves the opacity by 0.001); at most 40 evaluations.
constexpr double kOpacityTolerance = 2e-4;
constexpr double kThresholdTolerance = 1e-4;
constexpr int kMaxSolverSteps = 40;

// Runs fn(i) for i in [0, count) on up to 8 threads, thread t taking every n-th index: each
// index's work is independent, so the result does not depend on the thread count.
template <class Fn>
void parallelFor(int count, Fn fn) {
  const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
  auto work = [&](int first) {
    for (int i = first; i < count; i += threads) fn(i);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& t : pool) t.join();
}

void checkVolume(const NoiseVolume& v, const char* what) {
  const size_t n = size_t(v.size) * v.size * v.size * 4;
  if (v.size == 0 || v.rgba.size() != n)
    internalError(std::string("coverage calibration: the ") + what + " noise volume is empty or " +
                  "its size does not match");
}

// Where column k starts in the shape tile (tile fractions): the R3 low-discrepancy sequence
// (Roberts 2018, phi_3 the real root of x^4 = x + 1), spread evenly through the tile without
// lining up with the detail texture's shorter period, which a regular grid would sample at
// only a few distinct detail positions. In depth too: the raymarch reads the noise where the
// point lies on the Earth (ECEF, cloud_field.glsl), so a layer crosses the tile at every
// depth over a map. Columns that all started at the tile's z = 0 saw one slab of it, 2 km of
// a 5 km tile holding about one and a half of the outline's cells in depth, whose clouds are
// not the tile's: calibrated there, the default map rendered 0.06 more covered than it says.
glm::dvec3 columnStart(int k, glm::vec3 offset) {
  constexpr double g = 1.22074408460575947536;
  const glm::dvec3 s = 0.5 + glm::dvec3(offset) + double(k) / glm::dvec3(g, g * g, g * g * g);
  return s - glm::floor(s);
}

// The side of the tile the columns spread over (m): the shape tile, or for cumulus the tile of
// their outline's slower lookups (cumulusOutline), whose clusters of large clouds and clear
// areas are kilometres across: columns through one shape tile would see a few of them.
double columnTileM(const CoverageColumn& column) {
  return column.cumulus > 0.0f ? column.shapeScaleM * CLOUD_CUMULUS_REPEAT_SHAPES
                                  : column.shapeScaleM;
}

// The noise position (m) of a column's sample at height fraction ph of the cloud's range.
glm::dvec3 samplePosition(const CoverageColumn& column, glm::dvec3 start, double ph) {
  const double range = double(column.typeRange.y) - double(column.typeRange.x);
  const double z = (double(column.typeRange.x) + ph * range) * column.thicknessM;
  return start * columnTileM(column) + glm::dvec3(0.0, 0.0, z);
}

// The noise samples as a cloud of the column's type sees them (shaders/common/cloud_field.glsl):
// its shape's R with the cumulus outline mixed in by column.cumulus (cumulusShape, from
// the lookups at a half and a quarter of the frequency), then its shape's G, B, A and its
// detail kept by column.textureKeep, the rest their means.
class ColumnNoise {
public:
  ColumnNoise(const NoiseVolume& shape, const NoiseVolume& detail, const CoverageColumn& column)
      : mShape(shape),
        mDetail(detail),
        mShapeScaleM(column.shapeScaleM),
        mDetailScaleM(column.detailScaleM),
        mKeep(column.textureKeep),
        mCumulus(column.cumulus) {
    if (mKeep >= 1.0f && mCumulus <= 0.0f) return;  // the means are not needed
    mShapeMean = channelMeans(shape);
    mDetailMean = glm::vec3(channelMeans(detail));
  }
  // At noise position p (m).
  glm::vec4 shape(const glm::dvec3& p) const {
    glm::vec4 s = sampleNoise(mShape, glm::vec3(p / mShapeScaleM));
    if (mCumulus > 0.0f) {
      const glm::dvec3 quarter = p / (mShapeScaleM * CLOUD_CUMULUS_REPEAT_SHAPES);
      s = cumulusShape(s, sampleNoise(mShape, glm::vec3(2.0 * quarter)),
                           sampleNoise(mShape, glm::vec3(quarter)), mShapeMean.r, mCumulus);
    }
    if (mKeep >= 1.0f) return s;
    return {s.r, glm::mix(glm::vec3(mShapeMean.g, mShapeMean.b, mShapeMean.a),
                          glm::vec3(s.g, s.b, s.a), mKeep)};
  }
  glm::vec3 detail(const glm::dvec3& p) const {
    const glm::vec3 d(sampleNoise(mDetail, glm::vec3(p / mDetailScaleM)));
    return mKeep >= 1.0f ? d : glm::mix(mDetailMean, d, mKeep);
  }

private:
  const NoiseVolume& mShape;
  const NoiseVolume& mDetail;
  double mShapeScaleM, mDetailScaleM;
  float mKeep, mCumulus;
  glm::vec4 mShapeMean{0.0f};
  glm::vec3 mDetailMean{0.0f};
};

// The noise at every sample of the grid, reduced to what the density reads from it: Lu (12)'s
// NStex from the shape and Lu (14)'s fbm from the detail (Tang's density reads the same two).
struct GridSamples {
  int columns = 0, heights = 0;
  std::vector<float> nstex, ndfbm;  // [column * heights + height]
  double dzM = 0;                   // the height step inside the cloud's range
};

GridSamples sampleGrid(const NoiseVolume& shape, const NoiseVolume& detail,
                       const CoverageColumn& column, const OpacityGrid& grid) {
  GridSamples s;
  s.columns = grid.columns;
  s.heights = grid.heights;
  const double range = double(column.typeRange.y) - double(column.typeRange.x);
  s.dzM = range * column.thicknessM / grid.heights;
  s.nstex.resize(size_t(s.columns) * size_t(s.heights));
  s.ndfbm.resize(s.nstex.size());
  const ColumnNoise noise(shape, detail, column);
  parallelFor(s.columns, [&](int k) {
    const glm::dvec3 start = columnStart(k, grid.offset);
    for (int j = 0; j < s.heights; ++j) {
      const glm::dvec3 p = samplePosition(column, start, (j + 0.5) / s.heights);
      const size_t i = size_t(k) * size_t(s.heights) + size_t(j);
      s.nstex[i] = luNStex(noise.shape(p));
      s.ndfbm[i] = luNDfbm(noise.detail(p));
    }
  });
  return s;
}

// The CMc that Lu's GS (6), GD (10) and NDmod (15) see.
float profileCover(const CoverageColumn& column, float cover) {
  return column.profileCover >= 0.0f ? column.profileCover : cover;
}

float heightFraction(int j, int heights) {
  return (float(j) + 0.5f) / float(heights);
}

// The mean column opacity of one cover as a function of the threshold, with everything that
// does not depend on the threshold computed once: the solver evaluates it several times.
// Both models share one form after the threshold's remap,
//   density = SAT((SAT((x - t) / (1 - t)) - e) / (1 - e)) * scale,
// Lu (17)(18) with x = NStex * GS, e = NDmod, scale = GD; Tang with x = its base shape, e = its
// erosion, scale = the cover. The loop multiplies by reciprocals where luNSfinal, luDensity and
// tangDensity divide (a last-bit difference; the tests check the result against
// meanColumnOpacity, which calls the functions themselves).
class CoverOpacity {
public:
  CoverOpacity(const GridSamples& s, const CoverageColumn& column, float cover)
      : mColumns(s.columns),
        mHeights(s.heights),
        mOpticalDepthPerDensity(column.extinction * s.dzM),
        mEdgeSharpness(column.edgeSharpness) {
    const float cmc = profileCover(column, cover);
    // Per height: the height functions, and the erosion at fbm 0 and 1 (Lu (15) and Tang's
    // erosion are affine in the fbm, so the two ends give every value without an exp a sample).
    std::vector<float> shapeFactor(size_t(s.heights)), e0(shapeFactor.size()),
        e1(shapeFactor.size()), scale(shapeFactor.size());
    for (int j = 0; j < s.heights; ++j) {
      const float ph = heightFraction(j, s.heights);
      const size_t h = size_t(j);
      if (column.model == CloudModel::Lu2023) {
        shapeFactor[h] = luGS(ph, cmc);                      // Lu (7)
        e0[h] = cumulusNDmod(0.0f, cmc, ph, column.cumulus);  // Lu (15)
        e1[h] = cumulusNDmod(1.0f, cmc, ph, column.cumulus);
        scale[h] = cumulusGD(ph, cmc, column.cumulus);  // Lu (10)
      } else {
        shapeFactor[h] = tangTypeGradient(ph, column.type);
        e0[h] = tangErosion(0.0f, ph);
        e1[h] = tangErosion(1.0f, ph);
        scale[h] = cover;
      }
    }
    const size_t n = s.nstex.size();
    mX.resize(n);
    mE.resize(n);
    mInvE.resize(n);
    mScale.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const size_t h = i % size_t(s.heights);
      mX[i] = s.nstex[i] * shapeFactor[h];  // Lu (12) * (7); tangBaseShape
      mE[i] = e0[h] + s.ndfbm[i] * (e1[h] - e0[h]);
      mInvE[i] = 1.0f / (1.0f - mE[i]);
      mScale[i] = scale[h];
    }
  }

  double operator()(float threshold) const {
    if (threshold >= 1.0f) return 0.0;  // no cloud (luNSfinal, tangDensity)
    const float invT = 1.0f / (1.0f - threshold);
    double sum = 0;
    for (int k = 0; k < mColumns; ++k) {
      const size_t first = size_t(k) * size_t(mHeights), last = first + size_t(mHeights);
      float depth = 0;
      for (size_t i = first; i < last; ++i) {
        const float shaped = std::clamp((mX[i] - threshold) * invT, 0.0f, 1.0f);
        const float density = std::clamp((shaped - mE[i]) * mInvE[i], 0.0f, 1.0f) * mScale[i];
        depth += cloudEdgeDensity(density, mEdgeSharpness);
      }
      sum += 1.0 - std::exp(-mOpticalDepthPerDensity * depth);
    }
    return sum / mColumns;
  }

  // The mean density at each of the grid's heights (what operator() sums down a column,
  // averaged over the columns instead), and the share of the samples in cloud there.
  std::vector<FarMean> meanPerHeight(float threshold) const {
    std::vector<FarMean> mean(static_cast<size_t>(mHeights));
    if (threshold >= 1.0f) return mean;
    const float invT = 1.0f / (1.0f - threshold);
    std::vector<double> density(mean.size(), 0.0), inCloud(mean.size(), 0.0);
    for (int k = 0; k < mColumns; ++k)
      for (int j = 0; j < mHeights; ++j) {
        const size_t i = size_t(k) * size_t(mHeights) + size_t(j);
        const float shaped = std::clamp((mX[i] - threshold) * invT, 0.0f, 1.0f);
        const float d = std::clamp((shaped - mE[i]) * mInvE[i], 0.0f, 1.0f) * mScale[i];
        density[size_t(j)] += cloudEdgeDensity(d, mEdgeSharpness);
        inCloud[size_t(j)] += d > 0.0f ? 1.0 : 0.0;
      }
    for (size_t j = 0; j < mean.size(); ++j)
      mean[j] = {float(density[j] / mColumns), float(inCloud[j] / mColumns)};
    return mean;
  }

private:
  int mColumns, mHeights;
  double mOpticalDepthPerDensity;
  float mEdgeSharpness;
  std::vector<float> mX, mE, mInvE, mScale;  // per sample
};

// The threshold at which the opacity (non-increasing in the threshold: every remap it enters
// is) equals `cover`: the Illinois variant of regula falsi (Dowell & Jarratt 1971), which keeps
// bisection's bracket but needs about a third of its evaluations on these smooth curves.
float solveThreshold(const CoverOpacity& opacity, float cover) {
  if (cover <= 0.0f) return kHighestThreshold;
  double lo = kLowestThreshold, hi = kHighestThreshold;
  double fLo = opacity(float(lo)) - cover, fHi = -double(cover);  // opacity(1) = 0
  if (fLo <= 0.0) return kLowestThreshold;  // even the densest remap stays below the cover
  int side = 0;
  for (int step = 0; step < kMaxSolverSteps && hi - lo > kThresholdTolerance; ++step) {
    const double t = (lo * fHi - hi * fLo) / (fHi - fLo);
    const double f = opacity(float(t)) - cover;
    if (std::abs(f) < kOpacityTolerance) return float(t);
    if (f > 0) {
      lo = t;
      fLo = f;
      if (side == -1) fHi *= 0.5;  // Illinois: halve the stale end's value
      side = -1;
    } else {
      hi = t;
      fHi = f;
      if (side == 1) fLo *= 0.5;
      side = 1;
    }
  }
  return float(0.5 * (lo + hi));
}

}  // namespace

glm::vec4 sampleNoise(const NoiseVolume& volume, glm::vec3 uvw) {
  const int n = int(volume.size);
  const glm::vec3 p = uvw * float(n) - 0.5f;
  const glm::vec3 base = glm::floor(p);
  const glm::vec3 f = p - base;
  auto wrap = [n](float c) { return (int(c) % n + n) % n; };
  const int x0 = wrap(base.x), y0 = wrap(base.y), z0 = wrap(base.z);
  const int xs[2] = {x0, (x0 + 1) % n}, ys[2] = {y0, (y0 + 1) % n}, zs[2] = {z0, (z0 + 1) % n};
  glm::vec4 sum(0.0f);
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const float w = (dx ? f.x : 1.0f - f.x) * (dy ? f.y : 1.0f - f.y) * (dz ? f.z : 1.0f - f.z);
        const size_t i =
            ((size_t(zs[dz]) * size_t(n) + size_t(ys[dy])) * size_t(n) + size_t(xs[dx])) * 4;
        sum += w * glm::vec4(volume.rgba[i], volume.rgba[i + 1], volume.rgba[i + 2],
                             volume.rgba[i + 3]);
      }
  return sum * (1.0f / 255.0f);
}

float coverageThreshold(const CoverageLut& lut, float cover) {
  const float x = std::clamp(cover, 0.0f, 1.0f) * float(kCoverageLutSize - 1);
  const int i = std::min(int(x), kCoverageLutSize - 2);
  const float f = x - float(i);
  return lut[size_t(i)] + f * (lut[size_t(i) + 1] - lut[size_t(i)]);
}

double meanColumnOpacity(const NoiseVolume& shape, const NoiseVolume& detail,
                         const CoverageColumn& column, float cover, float threshold,
                         const OpacityGrid& grid) {
  checkVolume(shape, "shape");
  checkVolume(detail, "detail");
  const float cmc = profileCover(column, cover);
  const int columns = grid.columns;
  const double range = double(column.typeRange.y) - double(column.typeRange.x);
  const double dz = range * column.thicknessM / grid.heights;
  const ColumnNoise noise(shape, detail, column);
  double sum = 0;
  for (int k = 0; k < columns; ++k) {
    const glm::dvec3 start = columnStart(k, grid.offset);
    double depth = 0;
    for (int j = 0; j < grid.heights; ++j) {
      const float ph = heightFraction(j, grid.heights);
      const glm::dvec3 p = samplePosition(column, start, double(ph));
      const glm::vec4 s = noise.shape(p);
      const glm::vec3 d = noise.detail(p);
      depth += cloudEdgeDensity(column.model == CloudModel::Lu2023
                                    ? cumulusCloudDensity(s, d, ph, cmc, threshold, column.cumulus)
                                    : tangCloudDensity(s, d, ph, cover, column.type, threshold),
                                column.edgeSharpness);
    }
    sum += 1.0 - std::exp(-column.extinction * dz * depth);
  }
  return sum / columns;
}

CoverageLut calibrateCoverage(const NoiseVolume& shape, const NoiseVolume& detail,
                              const CoverageColumn& column) {
  checkVolume(shape, "shape");
  checkVolume(detail, "detail");
  const GridSamples samples = sampleGrid(shape, detail, column, {kColumns, kHeights, {}});
  CoverageLut lut{};
  parallelFor(kCoverageLutSize, [&](int i) {
    const float cover = float(i) / float(kCoverageLutSize - 1);
    lut[size_t(i)] = solveThreshold(CoverOpacity(samples, column, cover), cover);
  });
  return lut;
}

FarMeanTable farMeanDensity(const NoiseVolume& shape, const NoiseVolume& detail,
                            const CoverageColumn& column, const CoverageLut& lut) {
  checkVolume(shape, "shape");
  checkVolume(detail, "detail");
  static_assert(kHeights % kFarMeanHeights == 0, "each far height averages whole grid heights");
  const GridSamples samples = sampleGrid(shape, detail, column, {kColumns, kHeights, {}});
  FarMeanTable table{};
  parallelFor(kFarMeanCovers, [&](int i) {
    const float cover = float(i) / float(kFarMeanCovers - 1);
    const std::vector<FarMean> mean =
        CoverOpacity(samples, column, cover).meanPerHeight(coverageThreshold(lut, cover));
    constexpr int per = kHeights / kFarMeanHeights;
    for (int j = 0; j < kFarMeanHeights; ++j) {
      FarMean sum;
      for (int k = 0; k < per; ++k) {
        sum.density += mean[size_t(j * per + k)].density / per;
        sum.fraction += mean[size_t(j * per + k)].fraction / per;
      }
      table[size_t(i)][size_t(j)] = sum;
    }
  });
  return table;
}

}  // namespace sky::clouds
