#include "smocking/smocking_cloth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <Eigen/CholmodSupport>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <dlfcn.h>
#include <omp.h>

#include "common/closest_points.hpp"
#include "common/error.hpp"

namespace skein::smocking {
namespace {

using Vec3 = Eigen::Vector3d;
using Triplets = std::vector<Eigen::Triplet<double>>;

/// A pair of mesh elements near each other: a point and a triangle, or two edges. Their closest points' difference
/// is r = sum_k w_k x_k over the four vertices, with the closest points' weights held fixed (Danskin: the distance's
/// gradient at the closest points is that of |r|).
struct Pair {
  std::array<int, 4> v{};
  std::array<double, 4> w{};
  bool edges = false;  ///< two edges (vertices 0, 1 and 2, 3), or a point (0) and a triangle (1, 2, 3)
};

/// A uniform grid of boxes, for the pairs within a distance (broad phase).
class BoxGrid {
public:
  explicit BoxGrid(double cell) : m_cell(cell) {}
  void insert(int id, const Vec3& lo, const Vec3& hi) {
    each_cell(lo, hi, [&](long long key) { m_cells[key].push_back(id); });
  }
  template <class F> void query(const Vec3& lo, const Vec3& hi, F&& f) const {
    each_cell(lo, hi, [&](long long key) {
      const auto it = m_cells.find(key);
      if (it != m_cells.end())
        for (int id : it->second) f(id);
    });
  }

private:
  template <class F> void each_cell(const Vec3& lo, const Vec3& hi, F&& f) const {
    const auto at = [&](double x) { return static_cast<long long>(std::floor(x / m_cell)); };
    for (long long i = at(lo.x()); i <= at(hi.x()); ++i)
      for (long long j = at(lo.y()); j <= at(hi.y()); ++j)
        for (long long k = at(lo.z()); k <= at(hi.z()); ++k) f(((i * 73856093LL) ^ (j * 19349663LL) ^ (k * 83492791LL)));
  }
  double m_cell;
  std::unordered_map<long long, std::vector<int>> m_cells;
};

/// The fine fabric and its constant parts.
struct Fabric {
  int n = 0;  ///< vertices
  std::vector<std::array<int, 3>> tris;
  std::vector<std::array<int, 2>> edges;
  std::vector<double> rest_length, area;  ///< per edge; per vertex (lumped)
  Eigen::SparseMatrix<double> bend;       ///< K = L_int^T A^-1 L_int (cotangent Laplacian of the flat fabric, inner rows)
  std::vector<int> guided;                ///< vertices held toward targets (eq. 11)
  Eigen::Matrix3Xd targets;
  std::vector<std::array<int, 2>> sewn;   ///< eq. 10's stitches (fine vertices)
  std::vector<double> sewn_length;
};

/// Point-triangle and edge-edge pairs that share no vertex and whose boxes overlap (broad phase): each element's
/// box spans its vertices at x and, with `dir`, at x + dir (the box swept over a step), padded by `pad`. Calls
/// f(true, v, t) for point v and triangle t, f(false, e, g) for edges e < g; each pair once.
template <class F>
void candidate_pairs(const Fabric& f, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd* dir, double pad, F&& found) {
  const auto box = [&](std::initializer_list<int> vs, Vec3& lo, Vec3& hi) {
    lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    for (int v : vs) {
      lo = lo.cwiseMin(x.col(v));
      hi = hi.cwiseMax(x.col(v));
      if (dir) {
        lo = lo.cwiseMin(x.col(v) + dir->col(v));
        hi = hi.cwiseMax(x.col(v) + dir->col(v));
      }
    }
    lo.array() -= pad;
    hi.array() += pad;
  };
  const int tris = static_cast<int>(f.tris.size()), edges = static_cast<int>(f.edges.size());
  std::vector<Vec3> tri_lo(tris), tri_hi(tris), edge_lo(edges), edge_hi(edges);
  double cell = 0;
  for (int t = 0; t < tris; ++t) {
    box({f.tris[t][0], f.tris[t][1], f.tris[t][2]}, tri_lo[t], tri_hi[t]);
    cell = std::max(cell, (tri_hi[t] - tri_lo[t]).maxCoeff());
  }
  for (int e = 0; e < edges; ++e) box({f.edges[e][0], f.edges[e][1]}, edge_lo[e], edge_hi[e]);
  BoxGrid tri_grid(cell), edge_grid(cell);
  for (int t = 0; t < tris; ++t) tri_grid.insert(t, tri_lo[t], tri_hi[t]);
  for (int e = 0; e < edges; ++e) edge_grid.insert(e, edge_lo[e], edge_hi[e]);
  const auto overlap = [](const Vec3& alo, const Vec3& ahi, const Vec3& blo, const Vec3& bhi) {
    return (alo.array() <= bhi.array()).all() && (blo.array() <= ahi.array()).all();
  };
  std::vector<int> stamp(std::max(tris, edges), -1);  // the last query that saw an element (a box spans cells)
  for (int v = 0; v < f.n; ++v) {
    Vec3 lo, hi;
    box({v}, lo, hi);
    tri_grid.query(lo, hi, [&](int t) {
      if (stamp[t] == v) return;
      stamp[t] = v;
      const auto& tr = f.tris[t];
      if (tr[0] != v && tr[1] != v && tr[2] != v && overlap(lo, hi, tri_lo[t], tri_hi[t])) found(true, v, t);
    });
  }
  std::fill(stamp.begin(), stamp.end(), -1);
  for (int e = 0; e < edges; ++e)
    edge_grid.query(edge_lo[e], edge_hi[e], [&](int g) {
      if (g <= e || stamp[g] == e) return;
      stamp[g] = e;
      const auto [a0, a1] = f.edges[e];
      const auto [b0, b1] = f.edges[g];
      if (a0 != b0 && a0 != b1 && a1 != b0 && a1 != b1 && overlap(edge_lo[e], edge_hi[e], edge_lo[g], edge_hi[g])) found(false, e, g);
    });
}

/// The pair of elements (point v and triangle t, or edges e and g) with its closest points' weights at x.
Pair closest_pair(const Fabric& f, const Eigen::Matrix3Xd& x, bool point_triangle, int a, int b) {
  if (point_triangle) {
    const auto& tr = f.tris[b];
    const Vec3 w = closest_on_triangle(x.col(a), x.col(tr[0]), x.col(tr[1]), x.col(tr[2]));
    return {{a, tr[0], tr[1], tr[2]}, {1, -w[0], -w[1], -w[2]}};
  }
  const auto [a0, a1] = f.edges[a];
  const auto [b0, b1] = f.edges[b];
  const auto [s, t] = closest_on_segments(x.col(a0), x.col(a1), x.col(b0), x.col(b1));
  return {{a0, a1, b0, b1}, {1 - s, s, -(1 - t), -t}, true};
}

Vec3 difference(const Pair& p, const Eigen::Matrix3Xd& x) {
  Vec3 r = Vec3::Zero();
  for (int k = 0; k < 4; ++k) r += p.w[k] * x.col(p.v[k]);
  return r;
}

/// A pair of elements that may come within the barrier's reach over a step: point a and triangle b, or edges a, b.
struct Candidate {
  bool point_triangle;
  int a, b;
};

/// The pairs whose boxes, swept from x over x + dir (none: at x alone), come within `reach` of each other: every
/// pair that comes within `reach` anywhere on the step's straight path is among them.
std::vector<Candidate> step_candidates(const Fabric& f, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd* dir, double reach) {
  std::vector<Candidate> found;
  candidate_pairs(f, x, dir, 0.5 * reach, [&](bool point_triangle, int a, int b) { found.push_back({point_triangle, a, b}); });
  return found;
}

/// Of the candidates, the pairs within `radius` at x.
std::vector<Pair> pairs_within(const Fabric& f, const Eigen::Matrix3Xd& x, const std::vector<Candidate>& candidates, double radius) {
  std::vector<Pair> pairs;
  for (const auto& c : candidates) {
    const Pair p = closest_pair(f, x, c.point_triangle, c.a, c.b);
    if (difference(p, x).norm() < radius) pairs.push_back(p);
  }
  return pairs;
}

/// Pairs of elements (point-triangle, edge-edge) that share no vertex and lie within `radius` at x.
std::vector<Pair> near_pairs(const Fabric& f, const Eigen::Matrix3Xd& x, double radius) {
  return pairs_within(f, x, step_candidates(f, x, nullptr, radius), radius);
}

/// IPC's log barrier b(d) = -κ (d - d̂)² ln(d / d̂) below d̂, and its first two derivatives.
struct Barrier {
  double reach, k;
  double value(double d) const { return d >= reach ? 0 : -k * (d - reach) * (d - reach) * std::log(d / reach); }
  double d1(double d) const { return d >= reach ? 0 : -k * (2 * (d - reach) * std::log(d / reach) + (d - reach) * (d - reach) / d); }
  double d2(double d) const {
    return d >= reach ? 0 : -k * (2 * std::log(d / reach) + 4 * (d - reach) / d - (d - reach) * (d - reach) / (d * d));
  }
};

/// The incremental potential of one frame (eq. 9 with our fabric terms): proximal + stretch + bend + w_p eq. 11 +
/// w_s eq. 10 + barrier. `grad` when asked; `hess` gets the Hessian of the terms that change with x (PSD: each
/// spring's and pair's part projected), constant_hessian() that of the quadratic ones.
struct Potential {
  const Fabric& f;
  const ClothOptions& o;
  Barrier barrier;
  Eigen::Matrix3Xd anchor;  ///< the frame's start

