#include "stitchmesh/mesh_repair.hpp"

#include <cmath>

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Simple_cartesian.h>

namespace skein::mesh {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Polygon = std::vector<std::size_t>;
namespace pmp = CGAL::Polygon_mesh_processing;

std::string counted(long n, const std::string& one, const std::string& many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

/// A face's corners with repeats in a row (and across its start) dropped; empty when under 3 remain or the
/// polygon has zero area.
Polygon simplified(const Polygon& face, const std::vector<Kernel::Point_3>& points) {
  Polygon out;
  for (std::size_t v : face)
    if (out.empty() || out.back() != v) out.push_back(v);
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  if (out.size() < 3) return {};
  Kernel::Vector_3 area(0, 0, 0);  // twice the vector area (Newell)
  for (std::size_t k = 0; k < out.size(); ++k) area = area + CGAL::cross_product(points[out[k]] - CGAL::ORIGIN, points[out[(k + 1) % out.size()]] - CGAL::ORIGIN);
  if (!(area.squared_length() > 0)) return {};
  return out;
}

}  // namespace

bool RepairReport::changed() const {
  return non_finite_faces + merged_points + degenerate_faces + duplicate_faces + reversed_faces + split_points + unused_points > 0;
}

std::string RepairReport::summary() const {
  std::string text;
  const auto add = [&](long n, const std::string& what) {
    if (n > 0) text += (text.empty() ? "" : ", ") + what;
  };
  add(non_finite_faces, "removed " + counted(non_finite_faces, "face", "faces") + " with a non-finite corner");
  add(merged_points, "merged " + counted(merged_points, "duplicate point", "duplicate points"));
  add(degenerate_faces, "removed " + counted(degenerate_faces, "degenerate face", "degenerate faces"));
  add(duplicate_faces, "removed " + counted(duplicate_faces, "duplicate face", "duplicate faces"));
  add(reversed_faces, "turned " + counted(reversed_faces, "face", "faces") + " round to agree with " + (reversed_faces == 1 ? "its" : "their") + " neighbours");
  add(split_points, "split " + counted(split_points, "point", "points") + " where the surface met itself");
  add(unused_points, "dropped " + counted(unused_points, "unused point", "unused points"));
  return text.empty() ? "nothing to repair" : text;
}

MeshSoup repair_mesh_soup(MeshSoup soup, RepairReport& report) {
  report = {};
  std::vector<Kernel::Point_3> points;
  points.reserve(soup.points.size());
  for (const auto& p : soup.points) points.emplace_back(p.x(), p.y(), p.z());
  std::vector<Polygon> polygons;
  for (const auto& f : soup.faces) {
    bool finite = true;
    for (int v : f) finite = finite && soup.points[static_cast<std::size_t>(v)].allFinite();
    if (!finite) {
      ++report.non_finite_faces;
      continue;
    }
    polygons.emplace_back(f.begin(), f.end());
  }
  report.merged_points = static_cast<long>(pmp::merge_duplicate_points_in_polygon_soup(points, polygons));
  std::vector<Polygon> kept;
  for (const auto& f : polygons) {
    Polygon g = simplified(f, points);
    if (g.empty()) ++report.degenerate_faces;
    else kept.push_back(std::move(g));
  }
  polygons = std::move(kept);
  report.duplicate_faces = static_cast<long>(pmp::merge_duplicate_polygons_in_polygon_soup(points, polygons));
  report.unused_points = static_cast<long>(pmp::remove_isolated_points_in_polygon_soup(points, polygons));
  // Orientation: orient_polygon_soup reverses faces (counted against a copy) and duplicates the points where
  // the surface is not a manifold, so that it can be oriented.
  const std::vector<Polygon> before = polygons;
  const std::size_t count_before = points.size();
  pmp::orient_polygon_soup(points, polygons);
  report.split_points = static_cast<long>(points.size() - count_before);
  for (std::size_t i = 0; i < polygons.size() && i < before.size(); ++i)
    if (polygons[i] != before[i] && polygons[i].size() == before[i].size()) {
      Polygon reversed(before[i].rbegin(), before[i].rend());
      // A reversed polygon may start at another corner: compare as cycles.
      bool same_cycle = false;
      for (std::size_t shift = 0; shift < reversed.size() && !same_cycle; ++shift) {
        bool all = true;
        for (std::size_t k = 0; k < reversed.size() && all; ++k) all = points[polygons[i][k]] == points[reversed[(k + shift) % reversed.size()]];
        same_cycle = all;
      }
      if (same_cycle) ++report.reversed_faces;
    }
  MeshSoup out;
  out.points.reserve(points.size());
  for (const auto& p : points) out.points.emplace_back(p.x(), p.y(), p.z());
  for (const auto& f : polygons) {
    std::vector<int> face;
    for (std::size_t v : f) face.push_back(static_cast<int>(v));
    out.faces.push_back(std::move(face));
  }
  return out;
}

}  // namespace skein::mesh
