#include "relax/yarn_cell.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <set>
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

namespace {

/// Each segment as a piece of yarn wherever it is copied: the real points of its four and their repeats from the
/// first's, the same either way along the yarn (two segments with one key are translated copies); no key for
/// a segment next to a frozen point, which copies nothing. `real`: per point, whether it is a real one.
struct SegmentKeys {
  using Key = std::array<int, 10>;
  std::vector<std::optional<Key>> keys;
  std::vector<char> real;
};

SegmentKeys segment_keys(const YarnSystem& system, const PeriodicMap& map) {
  const int n = system.num_points();
  std::vector<int> root(n);
  std::vector<Eigen::Vector2i> cell(n, Eigen::Vector2i::Zero());
  std::iota(root.begin(), root.end(), 0);
  for (size_t i = 0; i < map.virtual_points.size(); ++i) root[map.virtual_points[i]] = map.real_points[i], cell[map.virtual_points[i]] = map.cells[i];
  for (int p : map.frozen) root[p] = -1;
  SegmentKeys out;
  out.real.assign(n, 1);
  for (int p : map.virtual_points) out.real[p] = 0;
  for (int p : map.frozen) out.real[p] = 0;
  out.keys.resize(system.num_segments());
  for (int s = 0; s < system.num_segments(); ++s) {
    const auto& sp = system.segment_points[s];
    if (std::any_of(sp.begin(), sp.end(), [&](int p) { return root[p] < 0; })) continue;
    SegmentKeys::Key forward, backward;
    for (int k = 0; k < 4; ++k) {
      forward[k] = root[sp[k]], backward[k] = root[sp[3 - k]];
      if (k == 0) continue;
      const Eigen::Vector2i f = cell[sp[k]] - cell[sp[0]], b = cell[sp[3 - k]] - cell[sp[3]];
      forward[2 + 2 * k] = f.x(), forward[3 + 2 * k] = f.y(), backward[2 + 2 * k] = b.x(), backward[3 + 2 * k] = b.y();
    }
    out.keys[s] = std::min(forward, backward);
  }
  return out;
}

/// repeat_segments from the segments' keys.
std::vector<char> one_of_each(const YarnSystem& system, const SegmentKeys& pieces) {
  std::set<SegmentKeys::Key> seen;
  std::vector<char> out(system.num_segments(), 0);
  for (int s = 0; s < system.num_segments(); ++s) {
    const auto& sp = system.segment_points[s];
    if (!pieces.real[sp[1]] && !pieces.real[sp[2]]) continue;
    if (!pieces.keys[s]) {
      out[s] = pieces.real[sp[1]];  // next to a frozen end: no copy of it can be told
      continue;
    }
    out[s] = seen.insert(*pieces.keys[s]).second;
  }
  return out;
}

}  // namespace

std::vector<char> repeat_segments(const YarnSystem& system, const PeriodicMap& map) { return one_of_each(system, segment_keys(system, map)); }

