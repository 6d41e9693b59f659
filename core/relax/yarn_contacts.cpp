#include "relax/yarn_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "relax/guard_model.hpp"

namespace skein::relax {
namespace {

model::Vec3<double> vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

bool close_enough(const SegmentSphere& a, const SegmentSphere& b, double reach) {
  return (a.center - b.center).norm() - a.radius - b.radius < reach;
}

/// Pairs kept both ways, partners sorted: the CSR of ContactPairs.
ContactPairs to_csr(int segments, std::vector<std::vector<int>>& lists) {
  ContactPairs out;
  out.start.resize(segments + 1, 0);
  for (int s = 0; s < segments; ++s) {
    std::sort(lists[s].begin(), lists[s].end());
    out.start[s + 1] = out.start[s] + static_cast<int>(lists[s].size());
  }
  out.partner.reserve(out.start[segments]);
  for (auto& list : lists) out.partner.insert(out.partner.end(), list.begin(), list.end());
  return out;
}

}  // namespace

std::vector<SegmentSphere> segment_spheres(const YarnSystem& system, const Eigen::Matrix3Xd& points) {
  std::vector<SegmentSphere> spheres(system.num_segments());
#pragma omp parallel for schedule(static)
  for (int seg = 0; seg < system.num_segments(); ++seg) {
    model::Vec3<double> p[4], c;
    for (int k = 0; k < 4; ++k) p[k] = vec(points.col(system.segment_points[seg][k]));
    double r;
    model::bezier_sphere(p, 0.0, 1.0, c, r);
    spheres[seg] = {Eigen::Vector3d(c.x, c.y, c.z), r};
  }
  return spheres;
}

ContactPairs find_contact_pairs(const YarnSystem& system, const Eigen::Matrix3Xd& points, double margin) {
  const auto spheres = segment_spheres(system, points);
  const int n = system.num_segments();
  const double reach = 2 * system.radius + margin;
  double largest = 0;
  for (const auto& s : spheres) largest = std::max(largest, s.radius);
  // Two spheres that can be close enough have centres at most 2 R_max + reach apart: one cell.
  const double cell = 2 * largest + reach;
  const auto cell_of = [&](const Eigen::Vector3d& c) {
    return Eigen::Vector3i(static_cast<int>(std::floor(c.x() / cell)), static_cast<int>(std::floor(c.y() / cell)),
                           static_cast<int>(std::floor(c.z() / cell)));
  };
  const auto key = [](const Eigen::Vector3i& c) {
    const auto part = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v + (1 << 20)) & 0x1fffff); };
    return (part(c.x()) << 42) | (part(c.y()) << 21) | part(c.z());
  };
  std::vector<std::pair<std::uint64_t, int>> sorted(n);
  for (int s = 0; s < n; ++s) sorted[s] = {key(cell_of(spheres[s].center)), s};
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::vector<int>> lists(n);
#pragma omp parallel for schedule(dynamic, 256)
  for (int s = 0; s < n; ++s) {
    const Eigen::Vector3i home = cell_of(spheres[s].center);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto k = key(home + Eigen::Vector3i(dx, dy, dz));
          auto it = std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(k, -1));
          for (; it != sorted.end() && it->first == k; ++it)
            if (!system.consecutive(s, it->second) && close_enough(spheres[s], spheres[it->second], reach))
              lists[s].push_back(it->second);
        }
  }
  return to_csr(n, lists);
}

ContactPairs find_contact_pairs_brute_force(const YarnSystem& system, const Eigen::Matrix3Xd& points, double margin) {
  const auto spheres = segment_spheres(system, points);
  const int n = system.num_segments();
  const double reach = 2 * system.radius + margin;
  std::vector<std::vector<int>> lists(n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (!system.consecutive(a, b) && close_enough(spheres[a], spheres[b], reach)) lists[a].push_back(b);
  return to_csr(n, lists);
}

}  // namespace skein::relax