  /// The Hessian of the proximal term, the bending and eq. 11: the same at every x.
  void constant_hessian(Triplets& hess) const {
    for (int v = 0; v < f.n; ++v)
      for (int c = 0; c < 3; ++c) hess.emplace_back(3 * v + c, 3 * v + c, o.inertia * f.area[v]);
    for (int k = 0; k < f.bend.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(f.bend, k); it; ++it)
        for (int c = 0; c < 3; ++c) hess.emplace_back(3 * static_cast<int>(it.row()) + c, 3 * static_cast<int>(it.col()) + c, o.k_bend * it.value());
    for (int v : f.guided)
      for (int c = 0; c < 3; ++c) hess.emplace_back(3 * v + c, 3 * v + c, 2 * o.w_pos);
  }

  double energy(const Eigen::Matrix3Xd& x, const std::vector<Pair>& pairs, Eigen::Matrix3Xd* grad, Triplets* hess) const {
    double e = 0;
    if (grad) grad->setZero(3, f.n);
    for (int v = 0; v < f.n; ++v) {
      const double mu = o.inertia * f.area[v];
      const Vec3 d = x.col(v) - anchor.col(v);
      e += 0.5 * mu * d.squaredNorm();
      if (grad) grad->col(v) += mu * d;
    }
    const auto spring = [&](int a, int b, double rest, double k) {  // k/2 (l - L)^2 / L
      const Vec3 d = x.col(a) - x.col(b);
      const double l = d.norm();
      if (!(l > 0)) return;
      e += 0.5 * k * (l - rest) * (l - rest) / rest;
      const Vec3 u = d / l;
      if (grad) {
        const Vec3 g = k * (l - rest) / rest * u;
        grad->col(a) += g;
        grad->col(b) -= g;
      }
      if (hess) {
        const Eigen::Matrix3d h = k / rest * (u * u.transpose() + std::max(0.0, 1 - rest / l) * (Eigen::Matrix3d::Identity() - u * u.transpose()));
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) {
            hess->emplace_back(3 * a + r, 3 * a + c, h(r, c));
            hess->emplace_back(3 * b + r, 3 * b + c, h(r, c));
            hess->emplace_back(3 * a + r, 3 * b + c, -h(r, c));
            hess->emplace_back(3 * b + r, 3 * a + c, -h(r, c));
          }
      }
    };
    for (std::size_t i = 0; i < f.edges.size(); ++i) spring(f.edges[i][0], f.edges[i][1], f.rest_length[i], o.k_stretch);
    for (std::size_t i = 0; i < f.sewn.size(); ++i) spring(f.sewn[i][0], f.sewn[i][1], std::max(f.sewn_length[i], 1e-6), o.w_sew);
    // Bending: k_b/2 sum over x, y, z of x_c^T K x_c.
    for (int c = 0; c < 3; ++c) {
      const Eigen::VectorXd xc = x.row(c).transpose();
      const Eigen::VectorXd kx = f.bend * xc;
      e += 0.5 * o.k_bend * xc.dot(kx);
      if (grad) grad->row(c) += o.k_bend * kx.transpose();
    }
    for (std::size_t i = 0; i < f.guided.size(); ++i) {  // eq. 11
      const int v = f.guided[i];
      const Vec3 d = x.col(v) - f.targets.col(static_cast<Eigen::Index>(i));
      e += o.w_pos * d.squaredNorm();
      if (grad) grad->col(v) += 2 * o.w_pos * d;
    }
    for (const auto& p : pairs) {
      const Vec3 r = difference(p, x);
      const double d = r.norm();
      if (!(d > 0)) return std::numeric_limits<double>::infinity();
      e += barrier.value(d);
      const Vec3 n = r / d;
      if (grad)
        for (int k = 0; k < 4; ++k) grad->col(p.v[k]) += barrier.d1(d) * p.w[k] * n;
      if (hess) {
        const Eigen::Matrix3d nn = barrier.d2(d) * n * n.transpose();  // the PSD part: b'' grad d grad d^T
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b)
            for (int r2 = 0; r2 < 3; ++r2)
              for (int c = 0; c < 3; ++c) hess->emplace_back(3 * p.v[a] + r2, 3 * p.v[b] + c, p.w[a] * p.w[b] * nn(r2, c));
      }
    }
    return e;
  }
};

