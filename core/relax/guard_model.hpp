#pragma once
// The pull-through guard's geometry (Yuksel 2012 §6.3), written once for the CPU guard (double) and the
// CUDA guard (float): bounding spheres of segment pieces swept over a step, and their hierarchical test.
#include "relax/yarn_model.hpp"

namespace skein::relax::model {

/// A bounding sphere of a segment piece at the start and at the end of the step.
template <class T>
struct SweptSphere {
  Vec3<T> c0, c1;
  T r0, r1;
};

/// The sphere about the centroid of the piece's Bezier control points that holds them (and so the piece).
template <class T> SKEIN_HD void bezier_sphere(const Vec3<T> p[4], T s0, T s1, Vec3<T>& centre, T& radius) {
  Vec3<T> b[4];
  piece_bezier(p, s0, s1, b);
  centre = (b[0] + b[1] + b[2] + b[3]) * T(0.25);
  radius = 0;
  for (int k = 0; k < 4; ++k) {
    const T d = norm(b[k] - centre);
    radius = d > radius ? d : radius;
  }
}

/// The piece [s0, s1] of a segment with control points p0 before the step and p1 after it.
template <class T> SKEIN_HD SweptSphere<T> swept_sphere(const Vec3<T> p0[4], const Vec3<T> p1[4], T s0, T s1) {
  SweptSphere<T> out;
  bezier_sphere(p0, s0, s1, out.c0, out.r0);
  bezier_sphere(p1, s0, s1, out.c1, out.r1);
  return out;
}

/// Do the two spheres, centres and radii moving linearly over t in [0, 1], meet? (Yuksel §6.3: a quadratic
/// in t.) Every point of a piece moves linearly, so the linear blend of the end radii bounds the piece at t.
/// `end_gap`: their distance at the end of the step.
template <class T> SKEIN_HD bool spheres_meet(const SweptSphere<T>& a, const SweptSphere<T>& b, T& end_gap) {
  const Vec3<T> d0 = b.c0 - a.c0, e = (b.c1 - a.c1) - d0;
  const T s0 = a.r0 + b.r0, f = (a.r1 + b.r1) - s0;
  end_gap = norm(b.c1 - a.c1) - (a.r1 + b.r1);
  // g(t) = |d0 + t e|^2 - (s0 + t f)^2 <= 0 somewhere in [0, 1]?
  const T qa = dot(e, e) - f * f, qb = 2 * (dot(d0, e) - s0 * f), qc = dot(d0, d0) - s0 * s0;
  const auto g = [&](T t) { return (qa * t + qb) * t + qc; };
  if (g(0) <= 0 || g(1) <= 0) return true;
  if (qa > 0) {
    const T t = -qb / (2 * qa);
    if (t > 0 && t < 1 && g(t) <= 0) return true;
  }
  return false;
}

/// Deepest refinement the guard allows (GuardOptions::max_depth).
constexpr int kMaxGuardDepth = 20;

/// The hierarchical sphere test of one pair of segments over a step (a before/after the step: a0/a1, b the
/// same): pieces whose swept spheres meet are split in two on both sides, down to `max_depth` levels.
/// Returns true when the finest level still meets. `gap`: the smallest end gap of the clean pieces (for the
/// safe bound); `tests` counts sphere tests.
template <class T>
SKEIN_HD bool pieces_meet(const Vec3<T> a0[4], const Vec3<T> a1[4], const Vec3<T> b0[4], const Vec3<T> b1[4], int max_depth, T& gap, long& tests) {
  struct Item {
    T a_lo, a_hi, b_lo, b_hi;
    int depth;
  };
  Item stack[3 * kMaxGuardDepth + 4];  // depth-first: at most three siblings wait per level
  int top = 0;
  stack[top++] = {0, 1, 0, 1, 0};
  gap = T(INFINITY);
  while (top > 0) {
    const Item it = stack[--top];
    T end_gap;
    ++tests;
    if (!spheres_meet(swept_sphere(a0, a1, it.a_lo, it.a_hi), swept_sphere(b0, b1, it.b_lo, it.b_hi), end_gap)) {
      gap = end_gap < gap ? end_gap : gap;
      continue;
    }
    if (it.depth >= max_depth) return true;
    const T am = T(0.5) * (it.a_lo + it.a_hi), bm = T(0.5) * (it.b_lo + it.b_hi);
    stack[top++] = {it.a_lo, am, it.b_lo, bm, it.depth + 1};
    stack[top++] = {it.a_lo, am, bm, it.b_hi, it.depth + 1};
    stack[top++] = {am, it.a_hi, it.b_lo, bm, it.depth + 1};
    stack[top++] = {am, it.a_hi, bm, it.b_hi, it.depth + 1};
  }
  return false;
}

/// What the guard does after a round of tests that left `hits` pairs still meeting at the finest level, the same
/// on both back-ends (the round loop itself is each back-end's: a loop on the CPU, a captured graph of kernels on
/// the GPU). First the hit pairs' points halve their moves, `max_halvings` rounds; then those points are held for
/// the step, kGuardHoldRounds rounds (a held point can leave a neighbour's pair still hit); then, if pairs still
/// meet, every point is held for the step, which no pair can pass through.
enum class GuardRound : int { Done = 0, Halve = 1, Hold = 2, HoldAll = 3 };
constexpr int kGuardHoldRounds = 3;
SKEIN_HD GuardRound guard_round(int round, long hits, int max_halvings) {
  if (hits == 0) return GuardRound::Done;
  if (round < max_halvings) return GuardRound::Halve;
  if (round < max_halvings + kGuardHoldRounds) return GuardRound::Hold;
  return GuardRound::HoldAll;
}

}  // namespace skein::relax::model
