#include "woven/volume.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "common/error.hpp"

namespace skein::woven {

std::vector<Eigen::MatrixXf> top_surfaces(const std::vector<Exemplar>& exemplars) {
  std::vector<Eigen::MatrixXf> out;
  for (const auto& ex : exemplars) {
    const auto& g = ex.grid;
    Eigen::MatrixXf top = Eigen::MatrixXf::Constant(g.nx, g.ny, std::numeric_limits<float>::quiet_NaN());
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        for (int z = g.nz - 1; z >= 0; --z)
          if (g.density[g.index(x, y, z)] > 0.05f) {
            top(x, y) = static_cast<float>(g.origin.z() + (z + 0.5) * g.voxel);
            break;
          }
    out.push_back(std::move(top));
  }
  return out;
}

namespace {

/// The top surface of a crossing's block at its voxel column (a, b).
float surface(const std::vector<Eigen::MatrixXf>& tops, const Exemplar& first, const Block& block, int a, int b) {
  return tops[block.exemplar](block.x * first.block_x + a, block.y * first.block_y + b);
}

/// Half the step between two surfaces, 0 where either side has no fibres.
float halfway(float towards, float from) { return std::isfinite(towards) && std::isfinite(from) ? 0.5f * (towards - from) : 0.0f; }

/// Boundary data of one block (crossing index `c`): its top edge (bx values, corners included) and its left
/// edge without corners (by - 2 values): the shift that meets the neighbour above, or to the left, halfway.
void edges(const std::vector<Exemplar>& ex, const std::vector<Eigen::MatrixXf>& tops, const Assignment& as, int i, int j,
           Eigen::VectorXf& top, Eigen::VectorXf& left) {
  const int bx = ex[0].block_x, by = ex[0].block_y;
  top.setZero(bx);
  left.setZero(by - 2);
  const Block& here = as.at(i, j);
  if (i + 1 < as.wefts)
    for (int a = 0; a < bx; ++a) top(a) = halfway(surface(tops, ex[0], as.at(i + 1, j), a, 0), surface(tops, ex[0], here, a, by - 1));
  if (j > 0)
    for (int b = 1; b < by - 1; ++b) left(b - 1) = halfway(surface(tops, ex[0], as.at(i, j - 1), bx - 1, b), surface(tops, ex[0], here, 0, b));
}

/// Solves the discrete Laplace equation on a bx x by grid whose outer ring holds `ring` (inner values ignored).
class Laplace {
public:
  Laplace(int bx, int by) : m_bx(bx), m_by(by) {
    const int n = (bx - 2) * (by - 2);
    std::vector<Eigen::Triplet<double>> entries;
    for (int b = 1; b < by - 1; ++b)
      for (int a = 1; a < bx - 1; ++a) {
        const int k = unknown(a, b);
        entries.emplace_back(k, k, 4.0);
        for (const auto& [da, db] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const int na = a + da, nb = b + db;
          if (na > 0 && nb > 0 && na < bx - 1 && nb < by - 1) entries.emplace_back(k, unknown(na, nb), -1.0);
        }
      }
    m_matrix.resize(n, n);
    m_matrix.setFromTriplets(entries.begin(), entries.end());
    m_solver.compute(m_matrix);
  }
  Eigen::MatrixXf solve(Eigen::MatrixXf ring) const {
    if (m_bx < 3 || m_by < 3) return ring;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m_matrix.rows());
    for (int b = 1; b < m_by - 1; ++b)
      for (int a = 1; a < m_bx - 1; ++a)
        for (const auto& [da, db] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const int na = a + da, nb = b + db;
          if (na == 0 || nb == 0 || na == m_bx - 1 || nb == m_by - 1) rhs(unknown(a, b)) += ring(na, nb);
        }
    const Eigen::VectorXd inner = m_solver.solve(rhs);
    for (int b = 1; b < m_by - 1; ++b)
      for (int a = 1; a < m_bx - 1; ++a) ring(a, b) = static_cast<float>(inner(unknown(a, b)));
    return ring;
  }

private:
  int unknown(int a, int b) const { return (b - 1) * (m_bx - 2) + (a - 1); }
  int m_bx, m_by;
  Eigen::SparseMatrix<double> m_matrix;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> m_solver;
};

/// The leading `rank` eigenvectors of a Gram matrix, and the share of its trace they keep.
Eigen::MatrixXd leading(const Eigen::MatrixXd& gram, int rank, double& kept_trace) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram);
  const int n = static_cast<int>(gram.rows()), r = std::min(rank, n);
  kept_trace = eigen.eigenvalues().tail(r).sum();
  return eigen.eigenvectors().rightCols(r);
}

}  // namespace

