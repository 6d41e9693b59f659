#include "garments.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace skein::models {
namespace {

using Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;

/// Collects points and quads; bands join two loops (or open polylines) of equal length.
struct Builder {
  std::vector<Vector3d> points;
  std::vector<std::vector<int>> faces;

  int add(const Vector3d& p) {
    points.push_back(p);
    return static_cast<int>(points.size()) - 1;
  }
  std::vector<int> add_all(const std::vector<Vector3d>& ps) {
    std::vector<int> ids;
    for (const auto& p : ps) ids.push_back(add(p));
    return ids;
  }
  /// Quads between loop `lower` and loop `upper` (same length); closed loops wrap around.
  void band(const std::vector<int>& lower, const std::vector<int>& upper, bool closed) {
    const size_t n = lower.size(), count = closed ? n : n - 1;
    for (size_t i = 0; i < count; ++i) {
      const size_t j = (i + 1) % n;
      faces.push_back({lower[i], lower[j], upper[j], upper[i]});
    }
  }
  /// Orients every face outward (away from the centroid); all faces share one orientation by construction.
  mesh::InputMesh finish(const std::string& name) {
    Vector3d centre = Vector3d::Zero();
    for (const auto& p : points) centre += p;
    centre /= static_cast<double>(points.size());
    double outward = 0;
    for (const auto& f : faces) {
      Vector3d n = Vector3d::Zero(), c = Vector3d::Zero();
      for (size_t i = 0; i < f.size(); ++i) n += points[f[i]].cross(points[f[(i + 1) % f.size()]]), c += points[f[i]];
      outward += n.dot(c / static_cast<double>(f.size()) - centre);
    }
    if (outward < 0)
      for (auto& f : faces) std::reverse(f.begin(), f.end());
    return mesh::InputMesh(points, faces, "models/" + name + ".obj");
  }
};

std::vector<Vector3d> ellipse(int n, double rx, double rz, double y, double phase = 0) {
  std::vector<Vector3d> ring;
  for (int i = 0; i < n; ++i) {
    const double t = phase + 2 * kPi * i / n;
    ring.emplace_back(rx * std::cos(t), y, rz * std::sin(t));
  }
  return ring;
}

std::vector<Vector3d> lerp(const std::vector<Vector3d>& a, const std::vector<Vector3d>& b, double t) {
  std::vector<Vector3d> out;
  for (size_t i = 0; i < a.size(); ++i) out.push_back((1 - t) * a[i] + t * b[i]);
  return out;
}

/// A stack of rings joined by bands; returns the ids of the last ring.
std::vector<int> stack(Builder& b, std::vector<int> first, const std::vector<std::vector<Vector3d>>& rings) {
  for (const auto& ring : rings) {
    auto next = b.add_all(ring);
    b.band(first, next, true);
    first = std::move(next);
  }
  return first;
}

/// A dome over a ring: rings shrink along a quarter circle to a small opening of radius `opening`.
void dome(Builder& b, const std::vector<int>& base, const Vector3d& centre, double height, int bands, double opening) {
  std::vector<Vector3d> from;
  for (int v : base) from.push_back(b.points[v]);
  std::vector<std::vector<Vector3d>> rings;
  for (int k = 1; k <= bands; ++k) {
    const double phi = 0.5 * kPi * k / bands;
    std::vector<Vector3d> ring;
    for (const auto& p : from) {
      Vector3d radial = p - centre;
      radial.y() = 0;
      const double r0 = radial.norm();
      const double r = std::max(opening, r0 * std::cos(phi));
      ring.push_back(centre + radial.normalized() * r + Vector3d(0, p.y() - centre.y() + height * std::sin(phi), 0));
    }
    rings.push_back(std::move(ring));
  }
  stack(b, base, rings);
}

/// A branch (sleeve, thumb) joined to a trunk ring at an underarm arc (Yuksel's sweater: sleeves meet the body
/// at the armholes). The arc runs trunk[a..b] (wrapping); an arch of new points rises from b back to a. The
/// branch tube starts from the loop arc + arch and runs along `direction`; the trunk continues from the ring
/// with the arc replaced by the arch (see join_ring).
struct Branch {
  int a, b;            ///< arc ends, indices into the trunk ring
  int arch_edges;      ///< edges of the arch
  double rise;         ///< arch height above the arc [mm]
  double bulge;        ///< arch offset away from the trunk axis [mm]
  Vector3d direction;  ///< along the branch, away from the trunk
  double length, end_radius, end_taper;  ///< end ring radius; end_taper < 1 closes the tip like a dome
  int bands;
  std::vector<int> arch;  ///< filled by add_arch: interior arch points from b to a
};

std::vector<int> arc(const std::vector<int>& ring, int a, int b) {
  std::vector<int> out;
  const int n = static_cast<int>(ring.size());
  for (int i = a;; i = (i + 1) % n) {
    out.push_back(ring[i]);
    if (i == b) break;
  }
  return out;
}

void add_arch(Builder& bld, const std::vector<int>& ring, Branch& br, const Vector3d& axis_point) {
  const Vector3d pa = bld.points[ring[br.a]], pb = bld.points[ring[br.b]];
  const Vector3d mid = 0.5 * (pa + pb), half = 0.5 * (pb - pa);
  Vector3d out = mid - axis_point;
  out.y() = 0;
  out.normalize();
  for (int j = 1; j < br.arch_edges; ++j) {
    const double phi = kPi * j / br.arch_edges;  // 0 at b, pi at a
    br.arch.push_back(bld.add(mid + half * std::cos(phi) + (Vector3d(0, br.rise, 0) + out * br.bulge) * std::sin(phi)));
  }
}

void add_branch_tube(Builder& bld, const std::vector<int>& ring, const Branch& br) {
  std::vector<int> loop = arc(ring, br.a, br.b);
  loop.insert(loop.end(), br.arch.begin(), br.arch.end());
  std::vector<Vector3d> from;
  Vector3d centre = Vector3d::Zero();
  for (int v : loop) from.push_back(bld.points[v]), centre += bld.points[v];
  centre /= static_cast<double>(loop.size());
  const Vector3d d = br.direction.normalized();
  std::vector<Vector3d> end;
  for (const auto& p : from) {
    Vector3d radial = p - centre;
    radial -= radial.dot(d) * d;
    end.push_back(centre + d * br.length + radial.normalized() * br.end_radius);
  }
  std::vector<std::vector<Vector3d>> rings;
  for (int k = 1; k <= br.bands; ++k) {
    const double t = static_cast<double>(k) / br.bands;
    auto ringk = lerp(from, end, t);
    if (br.end_taper < 1) {  // round the tip off: the last rings close in toward the axis
      const Vector3d c = centre + d * br.length * t;
      const double s = 1 - (1 - br.end_taper) * std::pow(t, 4);
      for (auto& p : ringk) p = c + (p - c) * s;
    }
    rings.push_back(std::move(ringk));
  }
  stack(bld, loop, rings);
}

/// The trunk ring with each branch's arc replaced by its arch (from a to b).
std::vector<int> join_ring(const std::vector<int>& ring, const std::vector<Branch>& branches) {
  std::vector<int> out;
  const int n = static_cast<int>(ring.size());
  std::vector<int> skip(n, 0);
  std::vector<const Branch*> at(n, nullptr);
  for (const auto& br : branches) {
    for (int i = (br.a + 1) % n; i != br.b; i = (i + 1) % n) skip[i] = 1;
    at[br.a] = &br;
  }
  for (int i = 0; i < n; ++i) {
    if (skip[i]) continue;
    out.push_back(ring[i]);
    if (at[i]) out.insert(out.end(), at[i]->arch.rbegin(), at[i]->arch.rend());
  }
  return out;
}

}  // namespace