/// additive_ccd of the pair (point v and triangle t, or edges e and g) of the fabric.
double pair_ccd(const Fabric& f, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& dir, bool point_triangle, int a, int b) {
  std::array<int, 4> v;
  if (point_triangle) v = {a, f.tris[b][0], f.tris[b][1], f.tris[b][2]};
  else v = {f.edges[a][0], f.edges[a][1], f.edges[b][0], f.edges[b][1]};
  std::array<Vec3, 4> y, p;
  for (int k = 0; k < 4; ++k) y[k] = x.col(v[k]), p[k] = dir.col(v[k]);
  return additive_ccd(y, p, point_triangle);
}

/// The largest step fraction along the step `dir` after which none of the candidates has come closer than a tenth of
/// its distance at x (additive_ccd).
double collision_bound(const Fabric& f, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& dir, const std::vector<Candidate>& candidates) {
  double alpha = 1;
  for (const auto& c : candidates) alpha = std::min(alpha, pair_ccd(f, x, dir, c.point_triangle, c.a, c.b));
  return alpha;
}

/// The Newton system H d = -g of the fabric, solved by CHOLMOD's supernodal Cholesky factorization. The unknowns
/// are put once in a fill-reducing order (METIS's nested dissection or AMD, whichever fills less) of the pattern
/// without contact; the barrier's pairs add few entries to it, so the order is kept and each new pattern costs only
/// a symbolic analysis. The Hessian's constant part (proximal, bending, eq. 11) is assembled once.
class NewtonSystem {
public:
  NewtonSystem(const Potential& potential, const Eigen::Matrix3Xd& x) : m_size(3 * x.cols()) {
    // OpenBLAS's threaded builds spin in sched_yield between calls: where one is the system's BLAS, one thread.
    if (auto* set_threads = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set_threads(1);
    Triplets constant, varying;
    potential.constant_hessian(constant);
    Eigen::Matrix3Xd grad;
    potential.energy(x, {}, &grad, &varying);  // the springs' pattern
    m_order = fill_reducing_order(constant, varying);
    m_position.resize(m_order.size());
    for (std::size_t k = 0; k < m_order.size(); ++k) m_position[m_order[k]] = static_cast<int>(k);
    m_constant = assemble(constant);
    m_solver.cholmod().nmethods = 1;
    m_solver.cholmod().method[0].ordering = CHOLMOD_NATURAL;  // already ordered
    m_solver.cholmod().print = 0;                             // a breakdown is handled below, not printed
  }

  /// The Newton step for the gradient `grad` and the varying part of the Hessian, and the diagonal shift it took
  /// (0 but where the factorization broke down); false when H cannot be factored.
  bool solve(Triplets& varying, const Eigen::Matrix3Xd& grad, Eigen::Matrix3Xd& step, double& shift) {
    Eigen::SparseMatrix<double> h = m_constant + assemble(varying);
    const bool same_pattern = h.nonZeros() == m_analysed.nonZeros() &&
                              std::equal(h.outerIndexPtr(), h.outerIndexPtr() + h.cols() + 1, m_analysed.outerIndexPtr()) &&
                              std::equal(h.innerIndexPtr(), h.innerIndexPtr() + h.nonZeros(), m_analysed.innerIndexPtr());
    if (!same_pattern) {
      m_solver.analyzePattern(h);
      m_analysed = h;
    }
    // H is positive definite in exact arithmetic (every term's part projected, the proximal term on the
    // diagonal), but a pair pressed to micrometres gives the barrier a curvature 10^15 times the fabric's, and the
    // factorization can break down in rounding. Then the diagonal is raised a little (Levenberg), as often as
    // needed, so the step shortens toward the gradient's instead of stopping the run.
    shift = 0;
    for (int attempt = 0;; ++attempt) {
      const int levels = omp_get_max_active_levels();
      omp_set_max_active_levels(0);  // CHOLMOD's small OpenMP regions cost more in wake-ups than they save
      m_solver.factorize(h);
      omp_set_max_active_levels(levels);
      if (m_solver.info() == Eigen::Success) break;
      if (attempt == 12) return false;
      double largest = 0;
      for (Eigen::Index k = 0; k < m_size; ++k) largest = std::max(largest, std::abs(h.coeff(k, k)));
      const double raise = shift == 0 ? 1e-10 * largest : 9 * shift;  // the total shift grows tenfold each time
      for (Eigen::Index k = 0; k < m_size; ++k) h.coeffRef(k, k) += raise;
      shift += raise;
    }
    Eigen::VectorXd g(m_size);
    for (Eigen::Index k = 0; k < m_size; ++k) g[k] = grad.data()[m_order[k]];
    const Eigen::VectorXd solved = m_solver.solve(g);
    step.resize(3, m_size / 3);
    for (Eigen::Index k = 0; k < m_size; ++k) step.data()[m_order[k]] = -solved[k];
    return true;
  }

private:
  /// The upper triangle (CHOLMOD's supernodal factorization reads it without a transpose), in the solver's order.
  Eigen::SparseMatrix<double> assemble(Triplets& entries) const {
    std::erase_if(entries, [](const auto& t) { return t.row() > t.col(); });
    if (!m_position.empty())
      for (auto& t : entries) {
        const int r = m_position[t.row()], c = m_position[t.col()];
        t = {std::min(r, c), std::max(r, c), t.value()};
      }
    Eigen::SparseMatrix<double> m(m_size, m_size);
    m.setFromTriplets(entries.begin(), entries.end());
    return m;
  }

  /// new unknown k = old unknown order[k]
  std::vector<int> fill_reducing_order(Triplets constant, Triplets varying) const {
    constant.insert(constant.end(), varying.begin(), varying.end());
    const Eigen::SparseMatrix<double> upper = assemble(constant);
    cholmod_common common;
    cholmod_start(&common);
    common.nmethods = 2;
    common.method[0].ordering = CHOLMOD_METIS;
    common.method[1].ordering = CHOLMOD_AMD;
    cholmod_sparse a = Eigen::viewAsCholmod(upper);
    a.stype = 1;
    cholmod_factor* factor = cholmod_analyze(&a, &common);
    std::vector<int> order(static_cast<std::size_t>(m_size));
    std::iota(order.begin(), order.end(), 0);  // if both fail: the natural order, slower but right
    if (factor && common.status == CHOLMOD_OK) std::copy_n(static_cast<const int*>(factor->Perm), order.size(), order.begin());
    cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
    return order;
  }

  Eigen::Index m_size;
  std::vector<int> m_order, m_position;
  Eigen::SparseMatrix<double> m_constant, m_analysed;
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Upper> m_solver;
};

Fabric build_fabric(const SmockingPattern& pattern, const Embedding& embedding, const Lift& lift, int n, std::vector<int>& grid_vertex,
                    Eigen::Matrix3Xd& rest) {
  Fabric f;
  const int cols = (pattern.columns - 1) * n + 1, rows = (pattern.rows - 1) * n + 1;
  f.n = cols * rows;
  const double h = pattern.spacing / n;
  rest.resize(3, f.n);
  const auto id = [&](int i, int j) { return j * cols + i; };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) rest.col(id(i, j)) = Vec3(h * i, -h * j, 0);
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < cols; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2) f.tris.push_back({a, d, c}), f.tris.push_back({a, c, b});
      else f.tris.push_back({a, d, b}), f.tris.push_back({b, d, c});
    }
  std::map<std::pair<int, int>, int> edge_id;
  for (const auto& t : f.tris)
    for (int k = 0; k < 3; ++k) {
      const auto key = std::minmax(t[k], t[(k + 1) % 3]);
      if (edge_id.try_emplace(key, static_cast<int>(f.edges.size())).second) f.edges.push_back({key.first, key.second});
    }
  for (const auto& e : f.edges) f.rest_length.push_back((rest.col(e[0]) - rest.col(e[1])).norm());
  f.area.assign(f.n, 0);
  std::vector<std::map<int, double>> cot(f.n);  // cotangent weights
  for (const auto& t : f.tris) {
    const double a = 0.5 * (rest.col(t[1]) - rest.col(t[0])).cross(rest.col(t[2]) - rest.col(t[0])).norm();
    for (int k = 0; k < 3; ++k) {
      f.area[t[k]] += a / 3;
      const int o = t[k], p = t[(k + 1) % 3], q = t[(k + 2) % 3];  // the corner o faces edge pq
      const Vec3 u = rest.col(p) - rest.col(o), v = rest.col(q) - rest.col(o);
      const double c = 0.5 * u.dot(v) / u.cross(v).norm();
      cot[p][q] += c;
      cot[q][p] += c;
    }
  }
  std::vector<char> border(f.n, 0);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i)
      if (i == 0 || j == 0 || i == cols - 1 || j == rows - 1) border[id(i, j)] = 1;
  Triplets lt;
  int inner = 0;
  std::vector<double> inv_area;
  for (int v = 0; v < f.n; ++v) {
    if (border[v]) continue;
    double sum = 0;
    for (const auto& [u, w] : cot[v]) lt.emplace_back(inner, u, w), sum += w;
    lt.emplace_back(inner, v, -sum);
    inv_area.push_back(1 / f.area[v]);
    ++inner;
  }
  Eigen::SparseMatrix<double> l(inner, f.n);
  l.setFromTriplets(lt.begin(), lt.end());
  Eigen::SparseMatrix<double> a_inv(inner, inner);
  for (int i = 0; i < inner; ++i) a_inv.insert(i, i) = inv_area[i];
  f.bend = l.transpose() * a_inv * l;

  grid_vertex.assign(pattern.num_points(), -1);
  for (int r = 0; r < pattern.rows; ++r)
    for (int c = 0; c < pattern.columns; ++c) grid_vertex[pattern.index({c, r})] = id(c * n, r * n);
  std::map<int, Vec3> target;  // fine vertex -> lifted place (two stitches with one midpoint: their mean)
  std::map<int, int> count;
  for (std::size_t i = 0; i < lift.points.size(); ++i) {
    const int v = grid_vertex[lift.points[i]];
    target.try_emplace(v, Vec3::Zero()).first->second += lift.point_positions.col(static_cast<Eigen::Index>(i));
    ++count[v];
  }
  std::map<int, Vec3> lifted_point;
  for (std::size_t i = 0; i < lift.points.size(); ++i) lifted_point[lift.points[i]] = lift.point_positions.col(static_cast<Eigen::Index>(i));
  for (std::size_t s = 0; s < embedding.stitches.size(); ++s) {
    const auto& st = embedding.stitches[s];
    const int ca = st.a % pattern.columns, ra = st.a / pattern.columns, cb = st.b % pattern.columns, rb = st.b / pattern.columns;
    const int mid = id((ca + cb) * n / 2, (ra + rb) * n / 2);
    target.try_emplace(mid, Vec3::Zero()).first->second += lift.midpoints.col(static_cast<Eigen::Index>(s));
    ++count[mid];
    f.sewn.push_back({grid_vertex[st.a], grid_vertex[st.b]});
    f.sewn_length.push_back((lifted_point[st.a] - lifted_point[st.b]).norm());
  }
  f.targets.resize(3, static_cast<Eigen::Index>(target.size()));
  for (const auto& [v, sum] : target) {
    f.targets.col(static_cast<Eigen::Index>(f.guided.size())) = sum / count[v];
    f.guided.push_back(v);
  }
  return f;
}

}  // namespace

