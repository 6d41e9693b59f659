#include "relax/yarn_cell.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "relax/yarn_model.hpp"
#include "relax/yarn_relax.hpp"
#include "relax/yarn_segment.hpp"

namespace skein::relax {
namespace {

using V = model::Vec3<double>;
V vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d eig(const V& v) { return {v.x, v.y, v.z}; }

/// A contact sample with its lattice coordinate: the cells of its segment's control points through the basis.
struct CellSample {
  V pos;
  Eigen::Vector2d cell;
  double weight = 0, arc = 0;
};

}  // namespace

Eigen::Matrix2d CellStress::mean_stress(const Eigen::Vector3d& period_x, const Eigen::Vector3d& period_y) const {
  Eigen::Matrix<double, 3, 2> p;
  p << period_x, period_y;
  const Eigen::Matrix3d virial = gradient * p.transpose();  // dE/dε for P -> (I + ε) P
  return virial.topLeftCorner<2, 2>() / area;
}

CellStress cell_stress(const YarnSystem& system, const YarnParams& params, const ContactPairs& pairs, const PeriodicMap& map,
                       const Eigen::Matrix3Xd& points) {
  if (map.cells.size() != map.virtual_points.size()) throw Error("", "period", "the periodic map does not say each virtual point's repeat");
  const int n = system.num_points();
  std::vector<Eigen::Vector2d> cell(n, Eigen::Vector2d::Zero());
  std::vector<char> real(n, 1);
  for (size_t i = 0; i < map.virtual_points.size(); ++i) {
    cell[map.virtual_points[i]] = map.cells[i].cast<double>();
    real[map.virtual_points[i]] = 0;
  }
  for (int p : map.frozen) real[p] = 0;
  const auto view = segment_view(system);
  const model::IntrinsicParams<double> intrinsic{params.k_bend, params.k_stretch, params.k_length};
  const model::ContactParams<double> contact{params.k_contact, 0.0, 0.0, system.radius, params.contact_soft};
  const auto samples_of = [&](int s, std::vector<CellSample>& out) {
    const auto& sp = system.segment_points[s];
    const int count = system.contact_samples[s];
    out.resize(count);
    for (int i = 0; i < count; ++i) {
      double w[4];
      model::basis(static_cast<double>(i) / (count - 1), w);
      Eigen::Vector3d pos = Eigen::Vector3d::Zero();
      Eigen::Vector2d c = Eigen::Vector2d::Zero();
      for (int k = 0; k < 4; ++k) {
        pos += w[k] * points.col(sp[k]);
        c += w[k] * cell[sp[k]];
      }
      out[i] = {vec(pos), c, model::contact_weight<double>(i, count) * system.rest_length[s],
                system.arc_start[s] + system.rest_length[s] * i / (count - 1)};
    }
  };
  CellStress out;
  std::vector<CellSample> mine, theirs;
  for (int s = 0; s < system.num_segments(); ++s) {
    const auto& sp = system.segment_points[s];
    if (!real[sp[1]]) continue;
    // Intrinsic terms (Leaf eqs. 1, 7, 8): dE/dP = Σ_k ∂E/∂p_k c_kᵀ.
    const Eigen::Vector3d origin = points.col(sp[1]);
    V p[4], grad[4] = {};
    for (int k = 0; k < 4; ++k) p[k] = vec(points.col(sp[k]) - origin);
    // The three terms are linear in their stiffnesses: taken one at a time they sum to the whole.
    out.terms.bending += model::segment_intrinsic(p, system.rest_length[s], {intrinsic.k_bend, 0.0, 0.0}, grad);
    out.terms.stretch += model::segment_intrinsic(p, system.rest_length[s], {0.0, intrinsic.k_stretch, 0.0}, grad);
    out.terms.length += model::segment_intrinsic(p, system.rest_length[s], {0.0, 0.0, intrinsic.k_length}, grad);
    for (int k = 0; k < 4; ++k) out.gradient += eig(grad[k]) * cell[sp[k]].transpose();
    // Contact (Leaf eq. 9), half of each pair, as segment_forces counts it.
    samples_of(s, mine);
    const int curve = system.segment_curve[s];
    for (int k = pairs.start[s]; k < pairs.start[s + 1]; ++k) {
      const int t = pairs.partner[k];
      samples_of(t, theirs);
      const bool same_yarn = system.segment_curve[t] == curve;
      for (const auto& a : mine)
        for (const auto& b : theirs) {
          if (same_yarn && model::arc_distance(view, curve, a.arc, b.arc) < 2 * system.radius) continue;
          V g{0, 0, 0}, d{0, 0, 0};
          const double e = model::sample_contact(a.pos, b.pos, V{0, 0, 0}, V{0, 0, 0}, a.weight * b.weight, contact, g, d);
          if (e == 0 && g.x == 0 && g.y == 0 && g.z == 0) continue;
          out.terms.contact += 0.5 * e;
          out.gradient += 0.5 * eig(g) * (a.cell - b.cell).transpose();
        }
    }
  }
  out.energy = out.terms.bending + out.terms.stretch + out.terms.length + out.terms.contact;
  out.area = map.period_x.cross(map.period_y).norm();
  return out;
}

Eigen::Vector3d period_stresses(const CellStress& stress, const Eigen::Matrix<double, 3, 2>& period) {
  const double lx = period(0, 0), ly = period(1, 1);
  return {stress.gradient(0, 0) / ly, stress.gradient(1, 1) / lx, stress.gradient(0, 1) / lx};
}

void PeriodOptions::validate() const {
  if (!(tolerance > 0) || !std::isfinite(tolerance))
    throw Error("", "period tolerance", "must be positive (a share of the yarn's bending force per length), found " + std::to_string(tolerance));
  if (!free_x && !free_y) throw Error("", "--free-period", "frees neither length of the repeat: give x, y or xy");
}

PeriodRelaxer::PeriodRelaxer(const PeriodOptions& options, const Eigen::Vector3d& period_x, const Eigen::Vector3d& period_y) : m_options(options) {
  options.validate();
  if (std::abs(period_x.y()) > 1e-9 * period_x.norm() || std::abs(period_x.z()) > 1e-9 * period_x.norm() || std::abs(period_y.z()) > 1e-9 * period_y.norm())
    throw Error("", "period", "a free period needs period_x along x and period_y in the xy plane");
  m_period << period_x, period_y;
  // First steps: a thousandth of the repeat.
  m_step = Eigen::Vector3d(period_x.x(), period_y.y(), period_y.y()) * 1e-3;
}

Eigen::Matrix<double, 3, 2> PeriodRelaxer::propose(const CellStress& stress, const PeriodicMap& map, double largest_move) {
  const Eigen::Vector3d free(m_options.free_x, m_options.free_y, m_options.shear);
  const Eigen::Vector3d g = Eigen::Vector3d(stress.gradient(0, 0), stress.gradient(1, 1), stress.gradient(0, 1)).cwiseProduct(free);
  m_stress = period_stresses(stress, m_period).cwiseProduct(free);
  m_energy = stress.energy;
  m_terms = stress.terms;
  Eigen::Vector3d move = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const double product = g[i] * m_last[i];
    if (product > 0) m_step[i] *= 1.2;
    if (product < 0) {
      m_step[i] *= 0.5;  // the stress changed sign: overshot; iRprop− waits a step
      m_last[i] = 0;
      continue;
    }
    m_last[i] = g[i];
    if (g[i] != 0) move[i] = g[i] > 0 ? -m_step[i] : m_step[i];
  }
  // The farthest virtual point's move bounds the step (the guard's movement limit).
  double farthest = 0;
  for (const auto& c : map.cells)
    farthest = std::max(farthest, Eigen::Vector2d(c.x() * move.x() + c.y() * move.z(), c.y() * move.y()).norm());
  if (farthest > largest_move) {
    const double f = largest_move / farthest;
    move *= f;
    m_step *= f;
  }
  Eigen::Matrix<double, 3, 2> next = m_period;
  next(0, 0) += move.x();
  next(1, 1) += move.y();
  next(0, 1) += move.z();
  return next;
}

void PeriodRelaxer::reject() {
  m_step *= 0.5;
  m_last.setZero();
}

bool PeriodRelaxer::converged(double limit) const {
  return m_stress.cwiseAbs().maxCoeff() <= limit;  // the held components' stresses are zero
}

}  // namespace skein::relax
