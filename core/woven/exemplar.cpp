#include "woven/exemplar.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "relax/yarn_relax.hpp"
#include "relax/yarn_system.hpp"
#include "workflow/yarn_io.hpp"
#include "workflow/yarn_shape.hpp"

namespace skein::woven {

void VoxelGrid::allocate() {
  density.assign(size(), 0.0f);
  orientation.assign(size(), Eigen::Vector3f::Zero());
  yarn.assign(size(), -1);
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// A hash of a voxel to [0, 1): the same fibres on every run.
double voxel_noise(size_t voxel, int yarn, std::uint64_t seed) {
  std::uint64_t h = voxel * 0x9E3779B97F4A7C15ull ^ (static_cast<std::uint64_t>(yarn) + 1) * 0xC2B2AE3D27D4EB4Full ^ seed;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

/// One yarn's centreline, densely sampled, with a parallel-transported frame (t, n, b) and the arc length.
struct Centreline {
  std::vector<Eigen::Vector3d> p, t, n, b;
  std::vector<double> s;
};

Centreline centreline(const std::vector<Eigen::Vector3d>& samples) {
  Centreline c;
  c.p = samples;
  const size_t k = samples.size();
  c.t.resize(k), c.n.resize(k), c.b.resize(k), c.s.assign(k, 0.0);
  for (size_t i = 0; i < k; ++i) {
    const Eigen::Vector3d d = samples[std::min(i + 1, k - 1)] - samples[i > 0 ? i - 1 : 0];
    c.t[i] = d.normalized();
    if (i > 0) c.s[i] = c.s[i - 1] + (samples[i] - samples[i - 1]).norm();
  }
  // The first normal: the fabric's normal (z) made perpendicular to the yarn, then carried along it.
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ().dot(c.t[0]) * c.t[0];
  if (n.norm() < 1e-6) n = c.t[0].unitOrthogonal();
  for (size_t i = 0; i < k; ++i) {
    n = (n - n.dot(c.t[i]) * c.t[i]).normalized();
    c.n[i] = n;
    c.b[i] = c.t[i].cross(n);
  }
  return c;
}

/// The fibres of one yarn at a point given in its frame: density and fibre direction (procedural plies after
/// Schröder 2015 and Zhao 2016: plies twisted around the centreline, each ply's fibres twisted the other way and
/// migrating in and out across the ply once per ply turn, a fibre density falling off across a ply, and sparse
/// flyaways outside the plies).
struct Fibres {
  int plies;
  double radius, helix, ply_radius, twist, phase, flyaways, migration;
  std::uint64_t seed;

  std::pair<float, Eigen::Vector3f> at(double s, double a, double b, const Eigen::Vector3d& t, const Eigen::Vector3d& n,
                                       const Eigen::Vector3d& bn, size_t voxel, int yarn) const {
    const double turn = 2 * std::numbers::pi / twist;
    double best = 0;
    Eigen::Vector3d direction = t;
    for (int k = 0; k < plies; ++k) {
      const double phi = turn * s + phase + 2 * std::numbers::pi * k / plies;
      const double ca = helix * std::cos(phi), cb = helix * std::sin(phi);
      const double da = a - ca, db = b - cb, delta = std::hypot(da, db);
      if (delta >= ply_radius) continue;
      const double rho = 0.8 * std::sqrt(1 - (delta / ply_radius) * (delta / ply_radius));
      if (rho <= best) continue;
      best = rho;
      // The ply's helix tangent, and the fibre's own twist around the ply's axis (the other hand).
      const Eigen::Vector3d around_yarn = -std::sin(phi) * n + std::cos(phi) * bn;
      const Eigen::Vector3d around_ply = delta > 1e-12 ? Eigen::Vector3d(-(db / delta) * n + (da / delta) * bn) : Eigen::Vector3d::Zero();
      const Eigen::Vector3d across_ply = delta > 1e-12 ? Eigen::Vector3d((da / delta) * n + (db / delta) * bn) : Eigen::Vector3d::Zero();
      // Migration: a fibre's distance from the ply's axis swings by `migration` of the ply's radius over a ply
      // turn, its phase set by where around the ply it lies; d(distance)/ds tilts it across the ply.
      const double swing = -0.5 * migration * ply_radius * turn * std::sin(turn * s + std::atan2(db, da));
      direction = (t + turn * helix * around_yarn - turn * delta * around_ply + swing * across_ply).normalized();
    }
    const double r = std::hypot(a, b);
    if (best == 0 && r < 1.4 * radius && r > 0.9 * radius && voxel_noise(voxel, yarn, seed) < 0.25) {
      best = flyaways * 0.8;
      direction = (t + 0.6 * (voxel_noise(voxel + 1, yarn, seed) - 0.5) * n + 0.6 * (voxel_noise(voxel + 2, yarn, seed) - 0.5) * bn).normalized();
    }
    return {static_cast<float>(best), direction.cast<float>()};
  }
};

}  // namespace

Exemplar voxelize(const relax::YarnCurves& yarn, const std::vector<int>& warp_curves, const std::vector<int>& weft_curves,
                  const Eigen::Vector2d& corner, const ExemplarOptions& options) {
  const double spacing = options.spacing > 0 ? options.spacing : 3 * options.radius;
  const double r = options.radius, voxel = spacing / options.voxels_per_crossing;
  Exemplar ex;
  ex.spacing = spacing;
  ex.radius = r;
  ex.block_x = ex.block_y = options.voxels_per_crossing;
  ex.weave = detect_weave(yarn, warp_curves, weft_curves);
  auto& g = ex.grid;
  g.voxel = voxel;
  g.nx = ex.block_x * ex.weave.warps;
  g.ny = ex.block_y * ex.weave.wefts;
  // Deep enough for the centrelines' reach from the middle plane, plus the fibres' 1.4 r (jittered) past them.
  double reach = 0;
  for (const auto& c : {warp_curves, weft_curves})
    for (int curve : c)
      for (int p = yarn.curve_start[curve]; p < yarn.curve_start[curve + 1]; ++p) reach = std::max(reach, std::abs(yarn.points[p].z()));
  const double depth = reach + 1.4 * (1 + options.jitter) * r + voxel;
  g.nz = static_cast<int>(std::ceil(2 * depth / voxel));
  g.origin = {corner.x(), corner.y(), -0.5 * g.nz * voxel};
  g.allocate();

  const int samples_per_segment = static_cast<int>(std::ceil(4 * spacing / voxel));
  const auto sampled = workflow::sample_curves(yarn, samples_per_segment);
  std::vector<float> nearest(g.size(), std::numeric_limits<float>::infinity());
  std::vector<int> nearest_sample(g.size(), -1);
  std::mt19937_64 random(options.seed ^ 0x5EEDull);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<int> curves = warp_curves;
  curves.insert(curves.end(), weft_curves.begin(), weft_curves.end());
  std::vector<Centreline> lines;
  std::vector<Fibres> fibres;
  const double twist = options.twist > 0 ? options.twist : 8 * r;
  for (size_t id = 0; id < curves.size(); ++id) {
    lines.push_back(centreline(sampled[curves[id]]));
    const double radius = r * (1 + options.jitter * unit(random));
    const bool plied = options.plies > 1;
    fibres.push_back({options.plies, radius, plied ? 0.5 * radius : 0.0, plied ? 0.55 * radius : radius, twist,
                      2 * std::numbers::pi * (0.5 + 0.5 * unit(random)), options.flyaways, options.migration, options.seed});
  }
  // §6.3: every voxel belongs to the yarn whose centreline is nearest.
  for (size_t id = 0; id < lines.size(); ++id) {
    const auto& c = lines[id];
    const double reach = 1.4 * fibres[id].radius;
    for (size_t k = 0; k < c.p.size(); ++k) {
      const Eigen::Vector3d lo = (c.p[k] - g.origin).array() / voxel - reach / voxel, hi = (c.p[k] - g.origin).array() / voxel + reach / voxel;
      const int x0 = std::max(0, static_cast<int>(std::floor(lo.x()))), x1 = std::min(g.nx - 1, static_cast<int>(std::ceil(hi.x())));
      const int y0 = std::max(0, static_cast<int>(std::floor(lo.y()))), y1 = std::min(g.ny - 1, static_cast<int>(std::ceil(hi.y())));
      const int z0 = std::max(0, static_cast<int>(std::floor(lo.z()))), z1 = std::min(g.nz - 1, static_cast<int>(std::ceil(hi.z())));
      for (int z = z0; z <= z1; ++z)
        for (int y = y0; y <= y1; ++y)
          for (int x = x0; x <= x1; ++x) {
            const Eigen::Vector3d v = g.origin + voxel * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
            const float d = static_cast<float>((v - c.p[k]).norm());
            const size_t i = g.index(x, y, z);
            if (d < reach && d < nearest[i]) nearest[i] = d, g.yarn[i] = static_cast<std::int16_t>(id), nearest_sample[i] = static_cast<int>(k);
          }
    }
  }
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const size_t i = g.index(x, y, z);
        if (g.yarn[i] < 0) continue;
        const auto& c = lines[g.yarn[i]];
        const int k = nearest_sample[i];
        const Eigen::Vector3d d = g.origin + voxel * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5) - c.p[k];
        const double along = d.dot(c.t[k]);
        const auto [rho, direction] = fibres[g.yarn[i]].at(c.s[k] + along, d.dot(c.n[k]), d.dot(c.b[k]), c.t[k], c.n[k], c.b[k], i, g.yarn[i]);
        if (rho <= 0) {
          g.yarn[i] = -1;
          continue;
        }
        g.density[i] = rho;
        g.orientation[i] = direction;
      }
  return ex;
}

