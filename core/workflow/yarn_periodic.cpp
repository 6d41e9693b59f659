#include "workflow/yarn_periodic.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "common/error.hpp"
#include "relax/yarn_system.hpp"
#include "stitchmesh/yarn_emission.hpp"

namespace skein::workflow {
namespace {

/// Virtual rings: at least two stitches or yarns wide on every side.
int virtual_rings(const mesh::Pattern& pattern) {
  return std::max({1, (2 + pattern.width() - 1) / pattern.width(), (2 + pattern.height() - 1) / pattern.height()});
}

/// Fills the map from each point's repeat (a, b) (or -1 for none): the centre repeat is real, the rings up to
/// `rings` from it virtual where a centre point sits at the position less the repeat's offset, the rest frozen.
void map_points(PeriodicPatch& patch, const std::vector<std::pair<int, int>>& repeat, int rings) {
  const int centre = rings + 1;
  const int n = static_cast<int>(patch.yarn.points.size());
  patch.map.period_x = patch.period_x;
  patch.map.period_y = patch.period_y;
  patch.ring.assign(n, patch.tiles);
  std::map<relax::PositionKey, int> real;
  for (int p = 0; p < n; ++p) {
    const auto [a, b] = repeat[p];
    if (a < 0) continue;
    patch.ring[p] = std::max(std::abs(a - centre), std::abs(b - centre));
    if (patch.ring[p] == 0) real.emplace(relax::position_key(patch.yarn.points[p]), p);
  }
  // A point on the centre repeat's edge can belong to it twice: a yarn that leaves through its top edge comes in
  // through the bottom one a period lower, and both points are the centre's faces'. The later of the two is a
  // copy of the earlier, as the rings' points are; else the repeat would hold the yarn there twice, in its energy
  // and its stress, and as two points free to part.
  std::vector<std::pair<int, Eigen::Vector2i>> copy_of(n, {-1, Eigen::Vector2i::Zero()});
  const auto add_virtual = [&](int p, int r, Eigen::Vector2i cell) {
    if (copy_of[r].first >= 0) cell += copy_of[r].second, r = copy_of[r].first;
    patch.map.virtual_points.push_back(p);
    patch.map.real_points.push_back(r);
    patch.map.offsets.push_back(cell.x() * patch.period_x + cell.y() * patch.period_y);
    patch.map.cells.push_back(cell);
  };
  for (int p = 0; p < n; ++p) {
    if (patch.ring[p] != 0) continue;
    for (int a = -1; a <= 1 && copy_of[p].first < 0; ++a)
      for (int b = -1; b <= 1 && copy_of[p].first < 0; ++b) {
        if (a == 0 && b == 0) continue;
        const auto it = real.find(relax::position_key(patch.yarn.points[p] - a * patch.period_x - b * patch.period_y));
        if (it != real.end() && it->second < p && copy_of[it->second].first < 0) copy_of[p] = {it->second, Eigen::Vector2i(a, b)};
      }
    if (copy_of[p].first >= 0) {
      patch.ring[p] = 1;
      add_virtual(p, copy_of[p].first, copy_of[p].second);
    }
  }
  for (int p = 0; p < n; ++p) {
    if (patch.ring[p] == 0 || copy_of[p].first >= 0) continue;
    if (patch.ring[p] <= rings) {
      const auto [a, b] = repeat[p];
      const Eigen::Vector3d offset = (a - centre) * patch.period_x + (b - centre) * patch.period_y;
      if (const auto it = real.find(relax::position_key(patch.yarn.points[p] - offset)); it != real.end()) {
        add_virtual(p, it->second, Eigen::Vector2i(a - centre, b - centre));
        continue;
      }
    }
    patch.map.frozen.push_back(p);
  }
}

/// Removes the frozen points: they only made the virtual rings' stitches interior ones at emission. Curves
/// are cut where they leave; the pieces that remain keep their order, and the map its meaning.
void drop_frozen(PeriodicPatch& patch) {
  const int n = static_cast<int>(patch.yarn.points.size());
  std::vector<char> keep(n, 1);
  for (int p : patch.map.frozen) keep[p] = 0;
  std::vector<int> index;
  auto out = relax::cut_curves(patch.yarn, keep, index);
  std::vector<int> ring(out.points.size());
  for (int p = 0; p < n; ++p)
    if (index[p] >= 0) ring[index[p]] = patch.ring[p];
  relax::PeriodicMap map;
  for (size_t i = 0; i < patch.map.virtual_points.size(); ++i) {
    const int v = index[patch.map.virtual_points[i]], r = index[patch.map.real_points[i]];
    if (v < 0) continue;  // a lone virtual point between dropped ones
    if (r < 0) throw Error("", "periodic patch", "a real point fell on a piece of fewer than two points");
    map.virtual_points.push_back(v);
    map.real_points.push_back(r);
    map.offsets.push_back(patch.map.offsets[i]);
    map.cells.push_back(patch.map.cells[i]);
  }
  map.period_x = patch.map.period_x;
  map.period_y = patch.map.period_y;
  patch.yarn = std::move(out);
  patch.map = std::move(map);
  patch.ring = std::move(ring);
}

}  // namespace

PeriodicPatch periodic_patch(const mesh::Pattern& written, const mesh::StitchLibrary& library, const mesh::StitchSize& size, double radius) {
  if (written.format == mesh::PatternFormat::Woven) throw Error("", "pattern " + written.name, "is woven: use periodic_woven_patch");
  const mesh::Pattern pattern = written.height() % 2 == 0 ? written : mesh::stacked(written, 2);
  const int rings = virtual_rings(pattern);
  PeriodicPatch patch;
  patch.repeat = {pattern.width(), pattern.height()};
  patch.tiles = 2 * rings + 3;
  const auto stitch = mesh::pattern_stitch_mesh(pattern, patch.tiles, patch.tiles, size);
  mesh::EmitOptions emit;
  emit.yarn_radius = radius;
  patch.yarn = mesh::emit_yarn(stitch, library, emit);
  patch.period_x = {pattern.width() * size.width, 0, 0};
  patch.period_y = {0, pattern.height() * size.height, 0};
  // pattern_stitch_mesh makes faces row by row, each row its repeats left to right.
  std::vector<std::pair<int, int>> face_repeat;
  for (int r = 0; r < patch.tiles * pattern.height(); ++r) {
    const int per_copy = static_cast<int>(pattern.rows[r % pattern.height()].size());
    for (int copy = 0; copy < patch.tiles; ++copy)
      for (int t = 0; t < per_copy; ++t) face_repeat.emplace_back(copy, r / pattern.height());
  }
  // A cable's crossing yarn (between two rows, reaching into both) goes with the stitch below it: of the
  // nearest points along its yarn that have a face, the one in the lower row. Other points of no face (turns,
  // bind-offs) go by position: the repeat of the row below.
  const auto& yarn = patch.yarn;
  const auto below_cable = [&](int p) {
    const int c = yarn.yarn_of(p), begin = yarn.curve_start[c], end = yarn.curve_start[c + 1];
    int best = -1;
    for (int step : {-1, 1}) {
      int q = p;
      while (q >= begin && q < end && yarn.point_face[q] < 0) q += step;
      if (q < begin || q >= end) continue;
      const int f = yarn.point_face[q];
      if (best < 0 || stitch.faces[f].row < stitch.faces[best].row) best = f;
    }
    return best;
  };
  std::vector<std::pair<int, int>> repeat;
  for (size_t p = 0; p < yarn.points.size(); ++p) {
    int f = yarn.point_face[p];
    if (f < 0 && yarn.point_type[p] >= 0 && yarn.type_names[yarn.point_type[p]].starts_with("cable")) f = below_cable(static_cast<int>(p));
    if (f >= 0 && f < static_cast<int>(face_repeat.size())) {
      repeat.push_back(face_repeat[f]);
      continue;
    }
    const Eigen::Vector3d& x = patch.yarn.points[p];
    const int a = static_cast<int>(std::floor(x.x() / patch.period_x.x())), b = static_cast<int>(std::floor((x.y() - 0.5 * size.height) / patch.period_y.y()));
    repeat.push_back(a >= 0 && a < patch.tiles && b >= 0 && b < patch.tiles ? std::pair{a, b} : std::pair{-1, -1});
  }
  map_points(patch, repeat, rings);
  drop_frozen(patch);
  return patch;
}

PeriodicPatch periodic_woven_patch(const mesh::Pattern& pattern, double spacing, double radius) {
  const int rings = virtual_rings(pattern);
  PeriodicPatch patch;
  patch.repeat = {pattern.width(), pattern.height()};
  patch.tiles = 2 * rings + 3;
  patch.yarn = mesh::woven_yarn(pattern, patch.tiles, patch.tiles, spacing, radius);
  mesh::colour_woven_yarn(patch.yarn, pattern, patch.tiles, patch.tiles);  // before the frozen ends are cut off
  patch.period_x = {pattern.width() * spacing, 0, 0};
  patch.period_y = {0, pattern.height() * spacing, 0};
  // Crossings lie on the grid of yarns; the yarns' ends beyond the last crossing belong to no repeat.
  const int cols = patch.tiles * pattern.width(), rows = patch.tiles * pattern.height();
  std::vector<std::pair<int, int>> repeat;
  for (const auto& p : patch.yarn.points) {
    const double j = p.x() / spacing, i = p.y() / spacing;
    const long jj = std::lround(j), ii = std::lround(i);
    const bool on_grid = std::abs(j - jj) < 1e-9 && std::abs(i - ii) < 1e-9 && jj >= 0 && jj < cols && ii >= 0 && ii < rows;
    repeat.push_back(on_grid ? std::pair{static_cast<int>(jj / pattern.width()), static_cast<int>(ii / pattern.height())} : std::pair{-1, -1});
  }
  map_points(patch, repeat, rings);
  drop_frozen(patch);
  return patch;
}

TiledPreview tile_relaxed_patch(const PeriodicPatch& patch, const Eigen::Matrix3Xd& relaxed, const relax::YarnCurves& tiled,
                                const Eigen::Vector2d& period_scale, const Eigen::Matrix<double, 3, 2>* period) {
  const int n = static_cast<int>(tiled.points.size());
  if (relaxed.cols() != static_cast<Eigen::Index>(patch.ring.size()))
    throw Error("", "tiled preview", "the relaxed state has " + std::to_string(relaxed.cols()) + " points, the patch " + std::to_string(patch.ring.size()));
  std::map<relax::PositionKey, int> real;
  for (int p = 0; p < static_cast<int>(patch.ring.size()); ++p)
    if (patch.ring[p] == 0) real.emplace(relax::position_key(patch.yarn.points[p]), p);
  const int centre = (patch.tiles - 1) / 2;
  // The emitted tiling mapped onto the relaxed lattice: by the period scales, or by the free period's own
  // lattice (the linear map that takes the emitted period to the relaxed one).
  Eigen::Matrix3d lattice = Eigen::Vector3d(period_scale.x(), period_scale.y(), 1).asDiagonal();
  if (period) {
    Eigen::Matrix3d from, to;
    from << patch.period_x, patch.period_y, Eigen::Vector3d::UnitZ();
    to << period->col(0), period->col(1), Eigen::Vector3d::UnitZ();
    lattice = to * from.inverse();
  }
  const auto scaled = [&](const Eigen::Vector3d& x) { return Eigen::Vector3d(lattice * x); };
  TiledPreview out;
  out.points.resize(3, n);
  std::vector<char> placed(n, 0);
  for (int p = 0; p < n; ++p) {
    const Eigen::Vector3d& e = tiled.points[p];
    const int i0 = static_cast<int>(std::floor(e.x() / patch.period_x.x())) - centre, j0 = static_cast<int>(std::floor(e.y() / patch.period_y.y())) - centre;
    for (int di = -1; di <= 1 && !placed[p]; ++di)
      for (int dj = -1; dj <= 1 && !placed[p]; ++dj) {
        const Eigen::Vector3d offset = (i0 + di) * patch.period_x + (j0 + dj) * patch.period_y;
        if (const auto it = real.find(relax::position_key(e - offset)); it != real.end()) {
          out.points.col(p) = relaxed.col(it->second) + scaled(offset);
          placed[p] = 1;
        }
      }
  }
  // The rest move as the nearest placed point of their yarn.
  Eigen::Matrix3Xd base(3, n);
  for (int p = 0; p < n; ++p) base.col(p) = scaled(tiled.points[p]);
  relax::follow_placed(tiled, placed, base, out.points);
  out.matched = static_cast<int>(std::count(placed.begin(), placed.end(), 1));
  return out;
}

PatchDifference centre_repeat_difference(const PeriodicPatch& patch, const Eigen::Matrix3Xd& patch_relaxed, const relax::YarnCurves& tiled,
                                         const Eigen::Matrix3Xd& tiled_relaxed, int n) {
  const int centre = (patch.tiles - 1) / 2;
  const Eigen::Vector3d shift = (centre - (n - 1) / 2) * (patch.period_x + patch.period_y);
  // The tiling's emitted points by position, as the patch matches its virtual points.
  std::map<relax::PositionKey, int> emitted;
  for (int q = 0; q < static_cast<int>(tiled.points.size()); ++q) emitted.emplace(relax::position_key(tiled.points[q] + shift), q);
  const auto match = [&](const Eigen::Vector3d& p) {
    const auto it = emitted.find(relax::position_key(p));
    return it == emitted.end() ? -1 : it->second;
  };
  std::vector<std::pair<int, int>> pairs;
  for (int p = 0; p < static_cast<int>(patch.ring.size()); ++p) {
    if (patch.ring[p] != 0) continue;
    const int q = match(patch.yarn.points[p]);
    if (q < 0) throw Error("", "periodic patch against a tiling", "real point " + std::to_string(p) + " has no point of the tiling at its place");
    pairs.emplace_back(p, q);
  }
  PatchDifference out;
  out.points = static_cast<int>(pairs.size());
  if (pairs.empty()) return out;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& [p, q] : pairs) mean += patch_relaxed.col(p) - tiled_relaxed.col(q);
  mean /= static_cast<double>(pairs.size());
  double sum = 0;
  for (const auto& [p, q] : pairs) {
    const double d = (patch_relaxed.col(p) - tiled_relaxed.col(q) - mean).norm();
    sum += d * d;
    out.largest = std::max(out.largest, d);
  }
  out.rms = std::sqrt(sum / static_cast<double>(pairs.size()));
  return out;
}

}  // namespace skein::workflow
