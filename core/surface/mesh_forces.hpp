#pragma once
// Spring terms of the mesh-based relaxation (Yuksel 2012 §6.1), as stateless functions on fixed-size types.
// Each gives its energy, the force on every vertex it touches (minus the energy gradient where one exists) and
// the force Jacobian blocks d f_a / d x_b. Positions in mm; forces in the paper's units (stiffness × strain).
#include <Eigen/Core>

namespace skein::surface::forces {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// Yuksel eq. 2: f_i = κ (ℓ/|x_i − x_j| − 1) (x_i − x_j)/|x_i − x_j|, infinite as the edge shrinks to nothing.
/// Energy κ (d − ℓ − ℓ ln(d/ℓ)) ≥ 0, zero at rest; f_j = −f_i.
struct Stretch {
  double energy;
  Vec3 force_i;
};
Stretch stretch(const Vec3& xi, const Vec3& xj, double rest, double stiffness);
/// d f_i / d x_i of the stretch force; d f_i / d x_j is its negative.
Mat3 stretch_jacobian(const Vec3& xi, const Vec3& xj, double rest, double stiffness);

/// Yuksel eq. 3 made conservative: E = κ/4 ((x_i − x_j)·(x_k − x_j))², whose force on the corner j is the
/// paper's −κ s (x_j − (x_i + x_k)/2); i and k get the matching gradient forces (the paper gives them half of
/// −f_j each, which no energy has).
struct Shear {
  double energy;
  Vec3 force[3];
};
Shear shear(const Vec3& xi, const Vec3& xj, const Vec3& xk, double stiffness);
/// The shear's Jacobian blocks J[a][b] = d f_a / d x_b for a, b in (i, j, k).
struct ShearJacobian {
  Mat3 block[3][3];
};
ShearJacobian shear_jacobian(const Vec3& xi, const Vec3& xj, const Vec3& xk, double stiffness);

/// Yuksel eq. 4: a strut between the far ends i and k of two consecutive wale edges i–j and j–k,
/// f_i = −κ (|x_i − x_k|/r − 1) (x_i − x_k)/|x_i − x_k|, r = max(r_wale, |x_i − x_j| + |x_k − x_j|), f_k = −f_i.
/// It pushes bent wale columns straight. Energy κ (d − r)²/(2r) with r taken at the current state.
struct Strut {
  double energy;
  Vec3 force_i;
};
Strut wale_strut(const Vec3& xi, const Vec3& xj, const Vec3& xk, double rest_wale, double stiffness);
/// The strut's Jacobian blocks d f_a / d x_b for a in (i, k), b in (i, j, k), with r's own derivative included.
struct StrutJacobian {
  Mat3 block[2][3];
};
StrutJacobian wale_strut_jacobian(const Vec3& xi, const Vec3& xj, const Vec3& xk, double rest_wale, double stiffness);

/// Keeps a stitch from turning over (not in Yuksel 2012): at a sub-quad corner j with neighbours i and k, the
/// signed area a = ((x_i − x_j) × (x_k − x_j))·n against the surface normal n is held above t0 a0 by
/// E = κ a0 φ²/2, φ = max(0, t0 − a/a0), a0 the rest corner area. n is fixed, so E is a function of x.
/// Forces on (i, j, k); `gradient` is da/dx (the Jacobian's Gauss-Newton part is −κ/a0 g gᵀ when active).
struct FoldGuard {
  double energy;
  Vec3 force[3];
  Vec3 gradient[3];
  bool active;
};
FoldGuard fold_guard(const Vec3& xi, const Vec3& xj, const Vec3& xk, const Vec3& normal, double rest_area, double threshold, double stiffness);

}  // namespace skein::surface::forces