void ClothOptions::validate() const {
  if (subdivisions < 2 || subdivisions > 32 || subdivisions % 2) throw Error("", "subdivisions", "must be even, 2 to 32 (stitch midpoints must be fine vertices), found " + std::to_string(subdivisions));
  for (const auto& [name, value] : {std::pair{"k_stretch", k_stretch}, {"k_bend", k_bend}, {"w_pos", w_pos}, {"w_sew", w_sew}, {"inertia", inertia}, {"k_barrier", k_barrier}})
    if (!(value > 0) || !std::isfinite(value)) throw Error("", name, "must be a positive number");
  if (frames < 1 || newton_per_frame < 1) throw Error("", "frames", "frames and Newton steps per frame must be at least 1");
  if (!(tolerance > 0)) throw Error("", "tolerance", "must be positive");
  if (!(k_barrier_max >= 1) || !std::isfinite(k_barrier_max)) throw Error("", "k_barrier_max", "must be a number of at least 1");
}

double barrier_reach(const SmockingPattern& pattern, const Embedding& embedding, const ClothOptions& options) {
  return options.reach > 0 ? options.reach : std::min(embedding.thickness, 0.5 * pattern.spacing / options.subdivisions);
}

double first_frame_potential(const SmockingPattern& pattern, const Embedding& embedding, const Lift& lift, const ClothOptions& options,
                             const Eigen::Matrix3Xd& x, Eigen::Matrix3Xd* grad) {
  options.validate();
  std::vector<int> grid_vertex;
  Eigen::Matrix3Xd rest;
  const Fabric f = build_fabric(pattern, embedding, lift, options.subdivisions, grid_vertex, rest);
  if (x.cols() != f.n) throw Error(pattern.name, "", "first_frame_potential: expected " + std::to_string(f.n) + " points");
  const double reach = barrier_reach(pattern, embedding, options);
  const Potential potential{f, options, Barrier{reach, options.k_barrier}, rest};
  return potential.energy(x, near_pairs(f, x, reach), grad, nullptr);
}

