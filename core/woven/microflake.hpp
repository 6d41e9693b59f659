#pragma once
#include <array>
#include <random>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace skein::woven {

/// The microflake phase function of Jakob et al. 2010 for fibres, as Zhao 2011 and 2012 render cloth: a
/// voxel is a cloud of mirror flakes whose normals m follow D(m) ∝ |sin(m, f)|^p about the fibre direction f
/// (normals perpendicular to the fibre, more so for larger p). Light travelling along ω meets the projected
/// flake area σ(ω) = ∫ |ω · m| D(m) dm per unit density (so extinction is anisotropic: σ_t = ρ σ(ω)), and
/// scatters by mirror reflection on a flake drawn from D(m) |ω · m|.
class FiberMicroflake {
public:
  explicit FiberMicroflake(double exponent = 20);
  double exponent() const { return m_p; }
  /// D(m) with m and f unit vectors; integrates to 1 over the sphere.
  double density(const Eigen::Vector3d& m, const Eigen::Vector3d& f) const;
  /// σ(ω), tabulated in |ω · f|; between 0 and 1.
  double sigma(const Eigen::Vector3d& w, const Eigen::Vector3d& f) const;
  double sigma_max() const { return m_sigma_max; }
  /// The phase function f_p(wi -> wo) = D(h) / (2 σ(wi)) (h and -h both count), h the half vector of wi and wo (wi points back along
  /// the path, towards where the light goes next after reversing: both point away from the scattering point).
  double phase(const Eigen::Vector3d& wi, const Eigen::Vector3d& wo, const Eigen::Vector3d& f) const;
  /// Samples wo for wi by the rejection of Jakob 2010 (a flake from D, kept with probability |wi · m|, then
  /// the mirror direction); the weight of the sample is exactly 1 (times the albedo).
  Eigen::Vector3d sample(const Eigen::Vector3d& wi, const Eigen::Vector3d& f, std::mt19937_64& random) const;

private:
  Eigen::Vector3d sample_normal(const Eigen::Vector3d& f, std::mt19937_64& random) const;
  double m_p, m_norm, m_sigma_max = 0;
  static constexpr int kTable = 257;
  std::array<double, kTable> m_sigma{};  ///< σ at |ω · f| = k / (kTable - 1)
};

}  // namespace skein::woven