mesh::InputMesh swatch() {
  Builder b;
  std::vector<int> prev;
  for (int r = 0; r <= 4; ++r) {
    std::vector<Vector3d> line;
    for (int c = 0; c <= 4; ++c) line.emplace_back(30.0 * c, 25.0 * r, 0);
    auto ids = b.add_all(line);
    if (r > 0) b.band(prev, ids, false);
    prev = ids;
  }
  return b.finish("swatch");
}

mesh::InputMesh tube() {
  Builder b;
  std::vector<std::vector<Vector3d>> rings;
  for (int k = 1; k <= 5; ++k) rings.push_back(ellipse(12, 40, 40, 30.0 * k));
  stack(b, b.add_all(ellipse(12, 40, 40, 0)), rings);
  return b.finish("tube");
}

mesh::InputMesh beanie() {
  Builder b;
  std::vector<std::vector<Vector3d>> rings;
  for (int k = 1; k <= 4; ++k) rings.push_back(ellipse(16, 90, 90, 35.0 * k));
  const auto top = stack(b, b.add_all(ellipse(16, 88, 88, 0)), rings);
  dome(b, top, Vector3d(0, 140, 0), 75, 4, 8);
  return b.finish("beanie");
}

mesh::InputMesh mitten() {
  Builder b;
  const int n = 16;
  std::vector<std::vector<Vector3d>> rings;
  for (double y : {35.0, 70.0, 100.0}) rings.push_back(ellipse(n, 48, 26, y));
  const auto joint = stack(b, b.add_all(ellipse(n, 44, 24, 0)), rings);
  // The thumb leaves the side of the hand (+x) at the gusset: arc over indices 15..1.
  std::vector<Branch> thumb{{15, 1, 4, 32, 6, Vector3d(0.8, 1.0, 0.35), 65, 11, 0.3, 4, {}}};
  add_arch(b, joint, thumb[0], Vector3d(0, 100, 0));
  add_branch_tube(b, joint, thumb[0]);
  const auto hand_ring = join_ring(joint, thumb);
  std::vector<Vector3d> from;
  for (int v : hand_ring) from.push_back(b.points[v]);
  std::vector<Vector3d> palm;
  for (const auto& p : from) {
    const double t = std::atan2(p.z(), p.x());
    palm.emplace_back(50 * std::cos(t), 185, 27 * std::sin(t));
  }
  std::vector<std::vector<Vector3d>> upper;
  for (int k = 1; k <= 3; ++k) upper.push_back(lerp(from, palm, k / 3.0));
  const auto top = stack(b, hand_ring, upper);
  dome(b, top, Vector3d(0, 185, 0), 45, 3, 5);
  return b.finish("mitten");
}

