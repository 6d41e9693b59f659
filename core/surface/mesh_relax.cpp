#include "surface/mesh_relax.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>

#include "common/error.hpp"
#include "surface/mesh_forces.hpp"

namespace skein::surface {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Basis = Eigen::Matrix<double, 3, 2>;
using SystemMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

void MeshRelaxOptions::validate() const {
  const auto need = [](bool ok, const char* what, const std::string& rule) {
    if (!ok) throw Error("", std::string("mesh relaxation option ") + what, rule);
  };
  need(alpha > 0 && alpha <= 1, "alpha", "must be in (0, 1]");
  need(aspect > 0 && std::isfinite(aspect), "aspect", "must be positive");
  need(k_stretch > 0 && k_shear >= 0 && k_wale >= 0 && k_fold >= 0, "stiffness", "stretch must be positive, the others at least 0");
  need(fold_area > 0 && fold_area < 1, "fold area", "must be in (0, 1)");
  need(time_step >= 0 && std::isfinite(time_step), "time step", "must be 0 (automatic) or positive");
  need(max_steps >= 0, "max steps", "must be at least 0");
  need(tolerance > 0 && max_move > 0, "tolerance", "tolerance and max move must be positive");
  need(cg_iterations > 0 && cg_tolerance > 0, "conjugate gradients", "iterations and tolerance must be positive");
  need(samples_per_edge >= 1 && samples_per_edge <= 64, "samples per edge", "must be 1 to 64");
}

namespace {
struct Spring {
  int i, j;
  double rest, stiffness;
};
struct Corner {
  int i, j, k;
};
/// One term of the linear system: a symmetric block K on a pair (A gets −hK on both diagonals, +hK off them).
/// `slot` numbers the pair in the system's pattern (Impl::pair_blocks).
struct PairBlock {
  int i, j, slot;
  Mat3 K;
};
/// A rank-1 term c g gᵀ over the three vertices of shear corner `corner` (Gauss-Newton part of the shear and
/// the fold guard).
struct RankOne {
  int corner;
  Vec3 g[3];
  double c;
};
/// Where a 2×2 block of the system lies in its values: the offsets of its two rows.
using BlockSlot = std::array<int, 2>;
}  // namespace

struct MeshRelaxer::Impl {
  MeshRelaxOptions options;
  SubdivSurface surface;
  std::unique_ptr<SurfaceProjector> projector;
  mesh::StitchMesh stitch;
  std::vector<Attachment> at;
  std::vector<Vec3> x;
  std::vector<SurfaceCoord> coords;
  std::vector<char> border;
  std::vector<std::pair<int, int>> border_neighbours;  // -1 when not exactly two
  std::vector<Spring> springs;
  std::vector<Corner> shears, struts;
  std::vector<Vec3> corner_normal;  // surface normal at each shear corner's middle vertex, at attachment
  double r_course = 0, r_wale = 0, h = 0;
  // Yuksel's shear (eq. 3) is cubic in length while the stretch force (eq. 2) is a pure strain: the paper's
  // stiffnesses hold for stitches of unit size. Both terms are applied in units of the rest size r, so that
  // κ_shear, κ_fold mean the same for 1 mm and 10 mm stitches: κ_shear / r³ and κ_fold / r (energy ∝ κ r).
  double k_shear = 0, k_fold = 0;
  SystemMatrix system;            // I + hK: its pattern is fixed (every pair of vertices some term joins)
  std::vector<double> stiffness;  // K's values in that pattern
  std::vector<std::array<BlockSlot, 4>> pair_blocks;    // (i,i), (j,j), (i,j), (j,i) of each spring, then strut
  std::vector<std::array<BlockSlot, 9>> corner_blocks;  // (a,b) of each shear corner's (i, j, k), row-major
  std::vector<int> diagonal;                            // each row's diagonal entry
  double current_energy = 0;
  int steps_done = 0;