EdgeFix::EdgeFix(const std::vector<Exemplar>& ex, const Assignment& as, int rank) : m_bx(ex[0].block_x), m_by(ex[0].block_y), m_warps(as.warps), m_wefts(as.wefts) {
  if (m_bx < 3 || m_by < 3) throw Error("", "edge fixing", "needs blocks of at least 3 x 3 voxels");
  const auto tops = top_surfaces(ex);
  const long blocks = static_cast<long>(as.warps) * as.wefts;
  // First pass: the Gram matrices T T^T and L L^T, without storing T and L (they are cheap to make again).
  Eigen::MatrixXd tt = Eigen::MatrixXd::Zero(m_bx, m_bx), ll = Eigen::MatrixXd::Zero(m_by - 2, m_by - 2);
  Eigen::VectorXf top, left;
  for (int i = 0; i < as.wefts; ++i)
    for (int j = 0; j < as.warps; ++j) {
      edges(ex, tops, as, i, j, top, left);
      const Eigen::VectorXd t = top.cast<double>(), l = left.cast<double>();
      tt.noalias() += t * t.transpose();
      ll.noalias() += l * l.transpose();
    }
  const int rt = rank > 0 ? std::min(rank, m_bx) : m_bx, rl = rank > 0 ? std::min(rank, m_by - 2) : m_by - 2;
  double kept_t = 0, kept_l = 0;
  const Eigen::MatrixXd bt = leading(tt, rt, kept_t), bl = leading(ll, rl, kept_l);
  const double total = tt.trace() + ll.trace();
  m_kept = total > 0 ? (kept_t + kept_l) / total : 1.0;
  m_rank = std::max(rt, rl);
  // The 2r Laplace solutions: basis column t on the top edge (or the left edge), every other edge 0.
  const Laplace laplace(m_bx, m_by);
  const int columns = m_bx * m_by;
  m_top = m_left = m_top_mirrored = m_left_mirrored = Eigen::MatrixXf::Zero(m_rank, columns);
  const auto store = [&](const Eigen::MatrixXf& field, int t, Eigen::MatrixXf& plain, Eigen::MatrixXf& mirrored, bool vertically) {
    for (int b = 0; b < m_by; ++b)
      for (int a = 0; a < m_bx; ++a) {
        plain(t, a + b * m_bx) = field(a, b);
        mirrored(t, a + b * m_bx) = vertically ? field(a, m_by - 1 - b) : field(m_bx - 1 - a, b);
      }
  };
  for (int t = 0; t < rt; ++t) {
    Eigen::MatrixXf ring = Eigen::MatrixXf::Zero(m_bx, m_by);
    for (int a = 0; a < m_bx; ++a) ring(a, m_by - 1) = static_cast<float>(bt(a, t));
    store(laplace.solve(ring), t, m_top, m_top_mirrored, true);
  }
  for (int t = 0; t < rl; ++t) {
    Eigen::MatrixXf ring = Eigen::MatrixXf::Zero(m_bx, m_by);
    for (int b = 1; b < m_by - 1; ++b) ring(0, b) = static_cast<float>(bl(b - 1, t));
    store(laplace.solve(ring), t, m_left, m_left_mirrored, false);
  }
  // Second pass: each block's coefficients C = B^T t.
  m_ct = Eigen::MatrixXf::Zero(m_rank, blocks);
  m_cl = Eigen::MatrixXf::Zero(m_rank, blocks);
  const Eigen::MatrixXf btf = bt.cast<float>(), blf = bl.cast<float>();
  for (int i = 0; i < as.wefts; ++i)
    for (int j = 0; j < as.warps; ++j) {
      edges(ex, tops, as, i, j, top, left);
      const long c = static_cast<long>(i) * as.warps + j;
      m_ct.col(c).head(rt) = btf.transpose() * top;
      m_cl.col(c).head(rl) = blf.transpose() * left;
    }
}

double EdgeFix::shift(int i, int j, int a, int b) const {
  if (m_rank == 0) return 0;
  const long c = static_cast<long>(i) * m_warps + j;
  const int k = a + b * m_bx;
  double s = m_ct.col(c).dot(m_top.col(k)) + m_cl.col(c).dot(m_left.col(k));
  // The lower neighbour's top edge is this block's bottom edge, and the right neighbour's left edge this block's
  // right edge, each with the opposite sign (the two sides meet halfway).
  if (i > 0) s -= m_ct.col(c - m_warps).dot(m_top_mirrored.col(k));
  if (j + 1 < m_warps) s -= m_cl.col(c + 1).dot(m_left_mirrored.col(k));
  return s;
}