mesh::InputMesh tea_cozy() {
  Builder b;
  const double radius = 110, height = 110;
  // Two panels of 6 columns between angles [20°, 160°] (front) and [200°, 340°] (back), 3 rows high.
  const auto panel = [&](double from_deg) {
    std::vector<int> prev;
    for (int r = 0; r <= 3; ++r) {
      std::vector<Vector3d> line;
      for (int c = 0; c <= 6; ++c) {
        const double t = (from_deg + 140.0 * c / 6) * kPi / 180;
        line.emplace_back(radius * std::cos(t), height * r / 3, radius * std::sin(t));
      }
      auto ids = b.add_all(line);
      if (r > 0) b.band(prev, ids, false);
      prev = ids;
    }
    return prev;
  };
  auto ring = panel(20);
  const auto back = panel(200);
  ring.insert(ring.end(), back.begin(), back.end());  // the gaps between panels are the openings' tops
  dome(b, ring, Vector3d(0, height, 0), 90, 4, 12);
  return b.finish("tea_cozy");
}

mesh::InputMesh sweater() {
  Builder b;
  const int n = 24;  // 15° per body column; side 1 at +x, front at +z
  const double underarm = 420, hem_scale = 0.96;
  std::vector<std::vector<Vector3d>> rings;
  for (int k = 1; k <= 7; ++k) {
    const double y = 60.0 * k, s = hem_scale + (1 - hem_scale) * y / underarm;
    rings.push_back(ellipse(n, 190 * s, 120 * s, y));
  }
  const auto joint = stack(b, b.add_all(ellipse(n, 190 * hem_scale, 120 * hem_scale, 0)), rings);
  // Sleeves: underarm arcs over ±30° at each side, arches 150 mm up over the shoulders.
  std::vector<Branch> sleeves{
      {22, 2, 8, 150, 12, Vector3d(1, -0.9, 0), 520, 40, 1, 8, {}},
      {10, 14, 8, 150, 12, Vector3d(-1, -0.9, 0), 520, 40, 1, 8, {}},
  };
  for (auto& s : sleeves) {
    add_arch(b, joint, s, Vector3d(0, underarm, 0));
    add_branch_tube(b, joint, s);
  }
  // Yoke: from the joined ring up to the neck, bulging a little over the shoulders and chest.
  const auto yoke_ring = join_ring(joint, sleeves);
  std::vector<Vector3d> from, neck;
  for (int v : yoke_ring) {
    const Vector3d& p = b.points[v];
    from.push_back(p);
    const double t = std::atan2(p.z(), p.x());
    neck.emplace_back(85 * std::cos(t), 650, 65 * std::sin(t));
  }
  std::vector<std::vector<Vector3d>> yoke;
  for (int k = 1; k <= 5; ++k) {
    const double t = k / 5.0;
    auto ring = lerp(from, neck, t);
    for (auto& p : ring) {
      Vector3d radial(p.x(), 0, p.z());
      p += radial.normalized() * 18 * std::sin(kPi * t);
    }
    yoke.push_back(std::move(ring));
  }
  stack(b, yoke_ring, yoke);
  return b.finish("sweater");
}

const std::vector<Garment>& garments() {
  static const std::vector<Garment> all{{"swatch", swatch}, {"tube", tube},       {"beanie", beanie},
                                        {"mitten", mitten}, {"tea_cozy", tea_cozy}, {"sweater", sweater}};
  return all;
}

}  // namespace skein::models