Exemplar make_exemplar(const mesh::Pattern& pattern, const ExemplarOptions& options, ExemplarReport* report) {
  if (pattern.format != mesh::PatternFormat::Woven) throw Error("", "pattern " + pattern.name, "is knitted: exemplars are woven");
  if (options.crossings < 2 || options.crossings > 64) throw Error("", "exemplar", "needs 2 to 64 crossings along a side");
  if (options.voxels_per_crossing < 4 || options.voxels_per_crossing > 256) throw Error("", "exemplar", "needs 4 to 256 voxels per crossing");
  if (!(options.radius > 0) || !(options.jitter >= 0 && options.jitter < 0.2) || options.plies < 1 || options.plies > 8 ||
      !(options.tension >= 0 && options.tension < 0.2) || !(options.migration >= 0 && options.migration <= 1))
    throw Error("", "exemplar", "needs a positive radius, a jitter and a tension below 0.2, 1 to 8 plies and a migration of 0 to 1");
  const double spacing = options.spacing > 0 ? options.spacing : 3 * options.radius;
  const int n = options.crossings + 2;
  mesh::Pattern field = pattern;
  field.over.assign(n, std::vector<char>(n, 0));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)  // the margin is crossing -1, so the exemplar starts at the repeat's first crossing
      field.over[i][j] = pattern.over[(i + pattern.height() - 1) % pattern.height()][(j + pattern.width() - 1) % pattern.width()];
  auto yarn = mesh::woven_yarn(field, 1, 1, spacing, options.radius);
  // woven_yarn lays the wefts first (rows bottom to top), then the warps (left to right); each yarn's two end
  // points lie in the margin, half a spacing past its last crossing.
  std::mt19937_64 random(options.seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (auto& p : yarn.points) p += options.jitter * spacing * Eigen::Vector3d(unit(random), unit(random), 0);
  auto system = relax::make_yarn_system(yarn, 1 - options.tension);
  relax::ShapeTargets targets;
  for (int c = 0; c < yarn.curves(); ++c) {
    targets.periodic.frozen.push_back(yarn.curve_start[c]);
    targets.periodic.frozen.push_back(yarn.curve_start[c + 1] - 1);
  }
  relax::YarnRelaxOptions relax_options;
  relax_options.method = relax::YarnMethod::Lbfgs;
  relax_options.stop_rule = relax::StopRule::Force;
  relax_options.max_steps = options.max_steps;
  relax_options.validate();
  auto state = relax::initial_state(system, relax_options);
  const auto start = std::chrono::steady_clock::now();
  const auto relaxed = relax::make_cpu_yarn_relaxer(system, targets, relax_options)->run(state);
  const double relax_seconds = seconds_since(start);
  if (relaxed.pull_through_events > 0) throw Error("", "exemplar of " + pattern.name, "the relaxation let yarn pass through yarn");
  // A patch held only at its yarns' ends sags, curls or wrinkles as a whole; a scan lies flat on its table.
  // Each point's height is taken relative to the local middle plane: the mean height of the centrelines within
  // 1.5 spacings of it (the crimp, up and down from one crossing to the next, averages out over that window).
  const Eigen::Matrix3Xd relaxed_points = state.points;
  double sag = 0;
  for (int p = 0; p < relaxed_points.cols(); ++p) {
    double sum = 0;
    int count = 0;
    for (int q = 0; q < relaxed_points.cols(); ++q)
      if ((relaxed_points.col(q).head<2>() - relaxed_points.col(p).head<2>()).norm() < 1.5 * spacing) sum += relaxed_points(2, q), ++count;
    state.points(2, p) -= sum / count;
    sag = std::max(sag, std::abs(sum / count));
  }
  const auto placed = relax::with_points(yarn, state.points);
  // A weave too close for its yarn buckles out of the fabric's plane (beyond the sag taken out).
  for (const auto& p : placed.points)
    if (std::abs(p.z()) > 3 * options.radius)
      throw Error("", "exemplar of " + pattern.name, "the relaxed yarn buckled out of the fabric's plane (a centreline " + std::to_string(p.z()) +
                                                          " mm from it): weave it with a larger spacing");
  std::vector<int> warps, wefts;
  for (int j = 1; j <= options.crossings; ++j) warps.push_back(n + j);
  for (int i = 1; i <= options.crossings; ++i) wefts.push_back(i);
  const auto voxel_start = std::chrono::steady_clock::now();
  // §6.5 weaving grid registration: the window moves with the relaxed yarn, so that on average the inner warps
  // and wefts run through the middles of their blocks (warp j was laid at x = j s, weft i at y = i s).
  Eigen::Vector2d drift = Eigen::Vector2d::Zero();
  Eigen::Vector2i counted = Eigen::Vector2i::Zero();
  for (int k = 1; k <= options.crossings; ++k) {
    for (int p = yarn.curve_start[k] + 2; p < yarn.curve_start[k + 1] - 2; ++p) drift.y() += state.points(1, p) - k * spacing, ++counted.y();
    for (int p = yarn.curve_start[n + k] + 2; p < yarn.curve_start[n + k + 1] - 2; ++p) drift.x() += state.points(0, p) - k * spacing, ++counted.x();
  }
  drift = drift.cwiseQuotient(counted.cast<double>());
  Exemplar ex = voxelize(placed, warps, wefts, Eigen::Vector2d::Constant(0.5 * spacing) + drift, options);
  ex.name = pattern.name;
  // §6.2: the relaxed yarn must still be the pattern's weave.
  for (int i = 0; i < options.crossings; ++i)
    for (int j = 0; j < options.crossings; ++j)
      if (ex.weave.at(i, j) != (field.over[i + 1][j + 1] == 0))
        throw Error("", "exemplar of " + pattern.name,
                    "after relaxation the crossing of weft " + std::to_string(i) + " and warp " + std::to_string(j) + " has the other yarn on top");
  if (report) {
    report->steps = relaxed.steps;
    report->converged = relaxed.converged;
    report->stopped_by = relax::to_string(relaxed.stopped_by);
    report->pull_through_events = relaxed.pull_through_events;
    report->relax_seconds = relax_seconds;
    report->sag = sag;
    report->voxel_seconds = seconds_since(voxel_start);
    report->filled = static_cast<double>(std::count_if(ex.grid.yarn.begin(), ex.grid.yarn.end(), [](auto y) { return y >= 0; })) / ex.grid.size();
  }
  return ex;
}

}  // namespace skein::woven
