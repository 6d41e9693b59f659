#include "relax/periodic_map.hpp"

#include <cmath>
#include <string>

#include "common/error.hpp"

namespace skein::relax {

void apply_periodic(const PeriodicMap& map, Eigen::Matrix3Xd& delta, Eigen::Matrix3Xd& velocities) {
  for (size_t i = 0; i < map.virtual_points.size(); ++i) {
    delta.col(map.virtual_points[i]) = delta.col(map.real_points[i]);
    velocities.col(map.virtual_points[i]) = velocities.col(map.real_points[i]);
  }
  for (int p : map.frozen) {
    delta.col(p).setZero();
    velocities.col(p).setZero();
  }
}

void group_copies(const PeriodicMap& map, std::vector<int>& groups, int first) {
  for (size_t i = 0; i < map.virtual_points.size(); ++i) {
    int& real = groups[map.real_points[i]];
    if (real < 0) real = first++;
    groups[map.virtual_points[i]] = real;
  }
}

void scale_period(PeriodicMap& map, Eigen::Matrix3Xd& points, double sx, double sy) {
  if (!(sx > 0 && sy > 0 && std::isfinite(sx) && std::isfinite(sy)))
    throw Error("", "period", "the period scales must be positive, found " + std::to_string(sx) + " x " + std::to_string(sy));
  points.row(0) *= sx;
  points.row(1) *= sy;
  for (auto& d : map.offsets) {
    d.x() *= sx;
    d.y() *= sy;
  }
  for (Eigen::Vector3d* d : {&map.period_x, &map.period_y}) {
    d->x() *= sx;
    d->y() *= sy;
  }
}

void set_period(PeriodicMap& map, Eigen::Matrix3Xd& points, const Eigen::Vector3d& period_x, const Eigen::Vector3d& period_y) {
  if (map.cells.size() != map.virtual_points.size()) throw Error("", "period", "the periodic map does not say each virtual point's repeat");
  map.period_x = period_x;
  map.period_y = period_y;
  for (size_t i = 0; i < map.virtual_points.size(); ++i) {
    map.offsets[i] = map.cells[i].x() * period_x + map.cells[i].y() * period_y;
    points.col(map.virtual_points[i]) = points.col(map.real_points[i]) + map.offsets[i];
  }
}

void constrain_gradient(const PeriodicMap& map, Eigen::Matrix3Xd& gradient) {
  for (int p : map.virtual_points) gradient.col(p).setZero();
  for (int p : map.frozen) gradient.col(p).setZero();
}

double patch_loop_length(const YarnSystem& system, const PeriodicMap& map, const std::array<int, 2>& repeat) {
  // The yarn of one repeat: the rest lengths of the segments that start at a real point.
  std::vector<char> copy(system.num_points(), 0);
  for (int v : map.virtual_points) copy[v] = 1;
  double yarn = 0;
  for (int s = 0; s < system.num_segments(); ++s)
    if (!copy[system.segment_points[s][1]]) yarn += system.rest_length[s];
  return yarn / (repeat[0] * repeat[1]);
}

}  // namespace skein::relax