  Impl(const std::vector<Vec3>& cp, const std::vector<std::vector<int>>& cf, const mesh::StitchMesh& s, const MeshRelaxOptions& o)
      : options(o), surface(cp, cf), stitch(s) {}

  double energy(const std::vector<Vec3>& p) const {
    double e = 0;
    for (const auto& s : springs) e += forces::stretch(p[s.i], p[s.j], s.rest, s.stiffness).energy;
    for (const auto& c : shears) e += forces::shear(p[c.i], p[c.j], p[c.k], k_shear).energy;
    for (const auto& c : struts) e += forces::wale_strut(p[c.i], p[c.j], p[c.k], r_wale, options.k_wale).energy;
    if (k_fold > 0)
      for (size_t q = 0; q < shears.size(); ++q) {
        const auto& c = shears[q];
        // Shear corners run (previous, corner, next) counter-clockwise; the guard's area wants (next, corner, previous).
        e += forces::fold_guard(p[c.k], p[c.j], p[c.i], corner_normal[q], r_course * r_wale, options.fold_area, k_fold).energy;
      }
    return e;
  }

  /// Forces at p and the definite parts of their Jacobians (so that I − hJ stays positive definite).
  void assemble(const std::vector<Vec3>& p, std::vector<Vec3>& f, std::vector<PairBlock>& pairs, std::vector<RankOne>& ranks) const {
    f.assign(p.size(), Vec3::Zero());
    pairs.clear();
    ranks.clear();
    for (const auto& s : springs) {
      const int slot = static_cast<int>(pairs.size());
      const auto t = forces::stretch(p[s.i], p[s.j], s.rest, s.stiffness);
      f[s.i] += t.force_i;
      f[s.j] -= t.force_i;
      // Drop the part that pushes sideways on a compressed spring (it makes the system indefinite).
      const Vec3 w = p[s.i] - p[s.j];
      const double d = std::max(w.norm(), 1e-12);
      const Vec3 u = w / d;
      const Mat3 uu = u * u.transpose();
      pairs.push_back({s.i, s.j, slot, s.stiffness / d * (std::min(s.rest / d - 1, 0.0) * (Mat3::Identity() - uu) - (s.rest / d) * uu)});
    }
    for (size_t q = 0; q < shears.size(); ++q) {
      const auto& c = shears[q];
      const auto t = forces::shear(p[c.i], p[c.j], p[c.k], k_shear);
      f[c.i] += t.force[0];
      f[c.j] += t.force[1];
      f[c.k] += t.force[2];
      const Vec3 a = p[c.i] - p[c.j], b = p[c.k] - p[c.j];
      ranks.push_back({static_cast<int>(q), {b, -a - b, a}, 0.5 * k_shear});
    }
    if (k_fold > 0)
      for (size_t q = 0; q < shears.size(); ++q) {
        const auto& c = shears[q];
        const auto t = forces::fold_guard(p[c.k], p[c.j], p[c.i], corner_normal[q], r_course * r_wale, options.fold_area, k_fold);
        if (!t.active) continue;
        f[c.k] += t.force[0];
        f[c.j] += t.force[1];
        f[c.i] += t.force[2];
        ranks.push_back({static_cast<int>(q), {t.gradient[2], t.gradient[1], t.gradient[0]}, k_fold / (r_course * r_wale)});
      }
    for (const auto& c : struts) {
      const int slot = static_cast<int>(pairs.size());
      const auto t = forces::wale_strut(p[c.i], p[c.j], p[c.k], r_wale, options.k_wale);
      f[c.i] += t.force_i;
      f[c.k] -= t.force_i;
      // The spring between i and k with its rest frozen at this state, definite part only.
      const Vec3 w = p[c.i] - p[c.k];
      const double d = std::max(w.norm(), 1e-12);
      const double r = std::max(r_wale, (p[c.i] - p[c.j]).norm() + (p[c.k] - p[c.j]).norm());
      const Vec3 u = w / d;
      const Mat3 uu = u * u.transpose();
      pairs.push_back({c.i, c.k, slot, -options.k_wale * (std::max(1 / r - 1 / d, 0.0) * (Mat3::Identity() - uu) + (1 / r) * uu)});
    }
  }