double seam_step(const std::vector<Exemplar>& ex, const Assignment& as, const EdgeFix* fix) {
  const auto tops = top_surfaces(ex);
  const int bx = ex[0].block_x, by = ex[0].block_y;
  const auto lifted = [&](int i, int j, int a, int b) {
    const float h = surface(tops, ex[0], as.at(i, j), a, b);
    return fix && !fix->empty() ? h + static_cast<float>(fix->shift(i, j, a, b)) : h;
  };
  double sum = 0;
  long count = 0;
  const auto add = [&](float p, float q) {
    if (std::isfinite(p) && std::isfinite(q)) sum += std::abs(p - q), ++count;
  };
  for (int i = 0; i < as.wefts; ++i)
    for (int j = 0; j < as.warps; ++j) {
      if (i + 1 < as.wefts)
        for (int a = 0; a < bx; ++a) add(lifted(i, j, a, by - 1), lifted(i + 1, j, a, 0));
      if (j + 1 < as.warps)
        for (int b = 1; b < by - 1; ++b) add(lifted(i, j, bx - 1, b), lifted(i, j + 1, 0, b));
    }
  return count > 0 ? sum / count : 0.0;
}

WovenVolume make_volume(const std::vector<Exemplar>& exemplars, const Weave& weave, const Assignment& assignment, int edge_rank,
                        std::vector<int> warp_color, std::vector<int> weft_color) {
  if (exemplars.empty()) throw Error("", "woven volume", "needs exemplars");
  const auto& first = exemplars[0];
  for (const auto& e : exemplars)
    if (e.block_x != first.block_x || e.block_y != first.block_y || std::abs(e.grid.voxel - first.grid.voxel) > 1e-9 ||
        std::abs(e.spacing - first.spacing) > 1e-9)
      throw Error("", "exemplar " + e.name, "has another block layout than exemplar " + first.name + " (blocks, voxel size and spacing must agree)");
  if (assignment.warps != weave.warps || assignment.wefts != weave.wefts) throw Error("", "woven volume", "the assignment is not the weave's size");
  WovenVolume v;
  v.exemplars = &exemplars;
  v.weave = weave;
  v.assignment = assignment;
  const size_t crossings = static_cast<size_t>(weave.warps) * weave.wefts;
  v.warp_color = warp_color.empty() ? std::vector<int>(crossings, 0) : std::move(warp_color);
  v.weft_color = weft_color.empty() ? std::vector<int>(crossings, 1) : std::move(weft_color);
  if (v.warp_color.size() != crossings || v.weft_color.size() != crossings) throw Error("", "woven volume", "a colour map is not one per crossing");
  v.spacing = first.spacing;
  v.voxel = first.grid.voxel;
  v.block_x = first.block_x;
  v.block_y = first.block_y;
  if (edge_rank != 0) v.fix = EdgeFix(exemplars, assignment, edge_rank);
  const double room = v.fix.empty() ? 0.0 : first.radius;  // edge fixing shifts stacks by a fraction of a yarn
  v.z_low = 1e30, v.z_high = -1e30;
  for (const auto& e : exemplars)
    v.z_low = std::min(v.z_low, e.grid.origin.z() - room), v.z_high = std::max(v.z_high, e.grid.origin.z() + e.grid.nz * e.grid.voxel + room);
  return v;
}

WovenVolume::Sample WovenVolume::at(const Eigen::Vector3d& p) const {
  const int j = static_cast<int>(std::floor(p.x() / spacing)), i = static_cast<int>(std::floor(p.y() / spacing));
  if (i < 0 || j < 0 || i >= weave.wefts || j >= weave.warps) return {};
  const int a = std::clamp(static_cast<int>((p.x() - j * spacing) / voxel), 0, block_x - 1);
  const int b = std::clamp(static_cast<int>((p.y() - i * spacing) / voxel), 0, block_y - 1);
  const Block& block = assignment.at(i, j);
  const Exemplar& ex = (*exemplars)[block.exemplar];
  const double z = p.z() - (fix.empty() ? 0.0 : fix.shift(i, j, a, b));
  const int k = static_cast<int>(std::floor((z - ex.grid.origin.z()) / voxel));
  if (k < 0 || k >= ex.grid.nz) return {};
  const size_t index = ex.grid.index(block.x * block_x + a, block.y * block_y + b, k);
  const int yarn = ex.grid.yarn[index];
  if (yarn < 0) return {};
  const bool warp = ex.is_warp(yarn);
  const size_t c = static_cast<size_t>(i) * weave.warps + j;
  return {ex.grid.density[index], ex.grid.orientation[index], warp ? warp_color[c] : weft_color[c], warp};
}

