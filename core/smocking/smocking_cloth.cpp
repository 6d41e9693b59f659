#include "smocking/smocking_cloth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

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

/// Pairs of elements (point-triangle, edge-edge) that share no vertex and lie within `radius` at x.
std::vector<Pair> near_pairs(const Fabric& f, const Eigen::Matrix3Xd& x, double radius) {
  std::vector<Pair> pairs;
  double cell = radius;
  for (const auto& e : f.edges) cell = std::max(cell, (x.col(e[0]) - x.col(e[1])).norm());
  BoxGrid tri_grid(cell), edge_grid(cell);
  const Vec3 pad = Vec3::Constant(radius);
  for (int t = 0; t < static_cast<int>(f.tris.size()); ++t) {
    const auto& tr = f.tris[t];
    tri_grid.insert(t, x.col(tr[0]).cwiseMin(x.col(tr[1])).cwiseMin(x.col(tr[2])), x.col(tr[0]).cwiseMax(x.col(tr[1])).cwiseMax(x.col(tr[2])));
  }
  for (int e = 0; e < static_cast<int>(f.edges.size()); ++e)
    edge_grid.insert(e, x.col(f.edges[e][0]).cwiseMin(x.col(f.edges[e][1])), x.col(f.edges[e][0]).cwiseMax(x.col(f.edges[e][1])));
  std::vector<int> seen;
  for (int v = 0; v < f.n; ++v) {
    const Vec3 p = x.col(v);
    seen.clear();
    tri_grid.query(p - pad, p + pad, [&](int t) { seen.push_back(t); });
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    for (int t : seen) {
      const auto& tr = f.tris[t];
      if (tr[0] == v || tr[1] == v || tr[2] == v) continue;
      const Vec3 b = closest_on_triangle(p, x.col(tr[0]), x.col(tr[1]), x.col(tr[2]));
      const Vec3 q = b[0] * x.col(tr[0]) + b[1] * x.col(tr[1]) + b[2] * x.col(tr[2]);
      if ((p - q).norm() < radius) pairs.push_back({{v, tr[0], tr[1], tr[2]}, {1, -b[0], -b[1], -b[2]}});
    }
  }
  for (int e = 0; e < static_cast<int>(f.edges.size()); ++e) {
    const auto [a0, a1] = f.edges[e];
    seen.clear();
    edge_grid.query(x.col(a0).cwiseMin(x.col(a1)) - pad, x.col(a0).cwiseMax(x.col(a1)) + pad, [&](int g) { if (g > e) seen.push_back(g); });
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    for (int g : seen) {
      const auto [b0, b1] = f.edges[g];
      if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) continue;
      const auto [s, t] = closest_on_segments(x.col(a0), x.col(a1), x.col(b0), x.col(b1));
      const Vec3 r = (1 - s) * x.col(a0) + s * x.col(a1) - (1 - t) * x.col(b0) - t * x.col(b1);
      if (r.norm() < radius) pairs.push_back({{a0, a1, b0, b1}, {1 - s, s, -(1 - t), -t}, true});
    }
  }
  return pairs;
}

