#include "surface/subdiv_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "common/closest_points.hpp"
#include "common/error.hpp"

namespace skein::surface {
namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

namespace {
/// The point type OpenSubdiv's refiners and stencils interpolate.
struct Point {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  void Clear(void* = nullptr) { x.setZero(); }
  void AddWithWeight(const Point& src, double w) { x += w * src.x; }
};
}  // namespace

struct SubdivSurface::Impl {
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::unique_ptr<Far::PatchTable> patches;
  std::unique_ptr<Far::PatchMap> patch_map;
  std::vector<Point> points;  ///< control, refined and local points
  std::vector<int> ptex_first, ptex_count, ptex_face;
};

SubdivSurface::SubdivSurface(const std::vector<Eigen::Vector3d>& points, const std::vector<std::vector<int>>& faces, int isolation)
    : m_impl(std::make_unique<Impl>()) {
  if (faces.empty()) throw Error("", "subdivision surface", "the control mesh has no faces");
  std::vector<int> sizes, indices;
  for (const auto& f : faces) {
    if (f.size() < 3) throw Error("", "subdivision surface", "a control face has fewer than 3 corners");
    sizes.push_back(static_cast<int>(f.size()));
    indices.insert(indices.end(), f.begin(), f.end());
  }
  Far::TopologyDescriptor desc;
  desc.numVertices = static_cast<int>(points.size());
  desc.numFaces = static_cast<int>(faces.size());
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = indices.data();
  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);  // the border is a limit curve through the corners
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  m_impl->refiner.reset(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdc)));
  if (!m_impl->refiner) throw Error("", "subdivision surface", "OpenSubdiv refused the control mesh's topology");

  Far::PatchTableFactory::Options options(isolation);
  options.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  options.SetPatchPrecision<double>();
  m_impl->refiner->RefineAdaptive(options.GetRefineAdaptiveOptions());
  m_impl->patches.reset(Far::PatchTableFactory::Create(*m_impl->refiner, options));

  // Control points, then every refined level, then the end caps' local points.
  const int refined = m_impl->refiner->GetNumVerticesTotal();
  const int local = m_impl->patches->GetNumLocalPoints();
  auto& pts = m_impl->points;
  pts.resize(refined + local);
  for (size_t i = 0; i < points.size(); ++i) pts[i].x = points[i];
  Far::PrimvarRefinerReal<double> primvar(*m_impl->refiner);
  Point* src = pts.data();
  for (int level = 1; level <= m_impl->refiner->GetMaxLevel(); ++level) {
    Point* dst = src + m_impl->refiner->GetLevel(level - 1).GetNumVertices();
    primvar.Interpolate(level, src, dst);
    src = dst;
  }
  if (local > 0) m_impl->patches->GetLocalPointStencilTable<double>()->UpdateValues(pts.data(), pts.data() + refined);
  m_impl->patch_map = std::make_unique<Far::PatchMap>(*m_impl->patches);

  const Far::PtexIndices ptex(*m_impl->refiner);
  for (size_t f = 0; f < faces.size(); ++f) {
    m_impl->ptex_first.push_back(ptex.GetFaceId(static_cast<int>(f)));
    m_impl->ptex_count.push_back(faces[f].size() == 4 ? 1 : static_cast<int>(faces[f].size()));
    for (int k = 0; k < m_impl->ptex_count.back(); ++k) m_impl->ptex_face.push_back(static_cast<int>(f));
  }
}

SubdivSurface::~SubdivSurface() = default;
SubdivSurface::SubdivSurface(SubdivSurface&&) noexcept = default;
SubdivSurface& SubdivSurface::operator=(SubdivSurface&&) noexcept = default;

int SubdivSurface::num_ptex_faces() const { return static_cast<int>(m_impl->ptex_face.size()); }
int SubdivSurface::ptex_of(int face) const { return m_impl->ptex_first.at(face); }
int SubdivSurface::ptex_count(int face) const { return m_impl->ptex_count.at(face); }
int SubdivSurface::face_of_ptex(int ptex) const { return m_impl->ptex_face.at(ptex); }

