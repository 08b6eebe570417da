#pragma once
// OpenVDB files of one float grid with metadata: the cloud density of skyrender
// export-volume for Blender/Cycles (scripts/pathtrace). The grid is dense in memory and
// stored sparse: voxels at 0 are the background, not written.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include <glm/vec3.hpp>

namespace sky {

struct VdbGrid {
  std::string name;                   // e.g. "density" (what Blender's volume shaders read)
  glm::uvec3 size{0};                 // voxels along x, y, z
  glm::dvec3 firstVoxelCentre{0.0};   // world position of voxel (0, 0, 0)'s centre
  double voxelSize = 1.0;             // world units per voxel edge
  std::vector<float> values;          // size.x * size.y * size.z, x fastest, then y, then z
};

using VdbMetaValue = std::variant<double, int64_t, std::string, glm::dvec3>;
using VdbMetadata = std::map<std::string, VdbMetaValue>;

// Writes `grid` (a fog volume) with `metadata` on the grid, through a temporary file (no
// partial file on failure). BadInput naming the path when it cannot be written.
void writeVdb(const std::filesystem::path& path, const VdbGrid& grid, const VdbMetadata& metadata);
// The same for several grids in one file (names distinct), each with its own metadata: the
// file is renamed into place only when every grid reads back whole.
struct VdbGridWithMetadata {
  const VdbGrid* grid;
  const VdbMetadata* metadata;
};
void writeVdb(const std::filesystem::path& path, const std::vector<VdbGridWithMetadata>& grids);

struct VdbFile {
  VdbGrid grid;          // dense over the grid's active bounding box as stored
  VdbMetadata metadata;  // the grid's metadata of the four types above (others skipped)
};
// Reads the float grid `name` from `path`, dense over the box from index (0, 0, 0) to the
// largest active index. BadInput naming the path for a missing file, grid or a grid that is
// not float.
VdbFile readVdb(const std::filesystem::path& path, const std::string& name);

}  // namespace sky
