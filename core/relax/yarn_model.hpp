#pragma once
// The yarn model's per-term math, written once for the CPU relaxer (double) and the CUDA relaxer (float):
// plain functions on fixed-size values, no allocation, no exceptions (STYLE.md, "one source of truth").
// Yarns are uniform Catmull-Rom splines; segment i runs between control points p1 and p2 with neighbours
// p0 and p3, parameter s in [0, 1].
#include <cmath>

#if defined(__CUDACC__)
#define SKEIN_HD __host__ __device__ inline
#else
#define SKEIN_HD inline
#endif

namespace skein::relax::model {

template <class T>
struct Vec3 {
  T x, y, z;
  SKEIN_HD Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  SKEIN_HD Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  SKEIN_HD Vec3 operator*(T s) const { return {x * s, y * s, z * s}; }
  SKEIN_HD Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  SKEIN_HD Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
};
template <class T> SKEIN_HD T dot(const Vec3<T>& a, const Vec3<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T> SKEIN_HD Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T> SKEIN_HD T norm(const Vec3<T>& a) { return std::sqrt(dot(a, a)); }

/// Catmull-Rom basis weights at s (Yuksel 2012 §6.3): y(s) = sum_k w[k] p_k; they sum to 1 and
/// sum |w| <= 1.25 (at s = 1/2), so a sample moves at most 1.25 times its control points' largest move.
template <class T> SKEIN_HD void basis(T s, T w[4]) {
  const T s2 = s * s, s3 = s2 * s;
  w[0] = T(0.5) * (-s3 + 2 * s2 - s);
  w[1] = T(0.5) * (3 * s3 - 5 * s2 + 2);
  w[2] = T(0.5) * (-3 * s3 + 4 * s2 + s);
  w[3] = T(0.5) * (s3 - s2);
}
/// d/ds of the basis.
template <class T> SKEIN_HD void basis_d1(T s, T w[4]) {
  const T s2 = s * s;
  w[0] = T(0.5) * (-3 * s2 + 4 * s - 1);
  w[1] = T(0.5) * (9 * s2 - 10 * s);
  w[2] = T(0.5) * (-9 * s2 + 8 * s + 1);
  w[3] = T(0.5) * (3 * s2 - 2 * s);
}
/// d²/ds² of the basis.
template <class T> SKEIN_HD void basis_d2(T s, T w[4]) {
  w[0] = T(0.5) * (-6 * s + 4);
  w[1] = T(0.5) * (18 * s - 10);
  w[2] = T(0.5) * (-18 * s + 8);
  w[3] = T(0.5) * (6 * s - 2);
}
template <class T> SKEIN_HD Vec3<T> combine(const T w[4], const Vec3<T> p[4]) {
  return p[0] * w[0] + p[1] * w[1] + p[2] * w[2] + p[3] * w[3];
}

/// The Bezier control points of the piece [s0, s1] of a segment: the piece lies in their convex hull, so
/// the smallest sphere about their centroid that holds them bounds it (Yuksel 2012 §6.3 bounding spheres).
template <class T> SKEIN_HD void piece_bezier(const Vec3<T> p[4], T s0, T s1, Vec3<T> out[4]) {
  T w[4], d[4];
  const T h = s1 - s0;
  basis(s0, w);
  basis_d1(s0, d);
  out[0] = combine(w, p);
  out[1] = out[0] + combine(d, p) * (h / 3);
  basis(s1, w);
  basis_d1(s1, d);
  out[3] = combine(w, p);
  out[2] = out[3] - combine(d, p) * (h / 3);
}

/// Composite Simpson weight of sample k of n (n odd) on [0, 1]; the weights sum to 1.
template <class T> SKEIN_HD T simpson_weight(int k, int n) {
  const T h = T(1) / T(n - 1);
  const T c = (k == 0 || k == n - 1) ? T(1) : (k % 2 == 1 ? T(4) : T(2));
  return c * h / T(3);
}

/// Quadrature weight of contact sample k of n on [0, 1]: composite Simpson for odd n (Leaf 2018 §3.1), the
/// trapezoid rule for n = 2, the fewest an adaptive segment gets (ContactSampling); the weights sum to 1.
template <class T> SKEIN_HD T contact_weight(int k, int n) { return n == 2 ? T(0.5) : simpson_weight<T>(k, n); }

/// Stiffnesses of the intrinsic terms (Leaf 2018 §3.1 and Appendix B).
template <class T>
struct IntrinsicParams {
  T k_bend;     ///< eq. 7, bending
  T k_stretch;  ///< eq. 8, internal stretch (uniform speed along the segment)
  T k_length;   ///< eq. 1, length penalty toward the rest length
};

/// Number of quadrature samples for the intrinsic energies (Leaf §3.1: 11, as Kaldor 2008).
constexpr int kIntrinsicSamples = 11;

/// Bending (Leaf eq. 7), internal stretch (eq. 8) and the length penalty (eq. 1) of one segment with rest
/// length `rest`; adds the energy gradient to grad[4] and returns the energy. Simpson quadrature.
template <class T>
SKEIN_HD T segment_intrinsic(const Vec3<T> p[4], T rest, const IntrinsicParams<T>& k, Vec3<T> grad[4]) {
  constexpr int n = kIntrinsicSamples;
  T bend = 0, stretch = 0, length = 0;
  Vec3<T> g_speed_sum[4] = {};  // d(length)/dp, for eq. 1's chain rule
  for (int i = 0; i < n; ++i) {
    const T s = T(i) / T(n - 1), q = simpson_weight<T>(i, n);
    T w1[4], w2[4];
    basis_d1(s, w1);
    basis_d2(s, w2);
    const Vec3<T> d1 = combine(w1, p), d2 = combine(w2, p);
    const T speed2 = dot(d1, d1), speed = std::sqrt(speed2);
    if (!(speed > T(0))) continue;
    // Curvature squared: |y' x y''|^2 / |y'|^6 (eq. 7); gradient in y' and y''.
    const Vec3<T> c = cross(d1, d2);
    const T c2 = dot(c, c), inv6 = T(1) / (speed2 * speed2 * speed2);
    bend += q * c2 * inv6;
    const Vec3<T> dk_d1 = cross(d2, c) * (2 * inv6) - d1 * (6 * c2 * inv6 / speed2);
    const Vec3<T> dk_d2 = cross(c, d1) * (2 * inv6);
    // Internal stretch (eq. 8): (1 - |y'|/l)^2.
    const T strain = T(1) - speed / rest;
    stretch += q * strain * strain;
    const Vec3<T> unit = d1 * (T(1) / speed);
    const Vec3<T> ds_d1 = unit * (-2 * strain / rest);
    length += q * speed;
    for (int j = 0; j < 4; ++j) {
      grad[j] += (dk_d1 * w1[j] + dk_d2 * w2[j]) * (q * k.k_bend * rest) + ds_d1 * (q * w1[j] * k.k_stretch);
      g_speed_sum[j] += unit * (q * w1[j]);
    }
  }
  // Length penalty (eq. 1): k_l (1 - L/l)^2 with L the quadrature length.
  const T c_len = T(1) - length / rest;
  for (int j = 0; j < 4; ++j) grad[j] += g_speed_sum[j] * (-2 * k.k_length * c_len / rest);
  return k.k_bend * rest * bend + k.k_stretch * stretch + k.k_length * c_len * c_len;
}

/// Kaldor's contact kernel (Leaf eq. 10) of d = distance / 2r: 1/d² + d² - 2 below 1, else 0, with its
/// derivative in d through `slope`. Below `d_soft` it continues along its tangent: emitted yarn can start
/// with centrelines almost touching (d near 0), where 1/d² would give forces no step size can follow; the
/// tangent keeps them finite and still pushing apart.
template <class T> SKEIN_HD T contact_kernel(T d, T d_soft, T& slope) {
  if (d >= T(1)) {
    slope = 0;
    return 0;
  }
  const T x = d < d_soft ? d_soft : d;
  const T inv2 = T(1) / (x * x);
  slope = -2 * inv2 / x + 2 * x;
  const T value = inv2 + x * x - 2;
  return d < d_soft ? value + slope * (d - d_soft) : value;
}

/// Contact stiffness and damping (Leaf eqs. 9 and 12).
template <class T>
struct ContactParams {
  T k_contact;  ///< eq. 9
  T k_dt;       ///< eq. 12, tangential damping
  T k_dn;       ///< eq. 12, normal damping
  T radius;     ///< r: samples closer than 2r touch
  T d_soft;     ///< distance / 2r below which the kernel is linear
};

/// One pair of contact samples (Leaf eqs. 9 and 12): sample a at ya moving with ua, sample b at yb moving
/// with ub, quadrature weight `weight` (w_i w_j l_a l_b). Returns the contact energy; adds its gradient with
/// respect to ya to grad_a and the contact damping force on a to damp_a (b's are the mirror images).
template <class T>
SKEIN_HD T sample_contact(const Vec3<T>& ya, const Vec3<T>& yb, const Vec3<T>& ua, const Vec3<T>& ub, T weight, const ContactParams<T>& k,
                          Vec3<T>& grad_a, Vec3<T>& damp_a) {
  const Vec3<T> diff = yb - ya;  // n_ij = y_b - y_a
  const T dist2 = dot(diff, diff), reach = 2 * k.radius;
  if (!(dist2 < reach * reach) || !(dist2 > T(0))) return 0;
  const T dist = std::sqrt(dist2), inv_2r = T(1) / reach;
  T slope;
  const T energy = weight * k.k_contact * contact_kernel(dist * inv_2r, k.d_soft, slope);
  const Vec3<T> normal = diff * (T(1) / dist);
  // dE/dy_a = k w f'(d) dd/dy_a = -k w f'(d) n / 2r
  grad_a += normal * (-k.k_contact * weight * slope * inv_2r);
  // Eq. 12 on a: 2 w [k_dt dv - (k_dt - k_dn) n (n . dv)], dv = u_b - u_a.
  const Vec3<T> dv = ub - ua;
  damp_a += (dv * k.k_dt - normal * ((k.k_dt - k.k_dn) * dot(normal, dv))) * (2 * weight);
  return energy;
}

/// The largest time step after which a sample with velocity u and acceleration acc (both already mapped
/// through the sample's basis row B_i(s)) moves at most `limit` (= eps r) under semi-implicit Euler:
/// Leaf 2018 eq. 2 (Appendix A). Returns +inf when the sample does not move.
template <class T> SKEIN_HD T step_bound(T u, T acc, T limit) {
  if (acc <= T(0)) return u > T(0) ? limit / u : T(INFINITY);
  return (-u + std::sqrt(u * u + 4 * limit * acc)) / (2 * acc);
}

/// Patch tracking (Yuksel 2012 eqs. 6–7) of one patch whose weighted mean drift from its start is v: the
/// energy W [phi_N(n.v) + k_T |v_t|^2] with phi_N quadratic, stiffened by k_far beyond `threshold` (biphasic).
/// The gradient on the patch's point i is w_i * slope.
template <class T>
SKEIN_HD T patch_tracking(const Vec3<T>& v, const Vec3<T>& normal, T weight_sum, T k_normal, T k_far, T threshold, T k_tangent, Vec3<T>& slope) {
  const T x = dot(normal, v), ax = x < 0 ? -x : x, beyond = ax > threshold ? ax - threshold : T(0);
  const Vec3<T> tangent = v - normal * x;
  const T dphi = 2 * k_normal * x + 2 * k_far * beyond * (x < 0 ? T(-1) : T(1));
  slope = normal * dphi + tangent * (2 * k_tangent);
  return weight_sum * (k_normal * x * x + k_far * beyond * beyond + k_tangent * dot(tangent, tangent));
}

/// Leaf 2018 eq. 5: converged when the residual |grad E| is small against the first one (eps1) and no longer
/// changing from the previous step (eps2). Never at step 0.
template <class T> SKEIN_HD bool converged(long step, T residual, T residual0, T residual_prev, T eps1, T eps2) {
  if (step <= 0 || !(residual0 > T(0))) return false;
  const T prev = residual_prev > T(1e-30) ? residual_prev : T(1e-30);
  const T change = residual / prev - T(1);
  return residual / residual0 <= eps1 && (change < 0 ? -change : change) <= eps2;
}

/// FIRE's controller (Bitzek et al. 2006) between steps: its step, mixing factor and count of steps downhill.
template <class T>
struct FireControl {
  T time_step, alpha;
  long positive;
};

/// One FIRE decision from the power P = F.v and the norms |v| and |F|: the new velocity is
/// keep v + mix F before this step's acceleration. Downhill, v turns toward F and after five such steps the
/// step grows (to at most max_step) and alpha shrinks; uphill, v stops, the step halves and alpha resets.
template <class T> SKEIN_HD void fire_control(T power, T vnorm, T fnorm, T max_step, FireControl<T>& c, T& keep, T& mix) {
  if (power > 0) {
    keep = fnorm > 0 ? 1 - c.alpha : T(1);
    mix = fnorm > 0 ? c.alpha * vnorm / fnorm : T(0);
    if (++c.positive > 5) {
      c.time_step = c.time_step * T(1.1) < max_step ? c.time_step * T(1.1) : max_step;
      c.alpha *= T(0.99);
    }
    return;
  }
  keep = mix = 0;
  c.time_step *= T(0.5);
  c.alpha = T(0.1);
  c.positive = 0;
}

}  // namespace skein::relax::model