  /// Baraff & Witkin 1998's constraint filter, as a basis of each vertex's free directions: two tangents of
  /// the surface; one, along the border, for a border vertex; none for a border vertex without two border
  /// neighbours. A missing direction is a zero column.
  std::vector<Basis> free_directions() const {
    std::vector<Basis> T(x.size());
#pragma omp parallel for schedule(static)
    for (size_t v = 0; v < x.size(); ++v) {
      const Vec3 n = surface.evaluate(coords[v]).normal();
      T[v].setZero();
      if (!border[v]) {
        const Vec3 t = n.unitOrthogonal();
        T[v] << t, n.cross(t);
        continue;
      }
      const auto [a, b] = border_neighbours[v];
      if (a < 0) continue;
      Vec3 t = x[b] - x[a];
      t -= t.dot(n) * n;
      if (t.norm() > 0) T[v].col(0) = t.normalized();
    }
    return T;
  }

  /// The stiffness −∂f/∂x (definite parts) in the free directions: K = Tᵀ(−J)T, two rows per vertex, in the
  /// fixed pattern of `system`. Then (I + hK) Δy = h Tᵀf is eq. 1 restricted to the surface, Δx = TΔy.
  void fill_stiffness(const std::vector<PairBlock>& pairs, const std::vector<RankOne>& ranks, const std::vector<Basis>& T) {
    std::fill(stiffness.begin(), stiffness.end(), 0.0);
    const auto add = [&](const BlockSlot& slot, const Eigen::Matrix2d& block) {
      stiffness[slot[0]] += block(0, 0), stiffness[slot[0] + 1] += block(0, 1);
      stiffness[slot[1]] += block(1, 0), stiffness[slot[1] + 1] += block(1, 1);
    };
    for (const auto& b : pairs) {
      // The pair term adds −K to (i,i), (j,j) and +K to (i,j), (j,i) of −J.
      const auto& slot = pair_blocks[b.slot];
      add(slot[0], -T[b.i].transpose() * b.K * T[b.i]);
      add(slot[1], -T[b.j].transpose() * b.K * T[b.j]);
      add(slot[2], T[b.i].transpose() * b.K * T[b.j]);
      add(slot[3], T[b.j].transpose() * b.K * T[b.i]);
    }
    for (const auto& r : ranks) {
      const auto& c = shears[r.corner];
      const int v[3] = {c.i, c.j, c.k};
      Eigen::Vector2d g[3];
      for (int q = 0; q < 3; ++q) g[q] = T[v[q]].transpose() * r.g[q];
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) add(corner_blocks[r.corner][3 * p + q], r.c * g[p] * g[q].transpose());
    }
  }

  BlockSlot block_slot(int a, int b) const {
    const auto find = [&](int row) {
      const int* begin = system.innerIndexPtr() + system.outerIndexPtr()[row];
      const int* end = system.innerIndexPtr() + system.outerIndexPtr()[row + 1];
      return static_cast<int>(std::lower_bound(begin, end, 2 * b) - system.innerIndexPtr());
    };
    return {find(2 * a), find(2 * a + 1)};
  }

  /// Conjugate gradients (Eigen's, Jacobi-preconditioned) on (I + hK) Δy = h Tᵀf.
  int solve(double step, const std::vector<Basis>& T, const std::vector<Vec3>& f, std::vector<Vec3>& dx) {
    const size_t n = x.size();
    for (size_t q = 0; q < stiffness.size(); ++q) system.valuePtr()[q] = step * stiffness[q];
    for (const int d : diagonal) system.valuePtr()[d] += 1;
    Eigen::VectorXd rhs(2 * n);
    for (size_t v = 0; v < n; ++v) rhs.segment<2>(2 * v) = step * T[v].transpose() * f[v];
    Eigen::ConjugateGradient<SystemMatrix, Eigen::Lower | Eigen::Upper> cg;
    cg.setMaxIterations(options.cg_iterations);
    cg.setTolerance(options.cg_tolerance);
    cg.compute(system);
    const Eigen::VectorXd dy = cg.solve(rhs);
    dx.resize(n);
    for (size_t v = 0; v < n; ++v) dx[v] = T[v] * dy.segment<2>(2 * v);
    return static_cast<int>(cg.iterations());
  }
};

