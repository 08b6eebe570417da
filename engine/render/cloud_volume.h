#pragma once
// The cloud density field in a box around the camera as a voxel grid with the camera and the
// light it is rendered with: what skyrender export-volume writes for the path-traced reference
// (scripts/pathtrace, docs/cloud-model.md "Path-traced reference").
#include <filesystem>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/io/vdb.h"
#include "engine/lighting/lighting_state.h"
#include "engine/scene/scene.h"
#include "shaders/common/cloud_volume_export_shared.h"
#include "shaders/common/view_shared.h"

namespace sky {

// An axis-aligned box in the camera's ENU frame: metres east, north and up of the camera.
struct CloudVolumeBox {
  glm::dvec3 minM{0.0}, maxM{0.0};
};

// How finely the exported density resolves the field (export-volume --lod). full: every noise
// octave at every voxel (a footprint of 0); view: the raymarch's level of detail, each voxel
// sampled as a sample one pixel of the scene's camera wide at its distance sees the field
// (docs/clouds.md, "Level of detail by footprint"), and never finer than the voxel itself, so
// no noise finer than the grid aliases into it.
enum class CloudVolumeLod { Full, View };
constexpr auto enumNames(CloudVolumeLod) {
  return std::to_array<EnumName<CloudVolumeLod>>(
      {{CloudVolumeLod::Full, "full"}, {CloudVolumeLod::View, "view"}});
}

// One grid of an export: its box and its voxel edge (m).
struct CloudVolumePart {
  CloudVolumeBox box;
  double voxelM = 50.0;
};

// Several parts cover a field whose resolution falls with distance (a path tracer's view of
// the clouds to the horizon): they are nested, finest first, each inside the next. Part k
// hands the field over to the next over a band kCloudVolumeBlendVoxels of the next part's
// voxels wide inside each of its faces that the next part reaches well past (its band and two
// of the next part's: a coarse grid cannot hold a ramp narrower than two of its voxels);
// faces the next part does not reach that far past are faces of the field. The shares at any
// point inside the outermost part sum to 1, so a path tracer that adds the grids' densities
// (overlapping volumes) sees the field once. BadInput naming --box when a part does not lie
// inside the one after it, or more than kMaxCloudVolumeVoxelsInAll voxels in all.
constexpr double kCloudVolumeBlendVoxels = 2.0;
void checkCloudVolumeParts(const std::vector<CloudVolumePart>& parts);
// The share of the density at `p` (ENU, m) that part k holds: s_k prod_{j<k} (1 - s_j), s_j
// rising from 0 on part j's handing-over faces to 1 a band inside them (1 for the last part
// inside its box), 0 outside part k.
double cloudVolumeShare(const std::vector<CloudVolumePart>& parts, size_t k, const glm::dvec3& p);
// The width of part k's band (m): kCloudVolumeBlendVoxels voxels of part k + 1, 0 for the last.
double cloudVolumeBlendM(const std::vector<CloudVolumePart>& parts, size_t k);

// What skyrender export-volume asks for.
struct CloudVolumeRequest {
  std::vector<CloudVolumePart> parts;  // nested, finest first; none: the default box
  double defaultVoxelM = 50.0;         // the default box's voxel edge (m)
  CloudVolumeLod lod = CloudVolumeLod::Full;
};

// The default box: a square 6 km on a side centred 4 km ahead of the camera along its heading
// (so its near side passes 1 km ahead), from the base of the lowest layer with cover to the
// top of the highest, taken down by the Earth's curvature at the square's far corners so it
// holds the whole layer. `maxCover` is the map's largest (low, mid) cover.
CloudVolumeBox defaultCloudVolumeBox(const Scene& cloudScene, const glm::vec2& maxCover);

// The voxels covering `box` at `voxelM` from its minimum corner, ceil(size / voxelM) along
// each axis (the last ones may reach past the maximum corner). BadInput for a voxel of 0 or
// less, or more than kMaxCloudVolumeVoxels voxels.
constexpr uint64_t kMaxCloudVolumeVoxels = uint64_t(1) << 26;
// Several parts are held in memory together (dense, 4 bytes a voxel): at most this many in all.
constexpr uint64_t kMaxCloudVolumeVoxelsInAll = uint64_t(1) << 28;
struct CloudVolumeGrid {
  CloudVolumeBox box;  // as asked
  double voxelM = 1.0;
  shared::CloudVolumeExportParams params{};  // footprint 0 (full detail) until the caller sets it
};
CloudVolumeGrid cloudVolumeGrid(const CloudVolumeBox& box, double voxelM);
// The footprint of `lod` for voxels of `voxelM` seen by `view` (CloudVolumeExportParams'
// footprintPerM and footprintMinM).
void setCloudVolumeFootprint(CloudVolumeGrid& grid, CloudVolumeLod lod,
                             const shared::ViewState& view);

struct CloudVolume {
  VdbGrid extinction;    // "density": extinction per metre (density x clouds.extinction)
  VdbMetadata metadata;  // camera, lights, phase and units; see docs/outputs.md
};

// The volume from the exported densities (`density`, x fastest, from the grid's readback) of
// `cloudScene` (the scene with the weather's region and layers filled in) lit by `lighting`.
// The light's altitude comes from `lightBox` (the first part of an export of several).
CloudVolume makeCloudVolume(const Scene& cloudScene, const LightingState& lighting,
                            const IsoTime& time, const shared::ViewState& view,
                            const CloudVolumeGrid& grid, std::vector<float> density,
                            const CloudVolumeBox& lightBox);

// The volumes of an export of several parts, each part's densities already times its share
// (cloudVolumeShare): grid k is named "density" for k = 0 and "density_k" after it, and its
// metadata say which part it is (grid_index, grid_count, blend_m; docs/outputs.md).
void nameCloudVolumeParts(std::vector<CloudVolume>& volumes,
                          const std::vector<CloudVolumePart>& parts);

// Writes `volume` as OpenVDB through a temporary file.
void writeCloudVolume(const std::filesystem::path& path, const CloudVolume& volume);
// Writes several volumes as the grids of one OpenVDB file, whole or not at all.
void writeCloudVolumes(const std::filesystem::path& path, const std::vector<CloudVolume>& volumes);

}  // namespace sky
