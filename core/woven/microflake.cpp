#include "woven/microflake.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/error.hpp"

namespace skein::woven {

FiberMicroflake::FiberMicroflake(double exponent) : m_p(exponent) {
  if (!(exponent >= 0 && exponent <= 1000)) throw Error("", "microflake", "the fibre exponent must be 0 to 1000");
  // Normalization: ∫ sin^p θ dm = 2π ∫_{-1}^{1} (1 - c²)^{p/2} dc (midpoint rule, fine enough for p <= 1000).
  const int n = 20000;
  double integral = 0;
  for (int k = 0; k < n; ++k) {
    const double c = -1 + (k + 0.5) * 2.0 / n;
    integral += std::pow(1 - c * c, 0.5 * m_p) * 2.0 / n;
  }
  m_norm = 2 * std::numbers::pi * integral;
  // σ(ω) = ∫ |ω · m| D(m) dm for ω at angle acos(u) from f, by quadrature over the flake's (θ, φ) about f.
  const int nt = 400, np = 256;
  std::array<double, np> cosines;
  for (int b = 0; b < np; ++b) cosines[b] = std::cos((b + 0.5) * 2 * std::numbers::pi / np);
  for (int k = 0; k < kTable; ++k) {
    const double u = static_cast<double>(k) / (kTable - 1), s = std::sqrt(1 - u * u);
    double sigma = 0;
    for (int a = 0; a < nt; ++a) {
      const double c = -1 + (a + 0.5) * 2.0 / nt, sc = std::sqrt(1 - c * c);
      const double d = std::pow(1 - c * c, 0.5 * m_p) / m_norm;
      for (int b = 0; b < np; ++b) sigma += std::abs(u * c + s * sc * cosines[b]) * d * (2.0 / nt) * (2 * std::numbers::pi / np);
    }
    m_sigma[k] = sigma;
    m_sigma_max = std::max(m_sigma_max, sigma);
  }
}

double FiberMicroflake::density(const Eigen::Vector3d& m, const Eigen::Vector3d& f) const {
  const double c = m.dot(f);
  return std::pow(std::max(0.0, 1 - c * c), 0.5 * m_p) / m_norm;
}

double FiberMicroflake::sigma(const Eigen::Vector3d& w, const Eigen::Vector3d& f) const {
  const double u = std::min(1.0, std::abs(w.dot(f))) * (kTable - 1);
  const int k = std::min(kTable - 2, static_cast<int>(u));
  const double t = u - k;
  return (1 - t) * m_sigma[k] + t * m_sigma[k + 1];
}

double FiberMicroflake::phase(const Eigen::Vector3d& wi, const Eigen::Vector3d& wo, const Eigen::Vector3d& f) const {
  const Eigen::Vector3d h = wi + wo;
  if (h.squaredNorm() < 1e-20) return 0;
  // Jakob 2010 writes D(h) / (4 σ); the flakes' normals h and -h both reflect wi into wo, so with D over the
  // whole sphere the density of wo is 2 D(h) / (4 σ) (the test integrates it to 1).
  return density(h.normalized(), f) / (2 * sigma(wi, f));
}

Eigen::Vector3d FiberMicroflake::sample_normal(const Eigen::Vector3d& f, std::mt19937_64& random) const {
  std::uniform_real_distribution<double> unit(0, 1);
  double c = 0;
  do c = 2 * unit(random) - 1;
  while (unit(random) > std::pow(1 - c * c, 0.5 * m_p));
  const double phi = 2 * std::numbers::pi * unit(random), s = std::sqrt(std::max(0.0, 1 - c * c));
  const Eigen::Vector3d u = f.unitOrthogonal(), v = f.cross(u);
  return c * f + s * (std::cos(phi) * u + std::sin(phi) * v);
}

Eigen::Vector3d FiberMicroflake::sample(const Eigen::Vector3d& wi, const Eigen::Vector3d& f, std::mt19937_64& random) const {
  std::uniform_real_distribution<double> unit(0, 1);
  Eigen::Vector3d m;
  do m = sample_normal(f, random);
  while (unit(random) > std::abs(wi.dot(m)));
  if (wi.dot(m) < 0) m = -m;
  return 2 * wi.dot(m) * m - wi;
}

}  // namespace skein::woven