MeshRelaxer::MeshRelaxer(const std::vector<Vec3>& control_points, const std::vector<std::vector<int>>& control_faces, const mesh::StitchMesh& stitch,
                         const MeshRelaxOptions& options) {
  options.validate();
  const auto check = mesh::validate(stitch);
  if (!check.valid()) throw Error("", "stitch mesh", "is not valid, so it cannot be relaxed:\n" + check.summary(5));
  m = std::make_unique<Impl>(control_points, control_faces, stitch, options);
  m->projector = std::make_unique<SurfaceProjector>(m->surface, triangulate(m->surface, options.samples_per_edge));

  // Rest lengths (Yuksel §6.1): N r_wale r_course = α A, r_wale = a r_course.
  double area = 0;
  const auto& tris = m->projector->triangles();
  for (const auto& t : tris.triangles)
    area += 0.5 * (tris.positions[t[1]] - tris.positions[t[0]]).cross(tris.positions[t[2]] - tris.positions[t[0]]).norm();
  m->r_course = std::sqrt(options.alpha * area / (static_cast<double>(stitch.faces.size()) * options.aspect));
  m->r_wale = options.aspect * m->r_course;
  m->h = options.time_step > 0 ? options.time_step : 1000 * m->r_course;
  const double r = std::sqrt(m->r_course * m->r_wale);
  m->k_shear = options.k_shear / (r * r * r);
  m->k_fold = options.k_fold / r;

  // Attach every vertex; border vertices to the border. Each remembers its fine triangle for the walks.
  const auto attached = attach_stitch_mesh(stitch, *m->projector);
  m->border = attached.on_border;
  m->coords = attached.coords;
  m->x = attached.positions;
  for (size_t v = 0; v < m->x.size(); ++v) m->at.push_back({attached.coords[v], attached.triangles[v], attached.positions[v], 0});

  // Springs on every edge, with the wale or course rest length.
  const auto table = mesh::edge_table(stitch);
  std::vector<std::vector<int>> border_of(stitch.vertices.size());
  for (const auto& [key, uses] : table) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    const bool wale = stitch.faces[uses.use[0].face].is_wale(uses.use[0].local);
    m->springs.push_back({a, b, wale ? m->r_wale : m->r_course, options.k_stretch});
    if (uses.count == 1) border_of[a].push_back(b), border_of[b].push_back(a);
  }
  std::sort(m->springs.begin(), m->springs.end(), [](const Spring& p, const Spring& q) { return std::pair(p.i, p.j) < std::pair(q.i, q.j); });
  for (const auto& nb : border_of) m->border_neighbours.emplace_back(nb.size() == 2 ? nb[0] : -1, nb.size() == 2 ? nb[1] : -1);

  // Sub-quads (Yuksel Fig. 15): an increase face is one sub-quad per top edge over its bottom edge, a decrease
  // one per bottom edge under its top edge. Diagonal springs and shear at every corner.
  const double diagonal = std::hypot(m->r_course, m->r_wale);
  std::set<std::pair<int, int>> wale_edges;  // (bottom, top)
  for (const auto& f : stitch.faces) {
    const int n = f.size(), nb = f.bottom, nt = f.top();
    const auto top = [&](int j) { return f.vertex(n - 1 - j); };  // top vertices left to right
    std::vector<std::array<int, 4>> quads;
    if (nb == 1)
      for (int j = 0; j < nt; ++j) quads.push_back({f.vertex(0), f.vertex(1), top(j + 1), top(j)});
    else
      for (int i = 0; i < nb; ++i) quads.push_back({f.vertex(i), f.vertex(i + 1), top(1), top(0)});
    for (const auto& q : quads) {
      m->springs.push_back({q[0], q[2], diagonal, options.k_stretch});
      m->springs.push_back({q[1], q[3], diagonal, options.k_stretch});
      for (int c = 0; c < 4; ++c) m->shears.push_back({q[(c + 3) % 4], q[c], q[(c + 1) % 4]});
    }
    wale_edges.insert({f.vertex(0), f.vertex(n - 1)});
    wale_edges.insert({f.vertex(nb), f.vertex(nb + 1)});
  }
  for (const auto& c : m->shears) m->corner_normal.push_back(m->surface.evaluate(m->coords[c.j]).normal());
  // Wale struts (eq. 4): a wale edge i-j and the wale edge j-k of the next row.
  std::map<int, std::vector<int>> up_from;
  for (const auto& [b, t] : wale_edges) up_from[b].push_back(t);
  for (const auto& [i, j] : wale_edges) {
    const auto it = up_from.find(j);
    if (it == up_from.end()) continue;
    for (int k : it->second) m->struts.push_back({i, j, k});
  }

  // The pattern of the linear system: a 2×2 block for every vertex and every pair that a term joins.
  std::vector<Eigen::Triplet<double>> pattern;
  const auto join = [&](int a, int b) {
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) pattern.emplace_back(2 * a + r, 2 * b + c, 0.0);
  };
  for (size_t v = 0; v < m->x.size(); ++v) join(static_cast<int>(v), static_cast<int>(v));
  for (const auto& s : m->springs) join(s.i, s.j), join(s.j, s.i);
  for (const auto& c : m->struts) join(c.i, c.k), join(c.k, c.i);
  for (const auto& c : m->shears) {
    const int v[3] = {c.i, c.j, c.k};
    for (int a : v)
      for (int b : v) join(a, b);
  }
  const auto dofs = static_cast<Eigen::Index>(2 * m->x.size());
  m->system.resize(dofs, dofs);
  m->system.setFromTriplets(pattern.begin(), pattern.end());
  m->system.makeCompressed();
  m->stiffness.assign(m->system.nonZeros(), 0.0);
  for (int d = 0; d < dofs; ++d) m->diagonal.push_back(m->block_slot(d / 2, d / 2)[d % 2] + d % 2);
  for (const auto& s : m->springs) m->pair_blocks.push_back({m->block_slot(s.i, s.i), m->block_slot(s.j, s.j), m->block_slot(s.i, s.j), m->block_slot(s.j, s.i)});
  for (const auto& c : m->struts) m->pair_blocks.push_back({m->block_slot(c.i, c.i), m->block_slot(c.k, c.k), m->block_slot(c.i, c.k), m->block_slot(c.k, c.i)});
  for (const auto& c : m->shears) {
    const int v[3] = {c.i, c.j, c.k};
    auto& blocks = m->corner_blocks.emplace_back();
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) blocks[3 * p + q] = m->block_slot(v[p], v[q]);
  }
  m->current_energy = m->energy(m->x);
}

