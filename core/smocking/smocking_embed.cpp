#include "smocking/smocking_embed.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "common/error.hpp"

namespace skein::smocking {
namespace {

/// D(X | L) (Zhou eq. 2).
double thread_length(const Eigen::Matrix2Xd& x, const std::vector<Stitch>& stitches) {
  double d = 0;
  for (const auto& s : stitches) d += (x.col(s.a) - x.col(s.b)).norm();
  return d;
}

/// Pulls a and b towards `target` apart with stiffness k (Algorithm 1, lines 11-13).
void spring_force(const Eigen::Matrix2Xd& x, int a, int b, double target, double k, Eigen::Matrix2Xd& acceleration) {
  const Eigen::Vector2d e = x.col(a) - x.col(b);
  const double length = e.norm();
  if (length <= 0) return;  // coincident ends: no direction to push them apart along
  const Eigen::Vector2d delta = (length - target) / length * e;
  acceleration.col(a) -= k * delta;
  acceleration.col(b) += k * delta;
}

/// Eq. 4's springs: no force between τ and the flat length, pushed back outside it.
void fabric_forces(const Embedding& e, const Eigen::Matrix2Xd& x, double k, Eigen::Matrix2Xd& acceleration) {
  for (const auto& f : e.fabric) {
    const double length = (x.col(f.a) - x.col(f.b)).norm();
    const double target = std::max(e.thickness, std::min(length, f.rest));
    if (target != length) spring_force(x, f.a, f.b, target, k, acceleration);
  }
}

/// The largest violation of eq. 1b: stretch over the rest length, or squeeze below τ over τ.
double fabric_violation(const Embedding& e, const Eigen::Matrix2Xd& x) {
  double worst = 0;
  for (const auto& f : e.fabric) {
    const double length = (x.col(f.a) - x.col(f.b)).norm();
    worst = std::max({worst, length / f.rest - 1, 1 - length / e.thickness});
  }
  return worst;
}

/// One Gauss-Seidel sweep of eq. 1b: each fabric spring put back inside [τ, flat length], its ends moving in
/// proportion to their `give`.
void project_fabric(const Embedding& e, const std::vector<double>& give, Eigen::Matrix2Xd& x) {
  for (const auto& f : e.fabric) {
    const Eigen::Vector2d d = x.col(f.a) - x.col(f.b);
    const double length = d.norm(), target = std::clamp(length, e.thickness, f.rest);
    if (target == length || length <= 0) continue;
    const Eigen::Vector2d move = (length - target) / length / (give[f.a] + give[f.b]) * d;
    x.col(f.a) -= give[f.a] * move;
    x.col(f.b) += give[f.b] * move;
  }
}

}  // namespace

const char* stop_name(EmbedStop stop) {
  switch (stop) {
    case EmbedStop::Reached: return "reached";
    case EmbedStop::Stalled: return "stalled";
    case EmbedStop::IterationCap: return "iteration_cap";
  }
  return "?";
}

void EmbedOptions::validate() const {
  const auto need = [](bool ok, const std::string& rule) {
    if (!ok) throw Error("", "smocking options", rule);
  };
  need(gamma > 0 && gamma <= 1, "gamma in (0, 1], found " + std::to_string(gamma));
  need(thickness < 0 || (thickness > 0 && std::isfinite(thickness)), "a thickness above 0 mm (or none for 1 % of the grid's longer side)");
  need(pull_along_stitches || (pull.allFinite() && pull.norm() > 1e-12), "a pulling direction of non-zero length");
  need(time_step > 0 && time_step <= 1, "a time step in (0, 1]");
  need(damping > 0 && damping < 1, "damping in (0, 1)");
  need(k_fabric > 0 && k_stitch > 0, "spring stiffnesses above 0");
  need(settle_tolerance > 0 && settle_iterations >= 0 && sweeps_per_step >= 0, "a settling tolerance above 0 and at least 0 settling sweeps");
  need(max_iterations >= 0 && stall_window >= 1 && history_every >= 1, "an iteration cap of at least 0, a stall window and history step of at least 1");
  for (double s : snapshots) need(s > 0 && s <= 1, "snapshot fractions in (0, 1]");
}

Embedding make_mass_spring_system(const SmockingPattern& pattern, double thickness) {
  Embedding e;
  const int n = pattern.num_points();
  e.rest.resize(2, n);
  for (int r = 0; r < pattern.rows; ++r)
    for (int c = 0; c < pattern.columns; ++c) e.rest.col(pattern.index({c, r})) = pattern.rest_position({c, r});
  e.positions = e.rest;
  const auto rest_length = [&](int a, int b) { return (e.rest.col(a) - e.rest.col(b)).norm(); };
  for (int r = 0; r < pattern.rows; ++r)
    for (int c = 0; c < pattern.columns; ++c) {
      const int i = pattern.index({c, r});
      if (c + 1 < pattern.columns) e.fabric.push_back({i, i + 1, rest_length(i, i + 1)});
      if (r + 1 < pattern.rows) e.fabric.push_back({i, i + pattern.columns, rest_length(i, i + pattern.columns)});
    }
  for (size_t t = 0; t < pattern.threads.size(); ++t) {
    const auto& thread = pattern.threads[t];
    for (size_t k = 0; k + 1 < thread.points.size(); ++k) {
      Stitch s;
      s.a = pattern.index(thread.points[k]);
      s.b = pattern.index(thread.points[k + 1]);
      s.rest = rest_length(s.a, s.b);
      s.thread = static_cast<int>(t);
      s.front = pattern.style == Style::Canadian || thread.front(static_cast<int>(k));
      for (const auto& b : pattern.beads)
        if ((thread.points[k] == b.a && thread.points[k + 1] == b.b) || (thread.points[k] == b.b && thread.points[k + 1] == b.a)) s.bead = std::max(s.bead, b.diameter);
      e.stitches.push_back(s);
    }
  }
  e.thickness = thickness > 0 ? thickness : 0.01 * pattern.spacing * std::max(pattern.columns - 1, pattern.rows - 1);
  e.threads_rest = e.threads = thread_length(e.rest, e.stitches);
  return e;
}

Embedding embed(const SmockingPattern& pattern, const EmbedOptions& options) {
  options.validate();
  Embedding e = make_mass_spring_system(pattern, options.thickness);
  const double tau = e.thickness;
  const Eigen::Vector2d pull = options.pull.normalized(), across(-pull.y(), pull.x());  // d, orthogonal to the pull (eq. 5)
  const bool canadian = pattern.style == Style::Canadian;
  const int n = static_cast<int>(e.rest.cols());
  Eigen::Matrix2Xd& x = e.positions;
  Eigen::Matrix2Xd v = Eigen::Matrix2Xd::Zero(2, n), a(2, n);
  std::vector<double> snapshots = options.snapshots;
  std::sort(snapshots.begin(), snapshots.end(), std::greater<>());
  size_t next_snapshot = 0;
  const auto take_snapshots = [&](double fraction) {
    for (; next_snapshot < snapshots.size() && fraction <= snapshots[next_snapshot]; ++next_snapshot) e.snapshots.emplace_back(snapshots[next_snapshot], x);
  };

  // How far each point gives when eq. 1b is projected: stitching points a tenth as far as pleat points.
  std::vector<double> give(n, 1.0);
  for (const auto& s : e.stitches) give[s.a] = give[s.b] = 0.1;
  const double goal = options.gamma * e.threads_rest;
  double window_start = e.threads;
  e.history.emplace_back(0, 1.0);
  take_snapshots(1.0);
  // Algorithm 1 from where the fabric is until D(X) <= γ D(X̄) (eq. 1c, line 3), a stall or the cap.
  const auto steps = [&] {
    e.stopped = EmbedStop::IterationCap;
    for (;; ++e.iterations) {
      if (e.threads <= goal) {
        e.stopped = EmbedStop::Reached;
        return;
      }
      if (e.iterations >= options.max_iterations) return;
      if (e.iterations > 0 && e.iterations % options.stall_window == 0) {
        if (window_start - e.threads < options.stall_tolerance * e.threads_rest) {
          e.stopped = EmbedStop::Stalled;
          return;
        }
        window_start = e.threads;
      }
      a.setZero();
      // Lines 4-6: stitching springs' targets by eq. 5, the stitch's extent across the pull (Canadian: 0, §5.4),
      // never below a bead on it (§5.2).
      for (const auto& s : e.stitches) {
        const double target = std::max(s.bead, canadian                      ? 0.0
                                               : options.pull_along_stitches ? tau
                                                                             : std::max(tau, std::abs(across.dot(x.col(s.a) - x.col(s.b)))));
        spring_force(x, s.a, s.b, target, options.k_stitch, a);
      }
      // Lines 7-9: fabric springs' targets by eq. 4.
      fabric_forces(e, x, options.k_fabric, a);
      // Lines 15-17: damped explicit step, unit masses.
      v = options.damping * (v + options.time_step * a);
      x += options.time_step * v;
      // Keeps eq. 1b as Appendix A says the scheme does.
      for (int sweep = 0; options.settle && sweep < options.sweeps_per_step && fabric_violation(e, x) > options.settle_tolerance; ++sweep)
        project_fabric(e, give, x);
      e.threads = thread_length(x, e.stitches);
      if ((e.iterations + 1) % options.history_every == 0) e.history.emplace_back(e.iterations + 1, e.threads / e.threads_rest);
      take_snapshots(e.threads / e.threads_rest);
    }
  };
  steps();
  e.stretch_before_settling = fabric_violation(e, x);
  e.shrinkage_before_settling = e.shrinkage();
  // The settling pass: the projection repeated until eq. 1b holds; where that gives the threads back more than
  // the tolerance past γ, Algorithm 1 goes on (at most 10 rounds), so that eq. 1c holds too.
  for (int round = 0; options.settle; ++round) {
    v.setZero();
    for (int sweep = 0; sweep < options.settle_iterations && fabric_violation(e, x) > options.settle_tolerance; ++sweep, ++e.settle_iterations)
      project_fabric(e, give, x);
    e.threads = thread_length(x, e.stitches);
    if (e.stopped != EmbedStop::Reached || e.threads <= goal * (1 + options.settle_tolerance) || round == 9) break;
    steps();
  }
  if (e.history.back().x() != e.iterations) e.history.emplace_back(e.iterations, e.shrinkage());
  // How well eq. 1b holds where the run ended.
  e.largest_stretch = 0;
  e.shortest_fabric = std::numeric_limits<double>::infinity();
  for (const auto& f : e.fabric) {
    const double length = (x.col(f.a) - x.col(f.b)).norm();
    e.largest_stretch = std::max(e.largest_stretch, length / f.rest - 1);
    e.shortest_fabric = std::min(e.shortest_fabric, length / tau);
  }
  return e;
}

Lift lift(const Embedding& e) {
  Lift l;
  std::set<int> points;
  for (const auto& s : e.stitches) points.insert(s.a), points.insert(s.b);
  l.points.assign(points.begin(), points.end());
  l.point_positions.resize(3, static_cast<int>(l.points.size()));
  for (size_t k = 0; k < l.points.size(); ++k) l.point_positions.col(k) << e.positions.col(l.points[k]), 0.0;  // eq. 6
  l.midpoints.resize(3, static_cast<int>(e.stitches.size()));
  for (size_t k = 0; k < e.stitches.size(); ++k) {
    const auto& s = e.stitches[k];
    const double half_now = 0.5 * (e.positions.col(s.a) - e.positions.col(s.b)).norm(), half_flat = 0.5 * s.rest;
    const double h = std::sqrt(std::max(0.0, half_flat * half_flat - half_now * half_now));  // eq. 8
    l.midpoints.col(k) << 0.5 * (e.positions.col(s.a) + e.positions.col(s.b)), s.front ? -h : h;  // eq. 7
  }
  return l;
}

}  // namespace skein::smocking
