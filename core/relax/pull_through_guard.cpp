#include "relax/pull_through_guard.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "relax/yarn_model.hpp"

namespace skein::relax {
namespace {

using V = model::Vec3<double>;
V vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// A bounding sphere of a segment piece at the start and at the end of the step.
struct SweptSphere {
  V c0, c1;
  double r0 = 0, r1 = 0;
};

SweptSphere sphere_of(const V p0[4], const V p1[4], double s0, double s1) {
  SweptSphere out;
  V b[4];
  const auto fit = [&](const V p[4], V& c, double& r) {
    model::piece_bezier(p, s0, s1, b);
    c = (b[0] + b[1] + b[2] + b[3]) * 0.25;
    r = 0;
    for (const auto& q : b) r = std::max(r, model::norm(q - c));
  };
  fit(p0, out.c0, out.r0);
  fit(p1, out.c1, out.r1);
  return out;
}

/// Do the two spheres, centres and radii moving linearly over t in [0, 1], meet? (Yuksel §6.3: a quadratic
/// in t.) Every point of a piece moves linearly, so the linear blend of the end radii bounds the piece at t.
bool spheres_meet(const SweptSphere& a, const SweptSphere& b, double& end_gap) {
  const V d0 = b.c0 - a.c0, e = (b.c1 - a.c1) - d0;
  const double s0 = a.r0 + b.r0, f = (a.r1 + b.r1) - s0;
  end_gap = model::norm(b.c1 - a.c1) - (a.r1 + b.r1);
  // g(t) = |d0 + t e|^2 - (s0 + t f)^2 <= 0 somewhere in [0, 1]?
  const double qa = model::dot(e, e) - f * f, qb = 2 * (model::dot(d0, e) - s0 * f), qc = model::dot(d0, d0) - s0 * s0;
  const auto g = [&](double t) { return (qa * t + qb) * t + qc; };
  if (g(0) <= 0 || g(1) <= 0) return true;
  if (qa > 0) {
    const double t = -qb / (2 * qa);
    if (t > 0 && t < 1 && g(t) <= 0) return true;
  }
  return false;
}

}  // namespace

void GuardOptions::validate() const {
  if (!(max_move > 0 && max_move <= 10)) throw Error("", "guard", "the movement limit ε must be in (0, 10], found " + std::to_string(max_move));
  if (max_depth < 0 || max_depth > 20) throw Error("", "guard", "the refinement depth must be in 0..20, found " + std::to_string(max_depth));
  if (max_halvings < 0 || max_halvings > 30) throw Error("", "guard", "the step halvings must be in 0..30, found " + std::to_string(max_halvings));
}

PullThroughGuard::PullThroughGuard(const YarnSystem& system, const GuardOptions& options, std::vector<int> groups)
    : m_system(system), m_options(options), m_groups(std::move(groups)), m_travel(system.num_points(), 0.0) {
  m_options.validate();
  if (m_groups.empty()) m_groups.assign(system.num_points(), -1);
}

void PullThroughGuard::reset(const ContactPairs& pairs) {
  m_pairs.clear();
  for (int a = 0; a + 1 < static_cast<int>(pairs.start.size()); ++a)
    for (int k = pairs.start[a]; k < pairs.start[a + 1]; ++k)
      if (pairs.partner[k] > a && !m_system.adjacent(a, pairs.partner[k])) m_pairs.push_back({a, pairs.partner[k]});
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
  struct Item {
    double a_lo, a_hi, b_lo, b_hi;
    int depth;
  };
  Item stack[4 * 21 + 4];
  int top = 0;
  stack[top++] = {0, 1, 0, 1, 0};
  gap = INFINITY;
  while (top > 0) {
    const Item it = stack[--top];
    double end_gap;
    ++tests;
    if (!spheres_meet(sphere_of(a0, a1, it.a_lo, it.a_hi), sphere_of(b0, b1, it.b_lo, it.b_hi), end_gap)) {
      gap = std::min(gap, end_gap);
      continue;
    }
    if (it.depth == m_options.max_depth) return true;
    const double am = 0.5 * (it.a_lo + it.a_hi), bm = 0.5 * (it.b_lo + it.b_hi);
    stack[top++] = {it.a_lo, am, it.b_lo, bm, it.depth + 1};
    stack[top++] = {it.a_lo, am, bm, it.b_hi, it.depth + 1};
    stack[top++] = {am, it.a_hi, it.b_lo, bm, it.depth + 1};
    stack[top++] = {am, it.a_hi, bm, it.b_hi, it.depth + 1};
  }
  return false;
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
  const int n = static_cast<int>(m_pairs.size());
  std::vector<double> new_budget(n, -1.0);
  std::vector<char> hit(n, 0), retest(n, 1);
  for (int round = 0; m_options.enabled; ++round) {
    const Eigen::VectorXd move = delta.colwise().norm().transpose();
    long tested = 0, skipped = 0, tests = 0, hits = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : tested, skipped, tests, hits)
    for (int i = 0; i < n; ++i) {
      if (!retest[i]) continue;
      const PairState& pair = m_pairs[i];
      hit[i] = 0;
      new_budget[i] = -1.0;
      bool still = true;
      for (int side = 0; side < 2 && still; ++side)
        for (int k = 0; k < 4; ++k)
          if (move[m_system.segment_points[side == 0 ? pair.a : pair.b][k]] > 0) still = false;
      if (still) continue;  // neither segment moves: they cannot pass through each other
      if (m_options.safe_bounds && skip(pair, move)) {
        ++skipped;
        continue;
      }
      ++tested;
      double gap;
      if (pieces_meet(pair, points, delta, gap, tests)) {
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
    if (hits == 0) break;
    m_counters.finest_hits += hits;
    if (round < m_options.max_halvings) {
      // Every point moves on a straight line, so the halved step is the first half of the same path: pairs
      // that were clean stay clean and only the hit ones are tested again. Their safe bounds were measured at
      // the end of the longer step, so they are dropped.
      ++m_counters.halvings;
      scale *= 0.5;
      delta *= 0.5;
      for (int i = 0; i < n; ++i) {
        retest[i] = hit[i];
        if (!hit[i]) new_budget[i] = -1.0;
      }
      continue;
    }
    // Out of halvings: hold the points of the pairs still hit (and their groups) for this step.
    std::vector<char> hold(m_system.num_points(), 0);
    std::vector<char> hold_group;
    for (int i = 0; i < n; ++i)
      if (hit[i])
        for (int side = 0; side < 2; ++side)
          for (int k = 0; k < 4; ++k) {
            const int p = m_system.segment_points[side == 0 ? m_pairs[i].a : m_pairs[i].b][k];
            hold[p] = 1;
            if (m_groups[p] >= 0) {
              if (hold_group.size() <= static_cast<size_t>(m_groups[p])) hold_group.resize(m_groups[p] + 1, 0);
              hold_group[m_groups[p]] = 1;
            }
          }
    for (int p = 0; p < m_system.num_points(); ++p) {
      hold[p] = hold[p] || (m_groups[p] >= 0 && static_cast<size_t>(m_groups[p]) < hold_group.size() && hold_group[m_groups[p]]);
      if (hold[p]) {
        if (delta.col(p).squaredNorm() > 0) ++m_counters.held_points;
        delta.col(p).setZero();
      }
    }
    // Pairs with a held point now move differently: test them again.
    for (int i = 0; i < n; ++i) {
      retest[i] = 0;
      for (int side = 0; side < 2; ++side)
        for (int k = 0; k < 4; ++k) retest[i] |= hold[m_system.segment_points[side == 0 ? m_pairs[i].a : m_pairs[i].b][k]];
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
  return delta.cwiseAbs().maxCoeff() > 0 ? scale : 0.0;
}

}  // namespace skein::relax
