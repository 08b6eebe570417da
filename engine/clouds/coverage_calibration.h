#pragma once
// The 'calibrated' coverage mode (clouds.coverage: calibrated): per cover value, the remap
// threshold of Lu (13)/(17) (or of Tang's coverage remap) at which the mean opacity of
// vertical columns through the layer, seen from above, equals the cover. Lu's own threshold
// 1 - CMc lets only sparse noise peaks through at low cover, so a 30 % cell renders nearly
// clear. The height profile and the erosion stay as the papers describe; only the threshold
// moves (and, where the caller asks, the CMc Lu's profile sees: profileCover).
// docs/cloud-model.md shows the tables and the figures.
#include <array>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "engine/clouds/noise_volume.h"
#include "engine/scene/scene.h"

namespace sky::clouds {

// How a vertical column through a layer samples the noise. Noise coordinates are the position
// in metres divided by the scale along all three axes (as the raymarch samples them). The
// raymarch reads the noise at Earth-fixed (ECEF) positions, so over a map a layer cuts the
// tile at every depth: the columns start anywhere in the tile, in all three coordinates, and
// run along its z axis (the noise is isotropic, so z stands for the local vertical, which
// crosses the tile on a diagonal away from the poles).
struct CoverageColumn {
  double thicknessM = 2000.0;                           // layer thickness (top - base)
  double shapeScaleM = 16000.0, detailScaleM = 2000.0;  // size of one texture repeat
  double extinction = 0.04;                             // per metre at density 1
  glm::vec2 typeRange{0.0f, 1.0f};                      // cloudTypeRange(layer, type)
  CloudModel model = CloudModel::Lu2023;
  float type = 1.0f;  // the map's type channel, for tang2019's type gradient
  // lu2023: the CMc that GS (6), GD (10) and NDmod (15) get. Below 0 (default): the cell's
  // cover, as Lu writes it; then low cover means low, faint clouds, and the calibrated
  // threshold goes negative to spread a faint layer over the whole cell. 1: full-height clouds
  // whose area the threshold sets (docs/cloud-model.md compares the two). The raymarch must
  // pass the same value to luCloudDensity.
  float profileCover = -1.0f;
  // The raymarch's cloudEdgeDensity gain applied to each density (1: the density as is).
  float edgeSharpness = 1.0f;
  // How much of the shape's G, B, A and of the detail the cloud keeps (cloudTypeTexture of the
  // type): the rest of each is the channel's mean over its volume, as the raymarch has it.
  float textureKeep = 1.0f;
  // How much of the cloud is shaped as cumulus (cloudCumulusWeight of the type): the cumulus
  // outline in the shape's R (cumulusShape), lu2023's profile and billows
  // (cumulusCloudDensity). Above 0 the columns spread over the repeat of the outline's slower
  // lookups, CLOUD_CUMULUS_REPEAT_SHAPES shape tiles a side, instead of one shape tile.
  float cumulus = 0.0f;
};

// Thresholds for cover i / (kCoverageLutSize - 1).
inline constexpr int kCoverageLutSize = 64;
using CoverageLut = std::array<float, kCoverageLutSize>;

// The far field per height (shaders/common/cloud_field.glsl farMeanDensity): for cover
// i / (kFarMeanCovers - 1) at its calibrated threshold, over the tile, at height fraction
// (j + 0.5) / kFarMeanHeights of the cloud's range (averaged over that slice), the mean of the
// density the raymarch marches (cloudEdgeDensity of the cloud's density) and the share of the
// space in cloud. A field at 40 % cover holds narrow towers whose tops fill far less than 40 %
// of the area: the cover times the full-cover profile put too much cloud in the top of the
// layer, where a low sun's light crosses it (docs/cloud-model.md, "The far field").
inline constexpr int kFarMeanCovers = 16;
inline constexpr int kFarMeanHeights = 8;
struct FarMean {
  float density = 0.0f;   // the mean density
  float fraction = 0.0f;  // the share of the samples with density above 0
};
using FarMeanTable = std::array<std::array<FarMean, kFarMeanHeights>, kFarMeanCovers>;

// The thresholds whose mean column opacity 1 - exp(-extinction * integral of density dz) over
// 2048 columns spread through the shape tile (32 heights each, trilinear noise) equals each
// cover: 1 (no cloud) at cover 0; where even the lowest threshold (-1) stays below the cover,
// -1. Deterministic (threads split the covers). Budget 0.3 s on 2 cores: the caller caches by
// column. Throws internalError for an empty volume.
CoverageLut calibrateCoverage(const NoiseVolume& shape, const NoiseVolume& detail,
                              const CoverageColumn& column);

// The far field's mean density and cloud share per height for each cover, at the thresholds of `lut`
// (calibrateCoverage's for the same column), on the calibration's grid.
FarMeanTable farMeanDensity(const NoiseVolume& shape, const NoiseVolume& detail,
                            const CoverageColumn& column, const CoverageLut& lut);

// The threshold for `cover` in [0, 1], linear between the LUT's entries.
float coverageThreshold(const CoverageLut& lut, float cover);

// Trilinear sample of a repeating RGBA8 volume at uvw (texel i's centre at (i + 0.5) / size),
// channels byte / 255 as the GPU's UNORM sampler returns them.
glm::vec4 sampleNoise(const NoiseVolume& volume, glm::vec3 uvw);

// Where meanColumnOpacity looks: `columns` columns whose starts follow a 3D low-discrepancy
// (R3) sequence through the shape tile (for cumulus, the tile of their lookups), shifted
// by `offset` (tile fractions), `heights` midpoint samples over the cloud's range.
struct OpacityGrid {
  int columns = 1024;
  int heights = 32;
  glm::vec3 offset{0.0f};
};

// The mean column opacity seen from above for a cell of uniform `cover` with the remap
// `threshold`, straight through cumulusCloudDensity / tangCloudDensity (the reference the fast
// calibration is tested against).
double meanColumnOpacity(const NoiseVolume& shape, const NoiseVolume& detail,
                         const CoverageColumn& column, float cover, float threshold,
                         const OpacityGrid& grid = {});

}  // namespace sky::clouds
