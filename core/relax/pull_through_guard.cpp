#include "relax/pull_through_guard.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "relax/guard_model.hpp"

namespace skein::relax {
namespace {

using V = model::Vec3<double>;
V vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

void GuardOptions::validate() const {
  if (!(max_move > 0 && max_move <= 10)) throw Error("", "guard", "the movement limit ε must be in (0, 10], found " + std::to_string(max_move));
  if (max_depth < 0 || max_depth > model::kMaxGuardDepth) throw Error("", "guard", "the refinement depth must be in 0.." + std::to_string(model::kMaxGuardDepth) + ", found " + std::to_string(max_depth));
  if (max_halvings < 0 || max_halvings > 30) throw Error("", "guard", "the step halvings must be in 0..30, found " + std::to_string(max_halvings));
}

PullThroughGuard::PullThroughGuard(const YarnSystem& system, const GuardOptions& options, std::vector<int> groups)
    : m_system(system), m_options(options), m_groups(std::move(groups)), m_travel(system.num_points(), 0.0) {
  m_options.validate();
  if (m_groups.empty()) m_groups.assign(system.num_points(), -1);
}

void PullThroughGuard::restrict_to(std::vector<char> segments) {
  if (!segments.empty() && segments.size() != static_cast<size_t>(m_system.num_segments()))
    throw Error("", "guard", "the segment mask has " + std::to_string(segments.size()) + " entries for " +
                std::to_string(m_system.num_segments()) + " segments");
  m_tested = std::move(segments);
}

void PullThroughGuard::reset(const ContactPairs& pairs) {
  m_pairs.clear();
  for (int a = 0; a + 1 < static_cast<int>(pairs.start.size()); ++a)
    for (int k = pairs.start[a]; k < pairs.start[a + 1]; ++k) {
      const int b = pairs.partner[k];
      if (b <= a || m_system.adjacent(a, b)) continue;
      if (!m_tested.empty() && !m_tested[a] && !m_tested[b]) continue;
      m_pairs.push_back({a, b});
    }
}

bool PullThroughGuard::pieces_meet(const PairState& pair, const Eigen::Matrix3Xd& points, const Eigen::Matrix3Xd& delta, double& gap,
                                   long& tests) const {
  V a0[4], a1[4], b0[4], b1[4];
  for (int k = 0; k < 4; ++k) {
    const int pa = m_system.segment_points[pair.a][k], pb = m_system.segment_points[pair.b][k];
    a0[k] = vec(points.col(pa));
    a1[k] = a0[k] + vec(delta.col(pa));
    b0[k] = vec(points.col(pb));
    b1[k] = b0[k] + vec(delta.col(pb));
  }
  return model::pieces_meet(a0, a1, b0, b1, m_options.max_depth, gap, tests);
}

void PullThroughGuard::sweep_segments(const Eigen::Matrix3Xd& points, const Eigen::Matrix3Xd& delta, const std::vector<char>& changed) {
  m_swept.resize(m_system.num_segments());
#pragma omp parallel for schedule(static)
  for (int s = 0; s < m_system.num_segments(); ++s) {
    if (!changed.empty() && !changed[s]) continue;
    V p0[4], p1[4];
    for (int k = 0; k < 4; ++k) {
      const int p = m_system.segment_points[s][k];
      p0[k] = vec(points.col(p));
      p1[k] = p0[k] + vec(delta.col(p));
    }
    m_swept[s] = model::swept_sphere(p0, p1, 0.0, 1.0);
  }
}

bool PullThroughGuard::skip(const PairState& pair, const Eigen::VectorXd& move) const {
  if (pair.budget < 0) return false;
  for (int side = 0; side < 2; ++side)
    for (int k = 0; k < 4; ++k) {
      const int p = m_system.segment_points[side == 0 ? pair.a : pair.b][k];
      if (m_travel[p] + move[p] - pair.travel[side * 4 + k] >= pair.budget) return false;
    }
  return true;
}

double PullThroughGuard::accept(const Eigen::Matrix3Xd& points, Eigen::Matrix3Xd& delta) {
  ++m_counters.steps;
  double scale = 1;
  const double limit = m_options.max_move * m_system.radius;
  const double largest = largest_sample_move(m_system, delta);
  if (largest > limit) {
    ++m_counters.rate_limited;
    scale = limit / largest;
    delta *= scale;
  }
  const int n = static_cast<int>(m_pairs.size()), segments = m_system.num_segments();
  std::vector<double> new_budget(n, -1.0);
  std::vector<char> hit(n, 0), retest(n, 1);
  std::vector<char> changed;  // per segment: a point's move changed in the last round (empty: the first round, all)
  std::vector<char> moves(segments);
  double least = 1;  // the smallest factor the halvings left on a point's move
  for (int round = 0; m_options.enabled; ++round) {
    const Eigen::VectorXd move = delta.colwise().norm().transpose();
#pragma omp parallel for schedule(static)
    for (int s = 0; s < segments; ++s) {
      moves[s] = 0;
      for (int k = 0; k < 4; ++k) moves[s] |= move[m_system.segment_points[s][k]] > 0;
    }
    sweep_segments(points, delta, changed);
    long tested = 0, skipped = 0, tests = 0, hits = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : tested, skipped, tests, hits)
    for (int i = 0; i < n; ++i) {
      if (!retest[i]) continue;
      const PairState& pair = m_pairs[i];
      hit[i] = 0;
      new_budget[i] = -1.0;
      if (!moves[pair.a] && !moves[pair.b]) continue;  // neither segment moves: they cannot pass through each other
      if (m_options.safe_bounds && skip(pair, move)) {
        ++skipped;
        continue;
      }
      ++tested;
      // The first level from the segments' own swept spheres; only pairs that meet there are refined (the
      // hierarchical test starts again at that level, counting it once).
      double gap;
      const bool clean = !model::spheres_meet(m_swept[pair.a], m_swept[pair.b], gap);
      if (clean) ++tests;
      if (!clean && pieces_meet(pair, points, delta, gap, tests)) {
        hit[i] = 1;
        ++hits;
      } else if (gap > 0 && std::isfinite(gap)) {
        // Yuksel eq. 9 with the simple partition d_i = d/8 and |b_i| <= 1: each of the 8 points may move
        // d/8 more without the clean pieces meeting.
        new_budget[i] = gap / 8;
      }
    }
    m_counters.pairs_tested += tested;
    m_counters.pairs_skipped += skipped;
    m_counters.sphere_tests += tests;
    const model::GuardRound action = model::guard_round(round, hits, m_options.max_halvings);
    if (action == model::GuardRound::Done) break;
    m_counters.finest_hits += hits;
    if (action == model::GuardRound::HoldAll) {
      for (int p = 0; p < m_system.num_points(); ++p)
        if (delta.col(p).squaredNorm() > 0) ++m_counters.held_points;
      delta.setZero();
      std::fill(new_budget.begin(), new_budget.end(), -1.0);
      break;
    }
    // The points of the pairs still hit, with their groups (a boundary loop's points move as one).
    std::vector<char> mark(m_system.num_points(), 0), mark_group;
    for (int i = 0; i < n; ++i)
      if (hit[i])
        for (int side = 0; side < 2; ++side)
          for (int k = 0; k < 4; ++k) {
            const int p = m_system.segment_points[side == 0 ? m_pairs[i].a : m_pairs[i].b][k];
            mark[p] = 1;
            if (m_groups[p] >= 0) {
              if (mark_group.size() <= static_cast<size_t>(m_groups[p])) mark_group.resize(m_groups[p] + 1, 0);
              mark_group[m_groups[p]] = 1;
            }
          }
    const bool halve = action == model::GuardRound::Halve;
    if (halve) {
      ++m_counters.halvings;
      least = std::min(least, std::ldexp(1.0, -(round + 1)));
    }
    for (int p = 0; p < m_system.num_points(); ++p) {
      mark[p] = mark[p] || (m_groups[p] >= 0 && static_cast<size_t>(m_groups[p]) < mark_group.size() && mark_group[m_groups[p]]);
      if (!mark[p]) continue;
      if (halve) {
        // Each point moves on a straight line, so a halved move is the first half of the same path.
        delta.col(p) *= 0.5;
      } else {
        // Out of halvings (GuardRound::Hold): the point stays put for this step.
        if (delta.col(p).squaredNorm() > 0) ++m_counters.held_points;
        delta.col(p).setZero();
      }
    }
    // Only the marked points' moves changed: pairs of unmarked points keep their paths and stay clean, and the
    // rest of the yarn keeps its whole step. Pairs with a marked point are tested again; their safe bounds, if
    // any, were measured on the longer moves.
    changed.assign(segments, 0);
#pragma omp parallel for schedule(static)
    for (int s = 0; s < segments; ++s)
      for (int k = 0; k < 4; ++k) changed[s] |= mark[m_system.segment_points[s][k]];
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
      retest[i] = changed[m_pairs[i].a] || changed[m_pairs[i].b];
      if (retest[i]) new_budget[i] = -1.0;
    }
  }
  // Commit: travel grows by what each point moves; clean pairs restart their safe bounds from here.
  for (int p = 0; p < m_system.num_points(); ++p) m_travel[p] += delta.col(p).norm();
  if (m_options.enabled && m_options.safe_bounds)
    for (int i = 0; i < n; ++i) {
      if (new_budget[i] < 0) continue;
      PairState& pair = m_pairs[i];
      pair.budget = new_budget[i];
      for (int side = 0; side < 2; ++side)
        for (int k = 0; k < 4; ++k) pair.travel[side * 4 + k] = m_travel[m_system.segment_points[side == 0 ? pair.a : pair.b][k]];
    }
  return delta.cwiseAbs().maxCoeff() > 0 ? scale * least : 0.0;
}

}  // namespace skein::relax
