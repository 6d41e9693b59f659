// Exemplars as OpenVDB files (issue 29): density, fibre direction and yarn id as three grids, the weave and
// the block layout as file metadata. Kept apart from exemplar.cpp so that only this file sees OpenVDB.
#include <algorithm>
#include <cstring>

#include <openvdb/openvdb.h>

#include "common/contained.hpp"
#include "common/error.hpp"
#include "common/input_file.hpp"
#include "woven/exemplar.hpp"

namespace skein::woven {

namespace {

openvdb::math::Transform::Ptr grid_transform(const VoxelGrid& g) {
  auto transform = openvdb::math::Transform::createLinearTransform(g.voxel);
  transform->postTranslate(openvdb::Vec3d(g.origin.x() + 0.5 * g.voxel, g.origin.y() + 0.5 * g.voxel, g.origin.z() + 0.5 * g.voxel));
  return transform;
}

template <class GridT>
typename GridT::Ptr grid_named(const openvdb::GridPtrVecPtr& grids, const std::string& name, const std::string& file) {
  for (const auto& base : *grids)
    if (base->getName() == name) {
      auto grid = openvdb::gridPtrCast<GridT>(base);
      if (!grid) throw Error(file, "grid " + name, "has the wrong value type (density float, orientation vec3s, yarn int32)");
      return grid;
    }
  throw Error(file, "grid " + name, "is missing (an exemplar holds the grids density, orientation and yarn)");
}

/// An exemplar as bytes, to come back from the child process that parsed it.
template <class T>
void put(std::string& out, const T* data, size_t count) {
  out.append(reinterpret_cast<const char*>(&count), sizeof count);
  out.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}
template <class T>
std::vector<T> take(const std::string& in, size_t& at) {
  size_t count = 0;
  std::memcpy(&count, in.data() + at, sizeof count);
  at += sizeof count;
  std::vector<T> v(count);
  std::memcpy(static_cast<void*>(v.data()), in.data() + at, count * sizeof(T));
  at += count * sizeof(T);
  return v;
}

std::string pack(const Exemplar& ex) {
  std::string out;
  const std::string weave = to_text(ex.weave);
  put(out, ex.name.data(), ex.name.size());
  put(out, weave.data(), weave.size());
  const int ints[] = {ex.block_x, ex.block_y, ex.grid.nx, ex.grid.ny, ex.grid.nz};
  const double doubles[] = {ex.spacing, ex.radius, ex.grid.voxel, ex.grid.origin.x(), ex.grid.origin.y(), ex.grid.origin.z()};
  put(out, ints, 5);
  put(out, doubles, 6);
  put(out, ex.grid.density.data(), ex.grid.density.size());
  put(out, ex.grid.orientation.data(), ex.grid.orientation.size());
  put(out, ex.grid.yarn.data(), ex.grid.yarn.size());
  return out;
}

Exemplar unpack(const std::string& in, const std::string& file) {
  size_t at = 0;
  Exemplar ex;
  const auto name = take<char>(in, at), weave = take<char>(in, at);
  ex.name.assign(name.begin(), name.end());
  ex.weave = from_text(std::string(weave.begin(), weave.end()), file);
  const auto ints = take<int>(in, at);
  const auto doubles = take<double>(in, at);
  ex.block_x = ints[0], ex.block_y = ints[1], ex.grid.nx = ints[2], ex.grid.ny = ints[3], ex.grid.nz = ints[4];
  ex.spacing = doubles[0], ex.radius = doubles[1], ex.grid.voxel = doubles[2];
  ex.grid.origin = {doubles[3], doubles[4], doubles[5]};
  ex.grid.density = take<float>(in, at);
  ex.grid.orientation = take<Eigen::Vector3f>(in, at);
  ex.grid.yarn = take<std::int16_t>(in, at);
  return ex;
}

std::string voxel_name(const openvdb::Coord& c) {
  return "(" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + ")";
}

}  // namespace

void write_exemplar(const Exemplar& ex, const std::filesystem::path& path) {
  openvdb::initialize();
  const auto& g = ex.grid;
  auto density = openvdb::FloatGrid::create(0.0f);
  auto orientation = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
  auto yarn = openvdb::Int32Grid::create(-1);
  density->setName("density");
  orientation->setName("orientation");
  yarn->setName("yarn");
  density->setGridClass(openvdb::GRID_FOG_VOLUME);
  const auto transform = grid_transform(g);
  for (auto* grid : std::initializer_list<openvdb::GridBase*>{density.get(), orientation.get(), yarn.get()}) grid->setTransform(transform->copy());
  auto d = density->getAccessor();
  auto o = orientation->getAccessor();
  auto y = yarn->getAccessor();
  for (int z = 0; z < g.nz; ++z)
    for (int yy = 0; yy < g.ny; ++yy)
      for (int x = 0; x < g.nx; ++x) {
        const size_t i = g.index(x, yy, z);
        if (g.yarn[i] < 0) continue;
        const openvdb::Coord c(x, yy, z);
        d.setValue(c, g.density[i]);
        o.setValue(c, openvdb::Vec3s(g.orientation[i].x(), g.orientation[i].y(), g.orientation[i].z()));
        y.setValue(c, g.yarn[i]);
      }
  openvdb::MetaMap meta;
  meta.insertMeta("skein_exemplar", openvdb::StringMetadata(ex.name));
  meta.insertMeta("skein_weave", openvdb::StringMetadata(to_text(ex.weave)));
  meta.insertMeta("skein_size", openvdb::Vec3IMetadata(openvdb::Vec3i(g.nx, g.ny, g.nz)));
  meta.insertMeta("skein_block", openvdb::Vec2IMetadata(openvdb::Vec2i(ex.block_x, ex.block_y)));
  meta.insertMeta("skein_origin", openvdb::Vec3DMetadata(openvdb::Vec3d(g.origin.x(), g.origin.y(), g.origin.z())));
  meta.insertMeta("skein_voxel", openvdb::DoubleMetadata(g.voxel));
  meta.insertMeta("skein_spacing", openvdb::DoubleMetadata(ex.spacing));
  meta.insertMeta("skein_radius", openvdb::DoubleMetadata(ex.radius));
  const auto temporary = std::filesystem::path(path.string() + ".part");
  try {
    openvdb::io::File file(temporary.string());
    file.write({density, orientation, yarn}, meta);
    file.close();
    std::filesystem::rename(temporary, path);
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw Error(path.string(), "", std::string("could not be written: ") + e.what());
  }
}

/// Parses the file here (read_exemplar runs this in a child process).
static Exemplar parse_exemplar(const std::filesystem::path& path) {
  openvdb::initialize();
  const std::string file_name = path.string();
  openvdb::io::File file(file_name);
  openvdb::GridPtrVecPtr grids;
  openvdb::MetaMap::Ptr meta;
  try {
    file.open(false);
    grids = file.getGrids();
    meta = file.getMetadata();
    file.close();
  } catch (const std::exception& e) {
    throw Error(file_name, "", std::string("is not a readable OpenVDB file: ") + e.what());
  }
  const auto need = [&](const char* key) {
    if (!(*meta)[key]) throw Error(file_name, std::string("metadata ") + key, "is missing: not an exemplar written by skein weave-exemplar");
  };
  for (const char* key : {"skein_exemplar", "skein_weave", "skein_size", "skein_block", "skein_origin", "skein_voxel", "skein_spacing", "skein_radius"}) need(key);
  Exemplar ex;
  try {
    ex.name = meta->metaValue<std::string>("skein_exemplar");
    ex.weave = from_text(meta->metaValue<std::string>("skein_weave"), file_name);
    const auto size = meta->metaValue<openvdb::Vec3i>("skein_size");
    const auto block = meta->metaValue<openvdb::Vec2i>("skein_block");
    const auto origin = meta->metaValue<openvdb::Vec3d>("skein_origin");
    ex.grid.nx = size.x(), ex.grid.ny = size.y(), ex.grid.nz = size.z();
    ex.block_x = block.x(), ex.block_y = block.y();
    ex.grid.origin = {origin.x(), origin.y(), origin.z()};
    ex.grid.voxel = meta->metaValue<double>("skein_voxel");
    ex.spacing = meta->metaValue<double>("skein_spacing");
    ex.radius = meta->metaValue<double>("skein_radius");
  } catch (const openvdb::Exception& e) {
    throw Error(file_name, "metadata", std::string("has a value of the wrong type: ") + e.what());
  }
  auto& g = ex.grid;
  if (ex.block_x < 1 || ex.block_y < 1 || ex.block_x > 1024 || ex.block_y > 1024 || g.nz < 1 || g.nz > 4096)
    throw Error(file_name, "metadata skein_block", "needs blocks of 1 to 1024 voxels and a depth of 1 to 4096");
  if (g.nx != ex.block_x * ex.weave.warps || g.ny != ex.block_y * ex.weave.wefts)
    throw Error(file_name, "metadata skein_size", "is not the weave's crossings times the block size");
  if (!(g.voxel > 0) || !(ex.spacing > 0) || !(ex.radius > 0)) throw Error(file_name, "metadata", "needs a positive voxel size, spacing and radius");
  if (g.size() > 64ull * 1024 * 1024) throw Error(file_name, "metadata skein_size", "is larger than 64 M voxels");
  g.allocate();
  const auto density = grid_named<openvdb::FloatGrid>(grids, "density", file_name);
  const auto orientation = grid_named<openvdb::Vec3SGrid>(grids, "orientation", file_name);
  const auto yarn = grid_named<openvdb::Int32Grid>(grids, "yarn", file_name);
  const int yarns = ex.weave.warps + ex.weave.wefts;
  const auto inside = [&](const openvdb::Coord& c) { return c.x() >= 0 && c.y() >= 0 && c.z() >= 0 && c.x() < g.nx && c.y() < g.ny && c.z() < g.nz; };
  for (auto it = yarn->cbeginValueOn(); it; ++it) {
    const auto c = it.getCoord();
    if (!inside(c)) throw Error(file_name, "grid yarn voxel " + voxel_name(c), "lies outside the exemplar's size");
    if (*it < 0 || *it >= yarns) throw Error(file_name, "grid yarn voxel " + voxel_name(c), "names yarn " + std::to_string(*it) + " of " + std::to_string(yarns));
    g.yarn[g.index(c.x(), c.y(), c.z())] = static_cast<std::int16_t>(*it);
  }
  for (auto it = density->cbeginValueOn(); it; ++it) {
    const auto c = it.getCoord();
    if (!inside(c) || !(*it >= 0 && *it <= 1)) throw Error(file_name, "grid density voxel " + voxel_name(c), "lies outside the exemplar or outside 0 to 1");
    g.density[g.index(c.x(), c.y(), c.z())] = *it;
  }
  for (auto it = orientation->cbeginValueOn(); it; ++it) {
    const auto c = it.getCoord();
    const openvdb::Vec3s v = *it;
    if (!inside(c) || !std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z()))
      throw Error(file_name, "grid orientation voxel " + voxel_name(c), "lies outside the exemplar or is not finite");
    g.orientation[g.index(c.x(), c.y(), c.z())] = Eigen::Vector3f(v.x(), v.y(), v.z());
  }
  return ex;
}

Exemplar read_exemplar(const std::filesystem::path& path) {
  // OpenVDB parses the file in a child process, under a memory limit and a deadline: a few wrong bytes can make
  // it allocate gigabytes for a name (fuzzing found one that took 24 s before the error).
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path.string(), "", "is not a readable OpenVDB file: no such file");
  auto limits = ContainedLimits::from_environment();
  if (!(limits.seconds > 0)) limits.seconds = 10 + 2 * static_cast<double>(std::filesystem::file_size(path, ec)) / 1e6;
  return unpack(run_contained(path.string(), "the OpenVDB reader", limits, [&] { return pack(parse_exemplar(path)); }), path.string());
}

std::vector<Exemplar> read_exemplars(const std::filesystem::path& folder) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) throw Error(folder.string(), "", "is not a folder of exemplars");
  const auto files = files_with_extension(folder, ".vdb");
  if (files.empty()) throw Error(folder.string(), "", "holds no .vdb exemplars (make them with skein weave-exemplar)");
  std::vector<Exemplar> out;
  for (const auto& f : files) out.push_back(read_exemplar(f));
  return out;
}

}  // namespace skein::woven
