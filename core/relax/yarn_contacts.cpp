#include "relax/yarn_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>

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
  if (n == 0) return {};
  const double reach = 2 * system.radius + margin;
  // The cells suit the spheres of all but the largest hundredth of the segments (a few long ones would make them
  // several times larger): two such spheres close enough have centres less than 2 R_small + reach apart, within one
  // cell of each other. A larger sphere looks as many cells out as its radius needs.
  std::vector<double> radii(n);
  for (int s = 0; s < n; ++s) radii[s] = spheres[s].radius;
  const int percentile = std::min(n - 1, n - n / 100);
  std::nth_element(radii.begin(), radii.begin() + percentile, radii.end());
  const double small = radii[percentile], cell = (2 * small + reach) * (1 + 1e-9);  // a hair wider than needed: no rounding loses a pair
  const auto cell_of = [&](const Eigen::Vector3d& c) {
    return Eigen::Vector3i(static_cast<int>(std::floor(c.x() / cell)), static_cast<int>(std::floor(c.y() / cell)),
                           static_cast<int>(std::floor(c.z() / cell)));
  };
  const auto key = [](const Eigen::Vector3i& c) {
    const auto part = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v + (1 << 20)) & 0x1fffff); };
    return (part(c.x()) << 42) | (part(c.y()) << 21) | part(c.z());
  };
  // The segments sorted by cell, their spheres copied in that order (each cell's contiguous), and the occupied
  // cells with where their segments start.
  std::vector<std::pair<std::uint64_t, int>> sorted(n);
#pragma omp parallel for schedule(static)
  for (int s = 0; s < n; ++s) sorted[s] = {key(cell_of(spheres[s].center)), s};
  std::sort(sorted.begin(), sorted.end());
  std::vector<SegmentSphere> ball(n);
  std::vector<char> large(n);
  std::vector<int> larges;
  std::vector<std::uint64_t> cell_key;
  std::vector<int> cell_start;
  for (int i = 0; i < n; ++i) {
    ball[i] = spheres[sorted[i].second];
    large[i] = ball[i].radius > small;
    if (large[i]) larges.push_back(i);
    if (i == 0 || sorted[i].first != sorted[i - 1].first) {
      cell_key.push_back(sorted[i].first);
      cell_start.push_back(i);
    }
  }
  const int cells = static_cast<int>(cell_key.size());
  cell_start.push_back(n);
  const auto find_cell = [&](const Eigen::Vector3i& c) {
    const auto k = key(c);
    const auto it = std::lower_bound(cell_key.begin(), cell_key.end(), k);
    return it == cell_key.end() || *it != k ? -1 : static_cast<int>(it - cell_key.begin());
  };
  const auto view = segment_view(system);
  const auto touch = [&](int i, int j) {
    return close_enough(ball[i], ball[j], reach) && !model::consecutive(view, sorted[i].second, sorted[j].second);
  };
  // Each unordered pair once. Two small spheres: a cell with itself, and with the 13 of its 26 neighbours that
  // follow it (the others test it from their side). A large sphere with the small ones in the cells its reach
  // covers, and with the large ones after it in order of their lowest x whose lowest x it reaches (sweep and
  // prune: a pair close enough overlaps in x by less than the reach).
  std::vector<Eigen::Vector3i> forward;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz)
        if (std::make_tuple(dx, dy, dz) > std::make_tuple(0, 0, 0)) forward.emplace_back(dx, dy, dz);
  std::sort(larges.begin(), larges.end(), [&](int a, int b) { return ball[a].center.x() - ball[a].radius < ball[b].center.x() - ball[b].radius; });
  const int jobs = cells + static_cast<int>(larges.size());
  std::vector<std::pair<int, int>> pairs;
#pragma omp parallel
  {
    std::vector<std::pair<int, int>> found;
    const auto test = [&](int i, int j) {
      if (touch(i, j)) found.emplace_back(sorted[i].second, sorted[j].second);
    };
#pragma omp for schedule(dynamic, 16) nowait
    for (int job = 0; job < jobs; ++job) {
      if (job < cells) {
        const int begin = cell_start[job], end = cell_start[job + 1];
        for (int i = begin; i < end; ++i)
          if (!large[i])
            for (int j = i + 1; j < end; ++j)
              if (!large[j]) test(i, j);
        const Eigen::Vector3i home = cell_of(ball[begin].center);
        for (const auto& offset : forward) {
          const int other = find_cell(home + offset);
          if (other < 0) continue;
          for (int i = begin; i < end; ++i)
            if (!large[i])
              for (int j = cell_start[other]; j < cell_start[other + 1]; ++j)
                if (!large[j]) test(i, j);
        }
      } else {
        const int rank = job - cells, i = larges[rank];
        const int out = static_cast<int>(std::ceil((ball[i].radius + small + reach) / cell));
        const Eigen::Vector3i home = cell_of(ball[i].center);
        for (int dx = -out; dx <= out; ++dx)
          for (int dy = -out; dy <= out; ++dy)
            for (int dz = -out; dz <= out; ++dz) {
              const int other = find_cell(home + Eigen::Vector3i(dx, dy, dz));
              if (other < 0) continue;
              for (int j = cell_start[other]; j < cell_start[other + 1]; ++j)
                if (!large[j]) test(i, j);
            }
        const double end = ball[i].center.x() + (ball[i].radius + reach) * (1 + 1e-9);
        for (int k = rank + 1; k < static_cast<int>(larges.size()) && ball[larges[k]].center.x() - ball[larges[k]].radius < end; ++k)
          test(i, larges[k]);
      }
    }
#pragma omp critical
    pairs.insert(pairs.end(), found.begin(), found.end());
  }
  // Both ways, each segment's partners sorted (the order the threads found them in does not matter).
  ContactPairs out;
  out.start.assign(n + 1, 0);
  for (const auto& [a, b] : pairs) ++out.start[a + 1], ++out.start[b + 1];
  std::partial_sum(out.start.begin(), out.start.end(), out.start.begin());
  out.partner.resize(out.start[n]);
  std::vector<int> next(out.start.begin(), out.start.end() - 1);
  for (const auto& [a, b] : pairs) out.partner[next[a]++] = b, out.partner[next[b]++] = a;
#pragma omp parallel for schedule(static)
  for (int s = 0; s < n; ++s) std::sort(out.partner.begin() + out.start[s], out.partner.begin() + out.start[s + 1]);
  return out;
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