Vec3 difference(const Pair& p, const Eigen::Matrix3Xd& x) {
  Vec3 r = Vec3::Zero();
  for (int k = 0; k < 4; ++k) r += p.w[k] * x.col(p.v[k]);
  return r;
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
/// w_s eq. 10 + barrier. `grad` and `hessian` (PSD: each spring's and pair's part projected) when asked.
struct Potential {
  const Fabric& f;
  const ClothOptions& o;
  Barrier barrier;
  Eigen::Matrix3Xd anchor;  ///< the frame's start

  double energy(const Eigen::Matrix3Xd& x, const std::vector<Pair>& pairs, Eigen::Matrix3Xd* grad, Triplets* hess) const {
    double e = 0;
    if (grad) grad->setZero(3, f.n);
    for (int v = 0; v < f.n; ++v) {
      const double mu = o.inertia * f.area[v];
      const Vec3 d = x.col(v) - anchor.col(v);
      e += 0.5 * mu * d.squaredNorm();
      if (grad) grad->col(v) += mu * d;
      if (hess)
        for (int c = 0; c < 3; ++c) hess->emplace_back(3 * v + c, 3 * v + c, mu);
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
    if (hess)
      for (int k = 0; k < f.bend.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(f.bend, k); it; ++it)
          for (int c = 0; c < 3; ++c) hess->emplace_back(3 * static_cast<int>(it.row()) + c, 3 * static_cast<int>(it.col()) + c, o.k_bend * it.value());
    for (std::size_t i = 0; i < f.guided.size(); ++i) {  // eq. 11
      const int v = f.guided[i];
      const Vec3 d = x.col(v) - f.targets.col(static_cast<Eigen::Index>(i));
      e += o.w_pos * d.squaredNorm();
      if (grad) grad->col(v) += 2 * o.w_pos * d;
      if (hess)
        for (int c = 0; c < 3; ++c) hess->emplace_back(3 * v + c, 3 * v + c, 2 * o.w_pos);
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

/// The largest step fraction along `dir` after which no pair of `pairs` has come closer than a tenth of its
/// distance at x: a pair's distance falls at most as fast as its two elements' fastest vertices move together
/// (each point of an element is a convex combination of its vertices), so this bound is conservative.
double collision_bound(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& dir, const std::vector<Pair>& pairs) {
  double alpha = 1;
  for (const auto& p : pairs) {
    const double d0 = difference(p, x).norm();
    double first = 0, second = 0;  // the point or first edge's fastest vertex; the other element's
    for (int k = 0; k < 4; ++k) {
      const bool first_element = k == 0 || (k == 1 && p.edges);
      const double speed = dir.col(p.v[k]).norm();
      (first_element ? first : second) = std::max(first_element ? first : second, speed);
    }
    const double closing = first + second;
    if (closing > 0) alpha = std::min(alpha, 0.9 * d0 / closing);
  }
  return alpha;
}

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
  if (subdivisions < 2 || subdivisions > 32 || subdivisions % 2) throw Error("", "subdivisions", "must be even, 2 to 32 (stitch midpoints must be fine vertices)");
  for (const auto& [name, value] : {std::pair{"k_stretch", k_stretch}, {"k_bend", k_bend}, {"w_pos", w_pos}, {"w_sew", w_sew}, {"inertia", inertia}, {"k_barrier", k_barrier}})
    if (!(value > 0) || !std::isfinite(value)) throw Error("", name, "must be a positive number");
  if (frames < 1 || newton_per_frame < 1) throw Error("", "frames", "frames and Newton steps per frame must be at least 1");
  if (!(tolerance > 0)) throw Error("", "tolerance", "must be positive");
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

Cloth smock_cloth(const SmockingPattern& pattern, const Embedding& embedding, const Lift& lift, const ClothOptions& options) {
  options.validate();
  Cloth cloth;
  const Fabric f = build_fabric(pattern, embedding, lift, options.subdivisions, cloth.grid_vertex, cloth.rest);
  const double h = pattern.spacing / options.subdivisions;
  cloth.reach = barrier_reach(pattern, embedding, options);
  for (const auto& t : f.tris) cloth.triangles.push_back(t);
  Potential potential{f, options, Barrier{cloth.reach, options.k_barrier}, cloth.rest};
  Eigen::Matrix3Xd x = cloth.rest;
  const double max_move = 4 * h, settled = options.tolerance * h;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  for (int frame = 0; frame < options.frames; ++frame) {
    potential.anchor = x;
    ++cloth.frames;
    for (int it = 0; it < options.newton_per_frame; ++it) {
      const auto pairs = near_pairs(f, x, cloth.reach);
      Eigen::Matrix3Xd grad;
      Triplets hess;
      const double e0 = potential.energy(x, pairs, &grad, &hess);
      if (!std::isfinite(e0)) throw Error(pattern.name, "frame " + std::to_string(frame), "the fabric's energy is not finite (a bug: please report it)");
      Eigen::SparseMatrix<double> hm(3 * f.n, 3 * f.n);
      hm.setFromTriplets(hess.begin(), hess.end());
      solver.compute(hm);
      if (solver.info() != Eigen::Success) throw Error(pattern.name, "frame " + std::to_string(frame), "the Newton system could not be factored");
      const Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXd>(grad.data(), grad.size());
      Eigen::VectorXd step = -solver.solve(g);
      Eigen::Matrix3Xd dir = Eigen::Map<Eigen::Matrix3Xd>(step.data(), 3, f.n);
      const double largest = dir.colwise().norm().maxCoeff();
      ++cloth.newton_iterations;
      if (largest < settled) break;
      if (largest > max_move) dir *= max_move / largest;
      const double reach = 2 * std::min(largest, max_move) + 1e-9;
      double alpha = collision_bound(x, dir, near_pairs(f, x, reach));
      if (alpha < 1) ++cloth.ccd_limited_steps;
      const double slope = (grad.array() * dir.array()).sum();
      double e1 = e0;
      Eigen::Matrix3Xd trial;
      for (int halving = 0; halving < 30; ++halving, alpha *= 0.5) {
        trial = x + alpha * dir;
        e1 = potential.energy(trial, near_pairs(f, trial, cloth.reach), nullptr, nullptr);
        if (e1 <= e0 + 1e-4 * alpha * slope) break;
      }
      if (!(e1 <= e0)) break;  // no descent left along this direction: the frame has settled
      x = trial;
    }
    const double moved = (x - potential.anchor).colwise().norm().maxCoeff();
    if (moved < settled) break;
  }
  cloth.positions = x;
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