SurfaceSample SubdivSurface::evaluate(const SurfaceCoord& at) const {
  if (at.ptex < 0 || at.ptex >= num_ptex_faces()) throw Error("", "ptex face " + std::to_string(at.ptex), "does not exist");
  const double u = std::clamp(at.u, 0.0, 1.0), v = std::clamp(at.v, 0.0, 1.0);
  const Far::PatchTable::PatchHandle* handle = m_impl->patch_map->FindPatch(at.ptex, u, v);
  if (!handle) throw Error("", "ptex face " + std::to_string(at.ptex), "has no patch at (" + std::to_string(u) + ", " + std::to_string(v) + ")");
  double wp[20], wu[20], wv[20];
  m_impl->patches->EvaluateBasis(*handle, u, v, wp, wu, wv);
  const Far::ConstIndexArray cvs = m_impl->patches->GetPatchVertices(*handle);
  SurfaceSample s;
  for (int i = 0; i < cvs.size(); ++i) {
    const Eigen::Vector3d& x = m_impl->points[cvs[i]].x;
    s.position += wp[i] * x;
    s.du += wu[i] * x;
    s.dv += wv[i] * x;
  }
  return s;
}

SurfaceTriangles triangulate(const SubdivSurface& surface, int n) {
  SurfaceTriangles out;
  // Weld samples that several ptex faces share (their edges), by position on a lattice far finer than the
  // samples' spacing and far coarser than the difference between two patches' evaluations of one point.
  Eigen::AlignedBox3d box;
  for (int p = 0; p < surface.num_ptex_faces(); ++p)
    for (const auto& c : {SurfaceCoord{p, 0, 0}, SurfaceCoord{p, 1, 1}, SurfaceCoord{p, 0.5, 0.5}}) box.extend(surface.evaluate(c).position);
  const double lattice = 1e-6 * std::max(1.0, box.diagonal().norm());
  std::map<std::array<long long, 3>, int> welded;
  const auto id_of = [&](const SurfaceCoord& c) {
    const Eigen::Vector3d x = surface.evaluate(c).position;
    const std::array<long long, 3> key{std::llround(x.x() / lattice), std::llround(x.y() / lattice), std::llround(x.z() / lattice)};
    const auto [it, inserted] = welded.try_emplace(key, static_cast<int>(out.positions.size()));
    if (inserted) out.positions.push_back(x);
    return it->second;
  };
  std::map<std::pair<int, int>, std::pair<int, int>> edge_uses;  // edge → (uses, a triangle)
  for (int p = 0; p < surface.num_ptex_faces(); ++p) {
    std::vector<int> ids((n + 1) * (n + 1));
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) ids[j * (n + 1) + i] = id_of({p, double(i) / n, double(j) / n});
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = ids[j * (n + 1) + i], b = ids[j * (n + 1) + i + 1], c = ids[(j + 1) * (n + 1) + i + 1], d = ids[(j + 1) * (n + 1) + i];
        const Eigen::Vector2d ua(double(i) / n, double(j) / n), ub(double(i + 1) / n, double(j) / n), uc(double(i + 1) / n, double(j + 1) / n),
            ud(double(i) / n, double(j + 1) / n);
        const std::array<Eigen::Vector2d, 3> uv_of[2] = {{ua, ub, uc}, {ua, uc, ud}};
        int half = 0;
        for (const auto& t : {Eigen::Vector3i(a, b, c), Eigen::Vector3i(a, c, d)}) {
          out.triangles.push_back(t);
          out.triangle_ptex.push_back(p);
          out.triangle_uv.push_back(uv_of[half++]);
          for (int k = 0; k < 3; ++k) {
            auto& use = edge_uses[std::minmax(t[k], t[(k + 1) % 3])];
            ++use.first;
            use.second = static_cast<int>(out.triangles.size()) - 1;
          }
        }
      }
  }
  for (const auto& [e, use] : edge_uses)
    if (use.first == 1) out.border.push_back(e), out.border_triangle.push_back(use.second);
  return out;
}


SurfaceProjector::SurfaceProjector(const SubdivSurface& surface, SurfaceTriangles triangles) : m_surface(surface), m_tris(std::move(triangles)) {
  double longest = 0;
  for (const auto& t : m_tris.triangles)
    for (int k = 0; k < 3; ++k) longest = std::max(longest, (m_tris.positions[t[k]] - m_tris.positions[t[(k + 1) % 3]]).norm());
  m_cell = std::max(longest, 1e-9);
  for (size_t t = 0; t < m_tris.triangles.size(); ++t) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) centre += m_tris.positions[m_tris.triangles[t][k]] / 3;
    m_grid.emplace_back(key(centre), static_cast<int>(t));
  }
  std::sort(m_grid.begin(), m_grid.end());
  m_vertex_triangles.resize(m_tris.positions.size());
  for (size_t t = 0; t < m_tris.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) m_vertex_triangles[m_tris.triangles[t][k]].push_back(static_cast<int>(t));
  m_vertex_border.resize(m_tris.positions.size());
  for (size_t e = 0; e < m_tris.border.size(); ++e) {
    m_vertex_border[m_tris.border[e].first].push_back(static_cast<int>(e));
    m_vertex_border[m_tris.border[e].second].push_back(static_cast<int>(e));
  }
}

