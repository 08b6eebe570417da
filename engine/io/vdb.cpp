#include "engine/io/vdb.h"

#include <sstream>

#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
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

openvdb::FloatGrid::Ptr makeVdbGrid(const VdbGrid& grid, const VdbMetadata& metadata) {
  const size_t count = size_t(grid.size.x) * grid.size.y * grid.size.z;
  if (grid.values.size() != count)
    internalError("writeVdb: " + std::to_string(grid.values.size()) + " values for " +
                  std::to_string(count) + " voxels");
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
  return vdb;
}

}  // namespace

void writeVdb(const std::filesystem::path& path, const VdbGrid& grid, const VdbMetadata& metadata) {
  writeVdb(path, std::vector<VdbGridWithMetadata>{{&grid, &metadata}});
}

void writeVdb(const std::filesystem::path& path, const std::vector<VdbGridWithMetadata>& grids) {
  initialize();
  openvdb::GridPtrVec vdbs;
  for (const VdbGridWithMetadata& g : grids) {
    for (const openvdb::GridBase::Ptr& other : vdbs)
      if (other->getName() == g.grid->name)
        internalError("writeVdb: two grids named '" + g.grid->name + "'");
    vdbs.push_back(makeVdbGrid(*g.grid, *g.metadata));
  }
  // The file's length, from the same grids serialised in memory (OpenVDB's stream and file
  // forms are the same bytes long): a short file is known without opening it.
  std::streamoff expectedBytes = 0;
  {
    std::ostringstream bytes(std::ios_base::binary);
    openvdb::io::Stream(bytes).write(vdbs);
    expectedBytes = bytes.tellp();
  }
  writeFileAtomic(path, [&](const std::filesystem::path& tmp) {
    try {
      openvdb::io::File file(tmp.string());
      file.write(vdbs);
      file.close();
    } catch (const openvdb::Exception& e) {
      inputError(path.string() + ": cannot write: " + e.what());
    }
    // OpenVDB writes through a std::ofstream whose errors it never checks: on a full disk
    // it returned normally after a 4,096-byte or empty file (issue 31, 1). So the temporary
    // must be as long as the grids serialised, and is read back: only a file whose every grid
    // is whole to its last voxel is renamed into place. The length comes first: OpenVDB
    // reading a file cut short inside its grid descriptors of several grids took a string
    // length from past the end and allocated gigabytes.
    std::error_code sizeError;
    const uintmax_t bytes = std::filesystem::file_size(tmp, sizeError);
    if (sizeError || bytes != static_cast<uintmax_t>(expectedBytes))
      inputError(path.string() + ": write failed (disk full?)");
    bool whole = true;
    try {
      openvdb::io::File check(tmp.string());
      check.open();
      for (const openvdb::GridBase::Ptr& vdb : vdbs) {
        openvdb::GridBase::Ptr back =
            check.hasGrid(vdb->getName()) ? check.readGrid(vdb->getName()) : nullptr;
        whole = whole && back && back->activeVoxelCount() == vdb->activeVoxelCount();
      }
      check.close();
    } catch (const std::exception&) {
      // A truncated file fails to read, with a message about OpenVDB's internals.
      whole = false;
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