Exemplar volume_region(const WovenVolume& v, int warp0, int weft0, int warps, int wefts) {
  if (warp0 < 0 || weft0 < 0 || warps < 1 || wefts < 1 || warp0 + warps > v.weave.warps || weft0 + wefts > v.weave.wefts)
    throw Error("", "region", "lies outside the fabric's " + std::to_string(v.weave.warps) + " x " + std::to_string(v.weave.wefts) + " crossings");
  Exemplar out;
  out.name = "region";
  out.weave = make_weave(warps, wefts);
  for (int i = 0; i < wefts; ++i)
    for (int j = 0; j < warps; ++j) out.weave.set(i, j, v.weave.at(weft0 + i, warp0 + j));
  out.block_x = v.block_x;
  out.block_y = v.block_y;
  out.spacing = v.spacing;
  out.radius = (*v.exemplars)[0].radius;
  auto& g = out.grid;
  g.voxel = v.voxel;
  g.nx = warps * v.block_x;
  g.ny = wefts * v.block_y;
  g.nz = static_cast<int>(std::ceil((v.z_high - v.z_low) / v.voxel));
  g.origin = {warp0 * v.spacing, weft0 * v.spacing, v.z_low};
  g.allocate();
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const Eigen::Vector3d p = g.origin + v.voxel * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
        const auto s = v.at(p);
        if (s.density <= 0) continue;
        const size_t k = g.index(x, y, z);
        g.density[k] = s.density;
        g.orientation[k] = s.direction;
        // The yarn at this crossing: its warp (column) or its weft (row), numbered as an exemplar's.
        g.yarn[k] = static_cast<std::int16_t>(s.warp ? x / v.block_x : warps + y / v.block_y);
      }
  return out;
}

VolumeDifference compare_grids(const VoxelGrid& a, const VoxelGrid& b, int warps) {
  if (a.nx != b.nx || a.ny != b.ny || std::abs(a.voxel - b.voxel) > 1e-9) throw Error("", "comparison", "the two grids differ in size or voxel");
  const int dz = static_cast<int>(std::lround((b.origin.z() - a.origin.z()) / a.voxel));  // b's layer k is a's k + dz
  double diff = 0, mass = 0, angle = 0, surface = 0;
  long either = 0, both = 0, surfaces = 0, agree = 0;
  for (int y = 0; y < a.ny; ++y)
    for (int x = 0; x < a.nx; ++x) {
      double top_a = std::numeric_limits<double>::quiet_NaN(), top_b = top_a;
      bool warp_a = false, warp_b = false;
      for (int z = std::min(0, dz); z < std::max(a.nz, b.nz + dz); ++z) {
        const bool in_a = z >= 0 && z < a.nz, in_b = z - dz >= 0 && z - dz < b.nz;
        const size_t ia = in_a ? a.index(x, y, z) : 0, ib = in_b ? b.index(x, y, z - dz) : 0;
        const float ra = in_a ? a.density[ia] : 0.0f, rb = in_b ? b.density[ib] : 0.0f;
        if (ra > 0.05f) top_a = z, warp_a = a.yarn[ia] < warps;
        if (rb > 0.05f) top_b = z, warp_b = b.yarn[ib] < warps;
        if (ra <= 0 && rb <= 0) continue;
        ++either;
        diff += std::abs(ra - rb);
        mass += 0.5 * (ra + rb);
        if (ra > 0 && rb > 0) {
          ++both;
          const double c = std::min(1.0, static_cast<double>(std::abs(a.orientation[ia].dot(b.orientation[ib]))));
          angle += std::acos(c) * 180 / std::numbers::pi;
        }
      }
      if (std::isfinite(top_a) && std::isfinite(top_b)) surface += std::abs(top_a - top_b) * a.voxel, ++surfaces, agree += warp_a == warp_b;
    }
  VolumeDifference d;
  d.density_error = mass > 0 ? diff / mass : 0;
  d.occupancy = either > 0 ? static_cast<double>(both) / either : 1;
  d.orientation_deg = both > 0 ? angle / both : 0;
  d.surface_error = surfaces > 0 ? surface / surfaces : 0;
  d.top_agreement = surfaces > 0 ? static_cast<double>(agree) / surfaces : 1;
  return d;
}

}  // namespace skein::woven