std::uint64_t SurfaceProjector::key(const Eigen::Vector3d& p) const {
  const auto q = (p / m_cell).array().floor().cast<std::int64_t>();
  return (static_cast<std::uint64_t>(q.x() & 0x1fffff) << 42) | (static_cast<std::uint64_t>(q.y() & 0x1fffff) << 21) | static_cast<std::uint64_t>(q.z() & 0x1fffff);
}

SurfaceCoord SurfaceProjector::coord_in(int t, const Eigen::Vector3d& w) const {
  // Barycentric weights carry over to the (u, v) of the triangle's corners in its own ptex face (Yuksel §6.1).
  SurfaceCoord c{m_tris.triangle_ptex[t], 0, 0};
  for (int k = 0; k < 3; ++k) {
    c.u += w[k] * m_tris.triangle_uv[t][k].x();
    c.v += w[k] * m_tris.triangle_uv[t][k].y();
  }
  return c;
}

SurfaceProjector::BorderHit SurfaceProjector::border_hit(const Eigen::Vector3d& point, int e) const {
  const auto [a, b] = m_tris.border[e];
  const Eigen::Vector3d &pa = m_tris.positions[a], &pb = m_tris.positions[b];
  const double t = std::clamp((point - pa).dot(pb - pa) / std::max((pb - pa).squaredNorm(), 1e-300), 0.0, 1.0);
  BorderHit hit{(pa + t * (pb - pa) - point).norm(), m_tris.border_triangle[e], Eigen::Vector3d::Zero()};
  const auto& tri = m_tris.triangles[hit.triangle];
  for (int k = 0; k < 3; ++k) {
    if (tri[k] == a) hit.weights[k] = 1 - t;
    if (tri[k] == b) hit.weights[k] = t;
  }
  return hit;
}

Attachment SurfaceProjector::attach(const Eigen::Vector3d& point, bool on_border) const {
  double best = std::numeric_limits<double>::infinity();
  int best_t = -1;
  Eigen::Vector3d best_w;
  const auto consider = [&](int t) {
    const auto& tri = m_tris.triangles[t];
    const Eigen::Vector3d w = closest_on_triangle(point, m_tris.positions[tri[0]], m_tris.positions[tri[1]], m_tris.positions[tri[2]]);
    const double d = (w[0] * m_tris.positions[tri[0]] + w[1] * m_tris.positions[tri[1]] + w[2] * m_tris.positions[tri[2]] - point).norm();
    if (d < best) best = d, best_t = t, best_w = w;
  };
  if (on_border) {
    // The closest border edge, and the triangle that owns it.
    if (m_tris.border.empty()) throw Error("", "border attachment", "the surface has no border");
    for (size_t e = 0; e < m_tris.border.size(); ++e)
      if (const BorderHit hit = border_hit(point, static_cast<int>(e)); hit.distance < best) best = hit.distance, best_t = hit.triangle, best_w = hit.weights;
  } else {
    // Grow the searched block of cells until the best distance found is certain.
    const auto q = (point / m_cell).array().floor().cast<std::int64_t>();
    for (int radius = 1; radius < 64 && (best_t < 0 || best > (radius - 1) * m_cell); ++radius) {
      best = std::numeric_limits<double>::infinity();
      best_t = -1;
      for (std::int64_t dx = -radius; dx <= radius; ++dx)
        for (std::int64_t dy = -radius; dy <= radius; ++dy)
          for (std::int64_t dz = -radius; dz <= radius; ++dz) {
            const std::uint64_t k = key(((q + Eigen::Array<std::int64_t, 3, 1>(dx, dy, dz)).cast<double>() + 0.5) * m_cell);
            auto it = std::lower_bound(m_grid.begin(), m_grid.end(), std::pair<std::uint64_t, int>(k, -1));
            for (; it != m_grid.end() && it->first == k; ++it) consider(it->second);
          }
    }
    if (best_t < 0)
      for (size_t t = 0; t < m_tris.triangles.size(); ++t) consider(static_cast<int>(t));  // far from the surface
  }
  return finish(point, best_t, best_w);
}

