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

// The default box: a square 6 km on a side centred 4 km ahead of the camera along its heading
// (so its near side passes 1 km ahead), from the base of the lowest layer with cover to the
// top of the highest, taken down by the Earth's curvature at the square's far corners so it
// holds the whole layer. `maxCover` is the map's largest (low, mid) cover.
CloudVolumeBox defaultCloudVolumeBox(const Scene& cloudScene, const glm::vec2& maxCover);

// The voxels covering `box` at `voxelM` from its minimum corner, ceil(size / voxelM) along
// each axis (the last ones may reach past the maximum corner). BadInput for a voxel of 0 or
// less, or more than kMaxCloudVolumeVoxels voxels.
constexpr uint64_t kMaxCloudVolumeVoxels = uint64_t(1) << 26;
struct CloudVolumeGrid {
  CloudVolumeBox box;  // as asked
  double voxelM = 1.0;
  shared::CloudVolumeExportParams params{};
};
CloudVolumeGrid cloudVolumeGrid(const CloudVolumeBox& box, double voxelM);

struct CloudVolume {
  VdbGrid extinction;    // "density": extinction per metre (density x clouds.extinction)
  VdbMetadata metadata;  // camera, lights, phase and units; see docs/outputs.md
};

// The volume from the exported densities (`density`, x fastest, from the grid's readback) of
// `cloudScene` (the scene with the weather's region and layers filled in) lit by `lighting`.
CloudVolume makeCloudVolume(const Scene& cloudScene, const LightingState& lighting,
                            const IsoTime& time, const shared::ViewState& view,
                            const CloudVolumeGrid& grid, std::vector<float> density);

// Writes `volume` as OpenVDB through a temporary file.
void writeCloudVolume(const std::filesystem::path& path, const CloudVolume& volume);

}  // namespace sky
