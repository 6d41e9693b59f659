#include "surface/mesh_forces.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace skein::surface::forces {

Stretch stretch(const Vec3& xi, const Vec3& xj, double rest, double k) {
  const Vec3 w = xi - xj;
  const double d = std::max(w.norm(), 1e-12);
  const Vec3 u = w / d;
  Stretch s;
  s.energy = k * (d - rest - rest * std::log(d / rest));
  s.force_i = k * (rest / d - 1) * u;
  return s;
}

Mat3 stretch_jacobian(const Vec3& xi, const Vec3& xj, double rest, double k) {
  const Vec3 w = xi - xj;
  const double d = std::max(w.norm(), 1e-12);
  const Vec3 u = w / d;
  // d/dx_i of k (ℓ/d − 1) u: k/d [(ℓ/d − 1)(I − u uᵀ) − (ℓ/d) u uᵀ]
  const Mat3 uu = u * u.transpose();
  return k / d * ((rest / d - 1) * (Mat3::Identity() - uu) - (rest / d) * uu);
}

Shear shear(const Vec3& xi, const Vec3& xj, const Vec3& xk, double k) {
  const Vec3 a = xi - xj, b = xk - xj;
  const double s = a.dot(b);
  // ds/dx for (i, j, k) and the constant second derivatives of s.
  const Vec3 g[3] = {b, -a - b, a};
  Shear out;
  out.energy = 0.25 * k * s * s;
  for (int p = 0; p < 3; ++p) out.force[p] = -0.5 * k * s * g[p];
  return out;
}

ShearJacobian shear_jacobian(const Vec3& xi, const Vec3& xj, const Vec3& xk, double k) {
  const Vec3 a = xi - xj, b = xk - xj;
  const double s = a.dot(b);
  const Vec3 g[3] = {b, -a - b, a};
  const double h[3][3] = {{0, -1, 1}, {-1, 2, -1}, {1, -1, 0}};  // the constant second derivatives of s
  ShearJacobian out;
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) out.block[p][q] = -0.5 * k * (g[p] * g[q].transpose() + s * h[p][q] * Mat3::Identity());
  return out;
}

namespace {
/// The strut's lengths: w = x_i − x_k (d, u its length and direction) and its rest r.
struct StrutGeometry {
  Vec3 w, u, eij, ekj;
  double d, r;
  bool follows;  ///< r = |x_i − x_j| + |x_k − x_j|, else the constant r_wale
  StrutGeometry(const Vec3& xi, const Vec3& xj, const Vec3& xk, double rest_wale)
      : w(xi - xk), eij(xi - xj), ekj(xk - xj), d(std::max(w.norm(), 1e-12)) {
    u = w / d;
    const double span = eij.norm() + ekj.norm();
    follows = span > rest_wale;
    r = follows ? span : rest_wale;
  }
};
}  // namespace

Strut wale_strut(const Vec3& xi, const Vec3& xj, const Vec3& xk, double rest_wale, double k) {
  const StrutGeometry g(xi, xj, xk, rest_wale);
  Strut out;
  out.energy = k * (g.d - g.r) * (g.d - g.r) / (2 * g.r);
  out.force_i = -k * (g.d / g.r - 1) * g.u;  // = −k w (1/r − 1/d)
  return out;
}

StrutJacobian wale_strut_jacobian(const Vec3& xi, const Vec3& xj, const Vec3& xk, double rest_wale, double k) {
  const StrutGeometry g(xi, xj, xk, rest_wale);
  const Vec3 &w = g.w, &u = g.u, &eij = g.eij, &ekj = g.ekj;
  const double d = g.d, r = g.r;
  const bool follows = g.follows;
  StrutJacobian out;
  // f_i = −k w (1/r − 1/d): d f_i/d x_b = −k [dw/dx_b (1/r − 1/d) + w (−dr/dx_b / r² + dd/dx_b / d²)]
  const Vec3 ui = eij.norm() > 0 ? Vec3(eij.normalized()) : Vec3::Zero(), uk = ekj.norm() > 0 ? Vec3(ekj.normalized()) : Vec3::Zero();
  const Vec3 dr[3] = {follows ? ui : Vec3::Zero(), follows ? Vec3(-ui - uk) : Vec3::Zero(), follows ? uk : Vec3::Zero()};
  const Vec3 dd[3] = {u, Vec3::Zero(), -u};
  const double dw[3] = {1, 0, -1};
  for (int b = 0; b < 3; ++b) {
    const Mat3 dfi = -k * (dw[b] * (1 / r - 1 / d) * Mat3::Identity() + w * (-dr[b] / (r * r) + dd[b] / (d * d)).transpose());
    out.block[0][b] = dfi;
    out.block[1][b] = -dfi;  // f_k = −f_i
  }
  return out;
}

FoldGuard fold_guard(const Vec3& xi, const Vec3& xj, const Vec3& xk, const Vec3& n, double a0, double t0, double k) {
  const Vec3 e1 = xi - xj, e2 = xk - xj;
  const double a = e1.cross(e2).dot(n);
  const double phi = std::max(0.0, t0 - a / a0);
  FoldGuard out;
  out.gradient[0] = e2.cross(n);  // (e1 × e2)·n = e1·(e2 × n) = e2·(n × e1)
  out.gradient[2] = n.cross(e1);
  out.gradient[1] = -out.gradient[0] - out.gradient[2];
  out.energy = 0.5 * k * a0 * phi * phi;
  out.active = phi > 0;
  for (int p = 0; p < 3; ++p) out.force[p] = k * phi * out.gradient[p];  // −dE/dx = k a0 φ (da/dx) / a0
  return out;
}

}  // namespace skein::surface::forces