std::vector<char> periodic_tested_segments(const YarnSystem& system, const PeriodicMap& map) {
  const auto pieces = segment_keys(system, map);
  std::vector<char> tested = one_of_each(system, pieces);
  std::set<SegmentKeys::Key> repeat;
  for (int s = 0; s < system.num_segments(); ++s)
    if (tested[s] && pieces.keys[s]) repeat.insert(*pieces.keys[s]);
  // Segments that copy no repeat segment: next to a frozen point, or at the patch's cut yarn ends, where the
  // copy of an end's real segment runs on.
  for (int s = 0; s < system.num_segments(); ++s) tested[s] |= !pieces.keys[s] || !repeat.count(*pieces.keys[s]);
  return tested;
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
  const auto counted = repeat_segments(system, map);
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
    if (!counted[s]) continue;
    const auto& sp = system.segment_points[s];
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
  if (!(bracket > 0 && bracket < 0.1))
    throw Error("", "period bracket", "must be above 0 and below 0.1 (a share of the width), found " + std::to_string(bracket));
  if (!(trial_force_tolerance > 0) || !std::isfinite(trial_force_tolerance))
    throw Error("", "period trial force tolerance", "must be positive, found " + std::to_string(trial_force_tolerance));
  if (free && method == Method::Bracket && (free_x == free_y || shear))
    throw Error("", "--period-method bracket", "finds one free length (--free-period x or y, without --shear); frame relaxes both");
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

CellFrame::CellFrame(const PeriodOptions& options, const Eigen::Matrix<double, 3, 2>& period, const PeriodicMap& map, const Eigen::Matrix3Xd& points)
    : m_free(options.free_x, options.free_y, options.shear), m_period0(period), m_period(period), m_map(map), m_frozen(points.cols(), 0) {
  options.validate();
  if (std::abs(period(1, 0)) > 1e-9 * period.col(0).norm() || std::abs(period(2, 0)) > 1e-9 * period.col(0).norm() ||
      std::abs(period(2, 1)) > 1e-9 * period.col(1).norm())
    throw Error("", "period", "a free period needs period_x along x and period_y in the xy plane");
  std::vector<char> real(points.cols(), 1);
  for (int p : map.virtual_points) real[p] = 0;
  for (int p : map.frozen) real[p] = 0, m_frozen[p] = 1;
  m_centre.setZero();
  int count = 0;
  for (long p = 0; p < points.cols(); ++p)
    if (real[p]) m_centre += points.col(p).head<2>(), ++count;
  if (count > 0) m_centre /= count;
  m_length = std::max(period(0, 0), period(1, 1));
}

Eigen::Matrix2d CellFrame::deformation() const {
  Eigen::Matrix2d p, p0;
  p << m_period(0, 0), m_period(0, 1), 0, m_period(1, 1);
  p0 << m_period0(0, 0), m_period0(0, 1), 0, m_period0(1, 1);
  return p * p0.inverse();
}

Eigen::Matrix3Xd CellFrame::gradient(const Eigen::Matrix3Xd& grad, const CellStress& stress, const Eigen::Matrix3Xd& points) const {
  const Eigen::Matrix2d f = deformation(), inverse = f.inverse();
  const long n = grad.cols();
  Eigen::Matrix3Xd out(3, n + 1);
  Eigen::Matrix2d dfdf = Eigen::Matrix2d::Zero();  // dE/dF: Σ g (X − c)ᵀ over the points ...
  for (long p = 0; p < n; ++p) {
    const Eigen::Vector2d g = grad.col(p).head<2>();
    out.col(p) << f.transpose() * g, grad(2, p);
    if (g.squaredNorm() > 0) dfdf += g * (inverse * (points.col(p).head<2>() - m_centre)).transpose();
  }
  // ... and ∂E/∂P P0ᵀ, the period's own share (the virtual copies' offsets P cell).
  Eigen::Matrix2d period_gradient, p0;
  period_gradient << stress.gradient(0, 0), stress.gradient(0, 1), stress.gradient(1, 0), stress.gradient(1, 1);
  p0 << m_period0(0, 0), m_period0(0, 1), 0, m_period0(1, 1);
  dfdf += period_gradient * p0.transpose();
  out.col(n) = Eigen::Vector3d(dfdf(0, 0), dfdf(1, 1), dfdf(0, 1)).cwiseProduct(m_free) / m_length;
  return out;
}

Eigen::Matrix<double, 3, 2> CellFrame::split(const Eigen::Matrix3Xd& move, Eigen::Matrix3Xd& points_move) const {
  const Eigen::Matrix2d f = deformation();
  const long n = move.cols() - 1;
  points_move.resize(3, n);
  for (long p = 0; p < n; ++p) points_move.col(p) << f * move.col(p).head<2>(), move(2, p);
  const Eigen::Vector3d dframe = move.col(n).cwiseProduct(m_free) / m_length;
  Eigen::Matrix2d next_f = f, p0;
  next_f(0, 0) += dframe.x();
  next_f(1, 1) += dframe.y();
  next_f(0, 1) += dframe.z();
  p0 << m_period0(0, 0), m_period0(0, 1), 0, m_period0(1, 1);
  const Eigen::Matrix2d next = next_f * p0;
  Eigen::Matrix<double, 3, 2> period = Eigen::Matrix<double, 3, 2>::Zero();
  period.topRows<2>() = next;
  return period;
}

Eigen::Matrix3Xd CellFrame::affine_move(const Eigen::Matrix<double, 3, 2>& next, const Eigen::Matrix3Xd& points) const {
  Eigen::Matrix2d p, q;
  p << m_period(0, 0), m_period(0, 1), 0, m_period(1, 1);
  q << next(0, 0), next(0, 1), 0, next(1, 1);
  const Eigen::Matrix2d strain = q * p.inverse() - Eigen::Matrix2d::Identity();
  Eigen::Matrix3Xd out = Eigen::Matrix3Xd::Zero(3, points.cols());
  for (long i = 0; i < points.cols(); ++i)
    if (!m_frozen[i]) out.col(i).head<2>() = strain * (points.col(i).head<2>() - m_centre);
  return out;
}

double CellFrame::largest_move(const Eigen::Matrix3Xd& move, const Eigen::Matrix3Xd& points) const {
  Eigen::Matrix3Xd points_move;
  const auto next = split(move, points_move);
  for (size_t i = 0; i < m_map.virtual_points.size(); ++i) points_move.col(m_map.virtual_points[i]) = points_move.col(m_map.real_points[i]);
  const Eigen::Matrix3Xd affine = affine_move(next, points + points_move);
  double largest = 0;
  for (long p = 0; p < points.cols(); ++p)
    if (!m_frozen[p]) largest = std::max(largest, (points_move.col(p) + affine.col(p)).norm());
  return largest;
}

Eigen::Matrix3Xd CellFrame::taken(const Eigen::Matrix3Xd& points_move, const Eigen::Matrix<double, 3, 2>& next) const {
  const Eigen::Matrix2d inverse = deformation().inverse();
  const long n = points_move.cols();
  Eigen::Matrix3Xd out(3, n + 1);
  for (long p = 0; p < n; ++p) out.col(p) << inverse * points_move.col(p).head<2>(), points_move(2, p);
  Eigen::Matrix2d p0, q;
  p0 << m_period0(0, 0), m_period0(0, 1), 0, m_period0(1, 1);
  q << next(0, 0), next(0, 1), 0, next(1, 1);
  const Eigen::Matrix2d change = q * p0.inverse() - deformation();
  out.col(n) = Eigen::Vector3d(change(0, 0), change(1, 1), change(0, 1)).cwiseProduct(m_free) * m_length;
  return out;
}

void CellFrame::accept(const Eigen::Matrix<double, 3, 2>& next) { m_period = next; }

}  // namespace skein::relax