MeshRelaxer::~MeshRelaxer() = default;

double MeshRelaxer::energy() const { return m->current_energy; }

MeshRelaxStep MeshRelaxer::step() {
  std::vector<Vec3> f, dx, next(m->x.size());
  std::vector<PairBlock> pairs;
  std::vector<RankOne> ranks;
  m->assemble(m->x, f, pairs, ranks);
  const auto T = m->free_directions();
  m->fill_stiffness(pairs, ranks, T);
  const double e0 = m->current_energy;
  MeshRelaxStep out;
  out.step = ++m->steps_done;
  std::vector<Attachment> moved(m->x.size());
  double step = m->h;
  for (int attempt = 0; attempt < 12; ++attempt, step *= 0.5) {
    out.cg_iterations = m->solve(step, T, f, dx);  // eq. 1: (I − h ∂f/∂x) Δx = h f0, in the free directions
    const double limit = m->options.max_move * m->r_course;
    // Every vertex moves on its own: the loop splits across threads without changing the result.
#pragma omp parallel for schedule(static)
    for (size_t v = 0; v < dx.size(); ++v) {
      if (dx[v].norm() > limit) dx[v] *= limit / dx[v].norm();
      moved[v] = m->projector->move(m->at[v], m->x[v] + dx[v], m->border[v]);
      next[v] = moved[v].position;
    }
    const double e1 = m->energy(next);
    if (e1 <= e0) {
      out.energy = e1;
      out.time_step = step;
      out.max_displacement = 0;
      for (size_t v = 0; v < next.size(); ++v) out.max_displacement = std::max(out.max_displacement, (next[v] - m->x[v]).norm());
      m->x = next;
      m->current_energy = e1;
      m->at = moved;
      for (size_t v = 0; v < moved.size(); ++v) m->coords[v] = moved[v].coord;
      return out;
    }
  }
  out.energy = e0;  // no step lowers the energy: a minimum, as far as this solver can tell
  out.time_step = 0;
  return out;
}