Cloth smock_cloth(const SmockingPattern& pattern, const Embedding& embedding, const Lift& lift, const ClothOptions& options,
                  const std::atomic<bool>* stop) {
  options.validate();
  Cloth cloth;
  const Fabric f = build_fabric(pattern, embedding, lift, options.subdivisions, cloth.grid_vertex, cloth.rest);
  const double h = pattern.spacing / options.subdivisions;
  cloth.reach = barrier_reach(pattern, embedding, options);
  for (const auto& t : f.tris) cloth.triangles.push_back(t);
  Potential potential{f, options, Barrier{cloth.reach, options.k_barrier}, cloth.rest};
  Eigen::Matrix3Xd x = cloth.rest;
  const double max_move = 4 * h, settled = options.tolerance * h;
  NewtonSystem system(potential, x);
  std::vector<Pair> pairs = near_pairs(f, x, cloth.reach);  // the barrier's pairs at x, kept with it
  constexpr double kDeep = 0.1;                              // κ doubles when a pair closes in below kDeep d̂
  double last_closest = cloth.reach;
  for (int frame = 0; frame < options.frames; ++frame) {
    potential.anchor = x;
    ++cloth.frames;
    bool shifted = false;  // a shifted step is short because of the shift: it says nothing of having settled
    for (int it = 0; it < options.newton_per_frame; ++it) {
      if (stop && *stop) throw Error(pattern.name, "frame " + std::to_string(frame), "stopped before the fabric was finished");
      Eigen::Matrix3Xd grad;
      Triplets hess;
      const double e0 = potential.energy(x, pairs, &grad, &hess);
      if (!std::isfinite(e0)) throw Error(pattern.name, "frame " + std::to_string(frame), "the fabric's energy is not finite (a bug: please report it)");
      Eigen::Matrix3Xd dir;
      double shift = 0;
      if (!system.solve(hess, grad, dir, shift)) throw Error(pattern.name, "frame " + std::to_string(frame), "the Newton system could not be factored");
      if (shift > 0) ++cloth.shifted_steps, shifted = true;
      const double largest = dir.colwise().norm().maxCoeff();
      ++cloth.newton_iterations;
      if (largest < settled && shift == 0) break;
      if (largest > max_move) dir *= max_move / largest;
      // One broad phase a step: the pairs that may come within reach on its path, for the collision bound and for
      // the barrier at every point of the line search.
      const auto candidates = step_candidates(f, x, &dir, cloth.reach);
      double alpha = collision_bound(f, x, dir, candidates);
      if (alpha < 1) ++cloth.ccd_limited_steps;
      const double slope = (grad.array() * dir.array()).sum();
      double e1 = e0;
      Eigen::Matrix3Xd trial;
      std::vector<Pair> trial_pairs;
      for (int halving = 0; halving < 30; ++halving, alpha *= 0.5) {
        trial = x + alpha * dir;
        trial_pairs = pairs_within(f, trial, candidates, cloth.reach);
        e1 = potential.energy(trial, trial_pairs, nullptr, nullptr);
        if (e1 <= e0 + 1e-4 * alpha * slope) break;
      }
      if (!(e1 <= e0)) break;  // no descent left along this direction: the frame has settled
      x = trial;
      pairs = std::move(trial_pairs);
      // IPC's adaptive barrier stiffness (Li et al. 2020, §4.3): a pair that keeps closing in deep inside the reach
      // means the barrier is too weak for the forces pressing it; doubling κ pushes back before every step is
      // cut short by the collision bound.
      double closest = cloth.reach;
      for (const auto& p : pairs) closest = std::min(closest, difference(p, x).norm());
      if (closest < kDeep * cloth.reach && closest < last_closest)
        potential.barrier.k = std::min(2 * potential.barrier.k, options.k_barrier_max * options.k_barrier);
      last_closest = closest;
    }
    const double moved = (x - potential.anchor).colwise().norm().maxCoeff();
    if (moved < settled && !shifted) break;
  }
  cloth.positions = x;
  cloth.barrier_stiffness = potential.barrier.k;
  potential.anchor = x;
  cloth.energy = potential.energy(x, near_pairs(f, x, cloth.reach), nullptr, nullptr);
  cloth.smallest_distance = 2 * cloth.reach;
  for (const auto& p : near_pairs(f, x, 2 * cloth.reach)) cloth.smallest_distance = std::min(cloth.smallest_distance, difference(p, x).norm());
  for (std::size_t i = 0; i < f.edges.size(); ++i)
    cloth.largest_stretch = std::max(cloth.largest_stretch, (x.col(f.edges[i][0]) - x.col(f.edges[i][1])).norm() / f.rest_length[i] - 1);
  double sq = 0;
  for (std::size_t i = 0; i < f.guided.size(); ++i) sq += (x.col(f.guided[i]) - f.targets.col(static_cast<Eigen::Index>(i))).squaredNorm();
  cloth.target_error = f.guided.empty() ? 0 : std::sqrt(sq / static_cast<double>(f.guided.size()));
  return cloth;
}

