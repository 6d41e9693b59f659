#pragma once
// Limited-memory BFGS directions (Liu and Nocedal 1989, the two-loop recursion; Nocedal and Wright 2006,
// Algorithm 7.4) for the yarn relaxer's --method lbfgs. There is no line search: as in atomistic relaxers the
// whole move is scaled down to the movement limit, and the pull-through guard has the last word on it.
#include <deque>

#include <Eigen/Core>

namespace skein::relax {

class LbfgsMemory {
public:
  explicit LbfgsMemory(int memory) : m_memory(memory) {}

  /// The descent direction −H ∇E for `gradient` from the remembered pairs; with none, or where the curvature
  /// they give points uphill, the steepest descent −∇E (the memory is then forgotten).
  Eigen::Matrix3Xd direction(const Eigen::Matrix3Xd& gradient) {
    const int m = static_cast<int>(m_s.size());
    Eigen::Matrix3Xd q = gradient;
    std::vector<double> alpha(m);
    for (int i = m - 1; i >= 0; --i) {
      alpha[i] = m_rho[i] * dot(m_s[i], q);
      q -= alpha[i] * m_y[i];
    }
    // H0 = γ I, γ = sᵀy / yᵀy of the newest pair (Nocedal and Wright eq. 7.20).
    if (m > 0) q *= dot(m_s.back(), m_y.back()) / dot(m_y.back(), m_y.back());
    for (int i = 0; i < m; ++i) {
      const double beta = m_rho[i] * dot(m_y[i], q);
      q += (alpha[i] - beta) * m_s[i];
    }
    if (m > 0 && dot(q, gradient) <= 0) {
      forget();
      return -gradient;
    }
    return -q;
  }

  /// The move the yarn took and the gradient change it brought; a pair with no positive curvature (sᵀy) is
  /// skipped, as BFGS must.
  void remember(const Eigen::Matrix3Xd& move, const Eigen::Matrix3Xd& gradient_change) {
    const double sy = dot(move, gradient_change);
    if (!(sy > 1e-12 * move.norm() * gradient_change.norm())) return;
    m_s.push_back(move);
    m_y.push_back(gradient_change);
    m_rho.push_back(1 / sy);
    if (static_cast<int>(m_s.size()) > m_memory) {
      m_s.pop_front();
      m_y.pop_front();
      m_rho.pop_front();
    }
  }

  void forget() {
    m_s.clear();
    m_y.clear();
    m_rho.clear();
  }
  bool empty() const { return m_s.empty(); }

private:
  static double dot(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) { return a.cwiseProduct(b).sum(); }
  int m_memory;
  std::deque<Eigen::Matrix3Xd> m_s, m_y;
  std::deque<double> m_rho;
};

}  // namespace skein::relax