MeshRelaxReport MeshRelaxer::run(const std::function<void(const MeshRelaxStep&)>& on_step) {
  MeshRelaxReport report;
  report.r_course = m->r_course;
  report.r_wale = m->r_wale;
  report.initial_energy = energy();
  report.turned_over_before = turned_over();
  for (int s = 0; s < m->options.max_steps; ++s) {
    const MeshRelaxStep st = step();
    report.steps.push_back(st);
    if (on_step) on_step(st);
    if (st.max_displacement < m->options.tolerance * m->r_course) {
      report.converged = true;
      break;
    }
    if (m->options.interrupt && m->options.interrupt->load()) break;
  }
  if (m->options.max_steps == 0) report.converged = false;
  report.turned_over_after = turned_over();
  return report;
}

const std::vector<Vec3>& MeshRelaxer::positions() const { return m->x; }
const std::vector<SurfaceCoord>& MeshRelaxer::coords() const { return m->coords; }
const std::vector<char>& MeshRelaxer::on_border() const { return m->border; }
const SubdivSurface& MeshRelaxer::surface() const { return m->surface; }
double MeshRelaxer::r_course() const { return m->r_course; }
double MeshRelaxer::r_wale() const { return m->r_wale; }

int MeshRelaxer::turned_over() const {
  int n = 0;
  for (const auto& f : m->stitch.faces) {
    Vec3 normal = Vec3::Zero();
    for (int k = 0; k < f.size(); ++k) normal += m->x[f.vertex(k)].cross(m->x[f.vertex(k + 1)]);
    n += normal.dot(m->surface.evaluate(m->coords[f.vertex(0)]).normal()) <= 0;
  }
  return n;
}

mesh::StitchMesh MeshRelaxer::relaxed() const {
  mesh::StitchMesh out = m->stitch;
  out.vertices = m->x;
  return out;
}

FaceStretch face_stretch(const mesh::StitchMesh& stitch, double r_course, double r_wale) {
  FaceStretch out;
  for (const auto& f : stitch.faces) {
    double strain = 0;
    Vec3 normal = Vec3::Zero();
    for (int k = 0; k < f.size(); ++k) {
      const Vec3 &a = stitch.vertices[f.vertex(k)], &b = stitch.vertices[f.vertex(k + 1)];
      strain += (b - a).norm() / (f.is_wale(k) ? r_wale : r_course) - 1;
      normal += a.cross(b);
    }
    out.edge_strain.push_back(strain / f.size());
    out.area_strain.push_back(0.5 * normal.norm() / (std::max(f.bottom, f.top()) * r_course * r_wale) - 1);
  }
  return out;
}

}  // namespace skein::surface
