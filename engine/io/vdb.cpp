#include "engine/io/vdb.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace sky {
namespace {

// The grid's extent in voxels, kept as metadata: the stored tree holds only the non-zero
// voxels, so its bounding box alone would lose clear voxels at the edges.
constexpr const char* kSizeKey = "grid_voxels";

void initialize() {
  static const bool done = [] {
    openvdb::initialize();
    return true;
  }();
  (void)done;
}

}  // namespace

void writeVdb(const std::filesystem::path& path, const VdbGrid& grid, const VdbMetadata& metadata) {
  const size_t count = size_t(grid.size.x) * grid.size.y * grid.size.z;
  if (grid.values.size() != count)
    internalError("writeVdb: " + std::to_string(grid.values.size()) + " values for " +
                  std::to_string(count) + " voxels");
  initialize();
  openvdb::FloatGrid::Ptr vdb = openvdb::FloatGrid::create(0.0f);
  vdb->setName(grid.name);
  vdb->setGridClass(openvdb::GRID_FOG_VOLUME);
  // Index (i, j, k) is voxel (i, j, k): OpenVDB places a voxel's value at its index, the
  // voxel's centre, and the voxel spans half a voxel either side.
  openvdb::math::Transform::Ptr transform =
      openvdb::math::Transform::createLinearTransform(grid.voxelSize);
  transform->postTranslate(
      openvdb::Vec3d(grid.firstVoxelCentre.x, grid.firstVoxelCentre.y, grid.firstVoxelCentre.z));
  vdb->setTransform(transform);
  openvdb::FloatGrid::Accessor acc = vdb->getAccessor();
  size_t i = 0;
  for (uint32_t z = 0; z < grid.size.z; ++z)
    for (uint32_t y = 0; y < grid.size.y; ++y)
      for (uint32_t x = 0; x < grid.size.x; ++x, ++i)
        if (grid.values[i] != 0.0f)
          acc.setValue(openvdb::Coord(int(x), int(y), int(z)), grid.values[i]);
  for (const auto& [key, value] : metadata) {
    if (const double* d = std::get_if<double>(&value)) vdb->insertMeta(key, openvdb::DoubleMetadata(*d));
    if (const int64_t* n = std::get_if<int64_t>(&value)) vdb->insertMeta(key, openvdb::Int64Metadata(*n));
    if (const std::string* s = std::get_if<std::string>(&value))
      vdb->insertMeta(key, openvdb::StringMetadata(*s));
    if (const glm::dvec3* v = std::get_if<glm::dvec3>(&value))
      vdb->insertMeta(key, openvdb::Vec3DMetadata(openvdb::Vec3d(v->x, v->y, v->z)));
  }
  vdb->insertMeta(kSizeKey, openvdb::Vec3IMetadata(openvdb::Vec3i(
                                int(grid.size.x), int(grid.size.y), int(grid.size.z))));
  writeFileAtomic(path, [&](const std::filesystem::path& tmp) {
    try {
      openvdb::io::File file(tmp.string());
      file.write({vdb});
      file.close();
    } catch (const openvdb::Exception& e) {
      inputError(path.string() + ": cannot write: " + e.what());
    }
    // OpenVDB writes through a std::ofstream whose errors it never checks: on a full disk
    // it returned normally after a 4,096-byte or empty file (issue 31, 1). So the temporary
    // is read back, and only a grid whole to its last voxel is renamed into place.
    bool whole = false;
    try {
      openvdb::io::File check(tmp.string());
      check.open();
      openvdb::GridBase::Ptr back = check.hasGrid(grid.name) ? check.readGrid(grid.name) : nullptr;
      check.close();
      whole = back && back->activeVoxelCount() == vdb->activeVoxelCount();
    } catch (const std::exception&) {
      // A truncated file fails to read, with a message about OpenVDB's internals.
    }
    if (!whole) inputError(path.string() + ": write failed (disk full?)");
  });
}

VdbFile readVdb(const std::filesystem::path& path, const std::string& name) {
  initialize();
  if (!std::filesystem::exists(path)) inputError(path.string() + ": no such file");
  openvdb::GridBase::Ptr base;
  try {
    openvdb::io::File file(path.string());
    file.open();
    if (!file.hasGrid(name)) inputError(path.string() + ": no grid named '" + name + "'");
    base = file.readGrid(name);
    file.close();
  } catch (const openvdb::Exception& e) {
    inputError(path.string() + ": not a readable OpenVDB file: " + e.what());
  }
  openvdb::FloatGrid::Ptr vdb = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  if (!vdb) inputError(path.string() + ": grid '" + name + "' is " + base->valueType() + ", not float");
  VdbFile out;
  out.grid.name = name;
  out.grid.voxelSize = vdb->voxelSize().x();
  const openvdb::Vec3d origin = vdb->indexToWorld(openvdb::Vec3d(0.0));
  out.grid.firstVoxelCentre = glm::dvec3(origin.x(), origin.y(), origin.z());
  if (auto size = vdb->getMetadata<openvdb::Vec3IMetadata>(kSizeKey)) {
    const openvdb::Vec3i& n = size->value();
    out.grid.size = glm::uvec3(uint32_t(std::max(n.x(), 0)), uint32_t(std::max(n.y(), 0)),
                               uint32_t(std::max(n.z(), 0)));
  } else {
    const openvdb::CoordBBox box = vdb->evalActiveVoxelBoundingBox();
    const openvdb::Coord& max = box.max();
    out.grid.size = glm::uvec3(uint32_t(std::max(max.x() + 1, 0)),
                               uint32_t(std::max(max.y() + 1, 0)), uint32_t(std::max(max.z() + 1, 0)));
  }
  out.grid.values.resize(size_t(out.grid.size.x) * out.grid.size.y * out.grid.size.z);
  openvdb::FloatGrid::ConstAccessor acc = vdb->getConstAccessor();
  size_t i = 0;
  for (uint32_t z = 0; z < out.grid.size.z; ++z)
    for (uint32_t y = 0; y < out.grid.size.y; ++y)
      for (uint32_t x = 0; x < out.grid.size.x; ++x)
        out.grid.values[i++] = acc.getValue(openvdb::Coord(int(x), int(y), int(z)));
  for (auto it = vdb->beginMeta(); it != vdb->endMeta(); ++it) {
    const openvdb::Metadata& m = *it->second;
    if (it->first == kSizeKey) continue;
    if (auto* d = dynamic_cast<const openvdb::DoubleMetadata*>(&m)) out.metadata[it->first] = d->value();
    else if (auto* n = dynamic_cast<const openvdb::Int64Metadata*>(&m))
      out.metadata[it->first] = int64_t(n->value());
    else if (auto* s = dynamic_cast<const openvdb::StringMetadata*>(&m))
      out.metadata[it->first] = s->value();
    else if (auto* v = dynamic_cast<const openvdb::Vec3DMetadata*>(&m))
      out.metadata[it->first] = glm::dvec3(v->value().x(), v->value().y(), v->value().z());
  }
  return out;
}

}  // namespace sky