double additive_ccd(const std::array<Eigen::Vector3d, 4>& x, const std::array<Eigen::Vector3d, 4>& dir, bool point_triangle) {
  // Conservative advancement on the relative motion: with the pair's common translation taken out, its distance
  // falls at most as fast as the fastest vertex of each element moves (every point of an element is a convex
  // combination of its vertices), so each advance of 0.9 d / l_p is safe; it goes on from where it got, so a
  // pair sliding past another is not held to its first distance.
  std::array<Vec3, 4> p, y = x;
  const Vec3 mean = 0.25 * (dir[0] + dir[1] + dir[2] + dir[3]);
  double first = 0, second = 0;  // the first element's fastest vertex (the point, or the first edge), the other's
  for (int k = 0; k < 4; ++k) {
    p[k] = dir[k] - mean;
    const bool first_element = k == 0 || (k == 1 && !point_triangle);
    (first_element ? first : second) = std::max(first_element ? first : second, p[k].norm());
  }
  const double lp = first + second;
  if (!(lp > 0)) return 1;
  const auto distance = [&] {
    if (point_triangle) {
      const Vec3 w = closest_on_triangle(y[0], y[1], y[2], y[3]);
      return (y[0] - w[0] * y[1] - w[1] * y[2] - w[2] * y[3]).norm();
    }
    const auto [s, t] = closest_on_segments(y[0], y[1], y[2], y[3]);
    return ((1 - s) * y[0] + s * y[1] - (1 - t) * y[2] - t * y[3]).norm();
  };
  constexpr double keep = 0.1;  // the share of its distance a pair keeps
  const double d0 = distance(), gap = keep * d0;
  double t = 0, advance = (1 - keep) * d0 / lp;
  for (int it = 0; it < 1000; ++it) {
    advance = std::min(advance, 1 - t);  // the end of the step is measured too
    for (int k = 0; k < 4; ++k) y[k] += advance * p[k];
    const double d = distance();
    if (t > 0 && d < gap) return t;
    t += advance;
    if (t >= 1) return 1;
    advance = 0.9 * d / lp;
  }
  return t;  // a thousand advances and still short of the step: stop there, conservatively
}

long exact_intersections(const Cloth& cloth) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, std::size_t, CGAL::Box_intersection_d::ID_EXPLICIT>;
  std::vector<K::Triangle_3> tris;
  std::vector<Box> boxes;
  const auto point = [&](int v) { return K::Point_3(cloth.positions(0, v), cloth.positions(1, v), cloth.positions(2, v)); };
  for (std::size_t t = 0; t < cloth.triangles.size(); ++t) {
    const auto& tr = cloth.triangles[t];
    tris.emplace_back(point(tr[0]), point(tr[1]), point(tr[2]));
    boxes.emplace_back(tris.back().bbox(), t);
  }
  long found = 0;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    const auto& ta = cloth.triangles[a.handle()];
    const auto& tb = cloth.triangles[b.handle()];
    for (int i : ta)
      for (int j : tb)
        if (i == j) return;  // neighbours share a vertex: not a crossing of the fabric through itself
    if (CGAL::do_intersect(tris[a.handle()], tris[b.handle()])) ++found;
  });
  return found;
}

}  // namespace skein::smocking