Attachment SurfaceProjector::finish(const Eigen::Vector3d& point, int triangle, const Eigen::Vector3d& weights) const {
  Attachment a;
  a.triangle = triangle;
  a.coord = coord_in(triangle, weights);
  a.position = m_surface.evaluate(a.coord).position;
  a.distance = (a.position - point).norm();
  return a;
}

Attachment SurfaceProjector::reattach(const Eigen::Vector3d& point, const Attachment& previous, bool on_border) const {
  if (previous.triangle < 0) return attach(point, on_border);
  // Walk: test the triangles (border edges) around the current best one's corners, move to the best, repeat.
  int best_t = previous.triangle;
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_w = Eigen::Vector3d::Constant(1.0 / 3);
  for (int round = 0; round < 64; ++round) {
    const int start = best_t;
    const auto& tri = m_tris.triangles[start];
    for (int k = 0; k < 3; ++k) {
      if (on_border) {
        for (int e : m_vertex_border[tri[k]])
          if (const BorderHit hit = border_hit(point, e); hit.distance < best) best = hit.distance, best_t = hit.triangle, best_w = hit.weights;
      } else {
        for (int t : m_vertex_triangles[tri[k]]) {
          const auto& c = m_tris.triangles[t];
          const Eigen::Vector3d w = closest_on_triangle(point, m_tris.positions[c[0]], m_tris.positions[c[1]], m_tris.positions[c[2]]);
          const double d = (w[0] * m_tris.positions[c[0]] + w[1] * m_tris.positions[c[1]] + w[2] * m_tris.positions[c[2]] - point).norm();
          if (d < best) best = d, best_t = t, best_w = w;
        }
      }
    }
    if (best_t == start) break;
  }
  if (on_border && !std::isfinite(best)) return attach(point, true);  // the walk started away from the border
  return finish(point, best_t, best_w);
}

Attachment SurfaceProjector::move(const Attachment& from, const Eigen::Vector3d& target, bool on_border) const {
  constexpr double eps = 1e-12;
  SurfaceCoord c = from.coord;
  const bool u_fixed = on_border && (c.u < eps || c.u > 1 - eps), v_fixed = on_border && (c.v < eps || c.v > 1 - eps);
  if (on_border && u_fixed == v_fixed) return reattach(target, from, on_border);  // a corner, or not on a ptex edge
  for (int it = 0; it < 4; ++it) {
    const SurfaceSample s = m_surface.evaluate(c);
    const Eigen::Vector3d r = target - s.position;
    if (u_fixed) {
      c.v += s.dv.dot(r) / std::max(s.dv.squaredNorm(), 1e-300);
    } else if (v_fixed) {
      c.u += s.du.dot(r) / std::max(s.du.squaredNorm(), 1e-300);
    } else {
      Eigen::Matrix<double, 3, 2> J;
      J << s.du, s.dv;
      const Eigen::Vector2d d = (J.transpose() * J).ldlt().solve(J.transpose() * r);
      c.u += d.x();
      c.v += d.y();
    }
    if (c.u < -eps || c.u > 1 + eps || c.v < -eps || c.v > 1 + eps) return reattach(target, from, on_border);
  }
  Attachment a;
  a.coord = {c.ptex, std::clamp(c.u, 0.0, 1.0), std::clamp(c.v, 0.0, 1.0)};
  a.triangle = from.triangle;
  a.position = m_surface.evaluate(a.coord).position;
  a.distance = (a.position - target).norm();
  return a;
}

StitchAttachment attach_stitch_mesh(const mesh::StitchMesh& stitch, const SurfaceProjector& projector) {
  StitchAttachment out;
  out.on_border.assign(stitch.vertices.size(), 0);
  for (const auto& [key, uses] : mesh::edge_table(stitch))
    if (uses.count == 1) out.on_border[key >> 32] = out.on_border[key & 0xffffffffu] = 1;
  for (size_t v = 0; v < stitch.vertices.size(); ++v) {
    const Attachment a = projector.attach(stitch.vertices[v], out.on_border[v]);
    out.coords.push_back(a.coord);
    out.positions.push_back(a.position);
    out.triangles.push_back(a.triangle);
    out.max_distance = std::max(out.max_distance, a.distance);
  }
  return out;
}

}  // namespace skein::surface
