#include "stitchmesh/yarn_emission.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "stitchmesh/mean_value.hpp"

namespace skein::mesh {

void EmitOptions::validate() const {
  if (!(std::isfinite(yarn_radius) && yarn_radius > 0)) throw Error("", "yarn radius", "must be a positive number of mm");
}

namespace {

/// The share of each neighbouring stitch's height a cable face takes (open_cable_faces). A round share keeps
/// the emitted points on the 0.1 µm grid that relax::position_key matches tilings by (0.45 put some of them
/// exactly half-way between its points, where rounding may go either way).
constexpr double kCableRoom = 0.4;

/// A crossing point shared by the pieces of neighbouring faces: an edge, which of its two crossing places,
/// and for cable edges which side of the cable face (1 = the stitch below, 2 = the stitch above).
struct CrossingKey {
  std::uint64_t edge;
  int slot;
  int side;
  bool operator==(const CrossingKey&) const = default;
};
struct CrossingHash {
  size_t operator()(const CrossingKey& k) const { return std::hash<std::uint64_t>()(k.edge * 8 + k.slot * 4 + k.side); }
};

struct Piece {
  std::vector<Eigen::Vector3d> points;  ///< both ends included
  int start = -1, end = -1;             ///< crossing nodes
  int face = -1, type = 0;
  bool vertical = false;  ///< passes its face from the bottom edge to the top (YarnCurves::point_vertical)
};

/// The 2D canonical polygon of a face and its corners, for mean value coordinates.
struct FaceFrame {
  std::vector<Eigen::Vector2d> canonical;
  std::vector<Eigen::Vector3d> position, normal;
};

class Emitter {
public:
  Emitter(const StitchMesh& mesh, const StitchLibrary& library, const EmitOptions& options)
      : m_mesh(mesh), m_library(library), m_radius(options.yarn_radius), m_table(edge_table(mesh)) {}

  relax::YarnCurves run(EmitReport& report) {
    check_wale_directions();
    vertex_normals();
    collect_cables();
    open_cable_faces();
    for (int f = 0; f < static_cast<int>(m_mesh.faces.size()); ++f) emit_face(f, report);
    for (const auto& run : m_cable_runs) emit_cable(run, report);
    join_turns(report);
    return join(report);
  }

private:
  // ---- geometry -------------------------------------------------------------------------------------
  void vertex_normals() {
    m_normal.assign(m_mesh.vertices.size(), Eigen::Vector3d::Zero());
    for (const auto& f : m_mesh.faces) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      for (int k = 0; k < f.size(); ++k) n += m_mesh.vertices[f.vertex(k)].cross(m_mesh.vertices[f.vertex(k + 1)]);
      for (int v : f.vertices) m_normal[v] += n;  // area-weighted
    }
    for (auto& n : m_normal)
      if (n.norm() > 0) n.normalize();
  }

  FaceFrame frame(int f) const {
    const auto& face = m_mesh.faces[f];
    const int n = face.size(), nb = face.bottom, nt = face.top();
    FaceFrame fr;
    for (int k = 0; k < n; ++k) {
      if (k <= nb) fr.canonical.emplace_back(static_cast<double>(k) / nb, 0.0);
      else fr.canonical.emplace_back(static_cast<double>(nt - (k - nb - 1)) / nt, 1.0);
      fr.position.push_back(corner(face, k));
      fr.normal.push_back(m_normal[face.vertex(k)]);
    }
    return fr;
  }

  /// Where a face's k-th vertex is for that face: its bottom chain where the stitches above a cable face see
  /// it (m_raised), its top chain where the stitches below one do (m_lowered); elsewhere the mesh's vertex.
  const Eigen::Vector3d& corner(const StitchFace& face, int k) const {
    return k <= face.bottom ? m_raised[face.vertex(k)] : m_lowered[face.vertex(k)];
  }

  Eigen::Vector3d centre(const StitchFace& face) const {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < face.size(); ++k) c += corner(face, k);
    return c / static_cast<double>(face.size());
  }

  /// A model point (u, v, h) on the face: mean value coordinates over the canonical polygon, then h yarn
  /// radii along the interpolated normal (Yuksel 2012 §4.1: the 2.5D representation).
  Eigen::Vector3d place(const FaceFrame& fr, const Eigen::Vector3d& uvh) const {
    const Eigen::VectorXd w = mean_value_coordinates(fr.canonical, uvh.head<2>());
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
    for (int i = 0; i < static_cast<int>(w.size()); ++i) p += w[i] * fr.position[i], n += w[i] * fr.normal[i];
    return p + uvh.z() * m_radius * (n.norm() > 0 ? n.normalized() : n);
  }

  // ---- crossings --------------------------------------------------------------------------------------
  /// The node for a crossing on edge a-b at fraction `from_a` of the way from a (the same point for both faces).
  int node(int a, int b, double from_a, bool wale, int side) {
    const bool a_low = a < b;
    const double from_low = a_low ? from_a : 1 - from_a;
    const int slot = from_low < 0.5 ? 0 : 1;
    const CrossingKey key{edge_key(a, b), slot + (wale ? 2 : 0), side};
    const auto [it, inserted] = m_nodes.try_emplace(key, static_cast<int>(m_node_pos.size()));
    if (inserted) {
      const int lo = std::min(a, b), hi = std::max(a, b);
      const double t = wale ? (slot == 0 ? kWaleCrossing : 1 - kWaleCrossing) : kCourseSlots[slot];
      // A wale edge runs from a (on its row's bottom line) to b (on the top line); a cable edge's crossings
      // sit on the line as the stitches on their side see it (open_cable_faces).
      const auto at = [&](int v) -> const Eigen::Vector3d& {
        if (wale) return v == a ? m_raised[v] : m_lowered[v];
        return side == 1 ? m_lowered[v] : side == 2 ? m_raised[v] : m_mesh.vertices[v];
      };
      const Eigen::Vector3d& pl = at(lo);
      Eigen::Vector3d pos = pl + t * (at(hi) - pl);
      // A cable edge has two crossings at each slot: the stitch below's into the cable (side 1) and the
      // cable's into the stitch above (side 2). Two yarns cannot share a point, so each sits one yarn radius
      // toward its stitch (at most 0.4 of the way to the stitch's centre), and the cable spans the gap.
      if (side != 0) pos = toward_stitch(a, b, side == 1, pos);
      m_node_pos.push_back(pos);
      m_node_border.push_back(m_table.at(edge_key(a, b)).count == 1);
      m_node_ends.emplace_back();
    }
    return it->second;
  }

  bool is_cable(int a, int b) const { return m_cable_edge.count(edge_key(a, b)) > 0; }

  /// `pos` moved one yarn radius toward the centre of the stitch below the course edge a-b (or above it).
  Eigen::Vector3d toward_stitch(int a, int b, bool below, const Eigen::Vector3d& pos) const {
    const auto& uses = m_table.at(edge_key(a, b));
    for (int k = 0; k < uses.count; ++k) {
      const auto& face = m_mesh.faces[uses.use[k].face];
      if (face.is_top(uses.use[k].local) != below) continue;
      const Eigen::Vector3d to = centre(face) - pos;
      const double d = to.norm();
      return d > 0 ? Eigen::Vector3d(pos + std::min(m_radius, 0.4 * d) / d * to) : pos;
    }
    return pos;
  }

  /// The node of a model crossing on face f.
  int crossing_node(int f, const Crossing& c) {
    const auto& face = m_mesh.faces[f];
    const int n = face.size(), nb = face.bottom;
    switch (c.side) {
      case Crossing::Side::Left: return node(face.vertex(0), face.vertex(n - 1), kWaleCrossing, true, 0);
      case Crossing::Side::Right: return node(face.vertex(nb), face.vertex(nb + 1), kWaleCrossing, true, 0);
      case Crossing::Side::Bottom: {
        const int a = face.vertex(c.edge), b = face.vertex(c.edge + 1);
        return node(a, b, kCourseSlots[c.slot], false, is_cable(a, b) ? 2 : 0);
      }
      case Crossing::Side::Top: {
        const int a = face.vertex(n - 1 - c.edge), b = face.vertex(n - 2 - c.edge);  // left to right
        return node(a, b, kCourseSlots[c.slot], false, is_cable(a, b) ? 1 : 0);
      }
    }
    return -1;
  }

  int type_id(const std::string& name) {
    const auto it = std::find(m_type_names.begin(), m_type_names.end(), name);
    if (it != m_type_names.end()) return static_cast<int>(it - m_type_names.begin());
    m_type_names.push_back(name);
    return static_cast<int>(m_type_names.size()) - 1;
  }

  void add_piece(Piece piece) {
    const int id = static_cast<int>(m_pieces.size());
    if (piece.start >= 0) m_node_ends[piece.start].push_back({id, 0});
    if (piece.end >= 0) m_node_ends[piece.end].push_back({id, 1});
    m_pieces.push_back(std::move(piece));
  }

  /// Adds a model's pieces: interior points through `place(uvh)`, crossings through `node(crossing)`;
  /// a piece with a crossing for which `drop(crossing, node)` holds is left out.
  template <class Place, class Node, class Drop>
  void add_model(const StitchModel& model, int face, int type, Place place, Node node, Drop drop) {
    for (const auto& mp : model.pieces) {
      Piece piece;
      piece.face = face;
      piece.type = type;
      bool dropped = false;
      for (size_t i = 0; i < mp.points.size(); ++i) {
        const auto& p = mp.points[i];
        if (!p.crossing) {
          piece.points.push_back(place(p.uvh));
          continue;
        }
        const int id = node(*p.crossing);
        dropped |= drop(*p.crossing, id);
        piece.points.push_back(m_node_pos[id]);
        (i == 0 ? piece.start : piece.end) = id;
      }
      const auto side = [&](size_t i) { return mp.points[i].crossing ? std::optional(mp.points[i].crossing->side) : std::nullopt; };
      const auto first = side(0), last = side(mp.points.size() - 1);
      using Side = Crossing::Side;
      piece.vertical = first && last && ((*first == Side::Bottom && *last == Side::Top) || (*first == Side::Top && *last == Side::Bottom));
      if (!dropped) add_piece(std::move(piece));
    }
  }
  static bool keep(const Crossing&, int) { return false; }

  // ---- faces --------------------------------------------------------------------------------------------
  bool bottom_on_border(int f) const {
    const auto& face = m_mesh.faces[f];
    for (int k = 0; k < face.bottom; ++k)
      if (m_table.at(edge_key(face.vertex(k), face.vertex(k + 1))).count == 1) return true;
    return false;
  }

  void emit_face(int f, EmitReport& report) {
    const auto& face = m_mesh.faces[f];
    const bool cast_on = bottom_on_border(f);
    // Yuksel §4.3: first-row stitches are cast on as y+1, ignoring their bottom edges.
    const std::string name = cast_on && face.bottom == 1 && face.top() == 1 ? "y+1" : face.type;
    const StitchModel& model = m_library.at(name);
    if (model.bottom != face.bottom || model.top != face.top() || !model.wale_edges)
      throw Error("", "face " + std::to_string(f), "stitch model '" + name + "' does not fit the face's shape");
    report.cast_on += cast_on;
    const FaceFrame fr = frame(f);
    add_model(
        model, f, type_id(face.type), [&](const Eigen::Vector3d& uvh) { return place(fr, uvh); },
        [&](const Crossing& c) { return crossing_node(f, c); },
        [&](const Crossing& c, int id) { return cast_on && c.side == Crossing::Side::Bottom && m_node_border[id]; });
    // Yuksel §4.3: bind-off pieces close the loops of the last row over its top border edges.
    for (int j = 0; j < face.top(); ++j) {
      const int a = face.vertex(face.size() - 1 - j), b = face.vertex(face.size() - 2 - j);
      if (m_table.at(edge_key(a, b)).count == 1) emit_bind_off(f, a, b, report);
    }
  }

  void emit_bind_off(int f, int a, int b, EmitReport& report) {
    const StitchModel& model = m_library.at("bind-off");
    const auto& face = m_mesh.faces[f];
    // A band half a stitch high above the edge, along the face's wale direction.
    Eigen::Vector3d bottom_mid = Eigen::Vector3d::Zero(), top_mid = Eigen::Vector3d::Zero();
    for (int k = 0; k <= face.bottom; ++k) bottom_mid += m_mesh.vertices[face.vertex(k)] / (face.bottom + 1);
    for (int k = face.bottom + 1; k < face.size(); ++k) top_mid += m_mesh.vertices[face.vertex(k)] / (face.top() + 1);
    const Eigen::Vector3d up = 0.5 * (top_mid - bottom_mid);
    FaceFrame fr;
    fr.canonical = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const Eigen::Vector3d &pa = m_mesh.vertices[a], &pb = m_mesh.vertices[b];
    fr.position = {pa, pb, pb + up, pa + up};
    fr.normal = {m_normal[a], m_normal[b], m_normal[b], m_normal[a]};
    add_model(
        model, -1, type_id("bind-off"), [&](const Eigen::Vector3d& uvh) { return place(fr, uvh); },
        [&](const Crossing& c) { return node(a, b, kCourseSlots[c.slot], false, is_cable(a, b) ? 1 : 0); }, keep);
    ++report.bind_off;
  }

  // ---- cables ---------------------------------------------------------------------------------------------
  struct CableRun {
    std::vector<std::pair<int, int>> edges;  ///< left to right as seen from the stitches below
    CableMark mark;
  };

  void collect_cables() {
    for (const auto& [edge, mark] : m_mesh.cables) m_cable_edge.insert(edge_key(edge.first, edge.second));
    // Marked edges in the top chains of the stitches below, keyed by their left end.
    std::unordered_map<int, std::pair<int, int>> by_left;
    std::unordered_map<int, CableMark> mark_of;
    std::unordered_map<int, int> right_to_left;
    for (const auto& face : m_mesh.faces)
      for (int j = 0; j < face.top(); ++j) {
        const int a = face.vertex(face.size() - 1 - j), b = face.vertex(face.size() - 2 - j);
        const auto it = m_mesh.cables.find(std::minmax(a, b));
        if (it == m_mesh.cables.end()) continue;
        by_left[a] = {a, b};
        mark_of[a] = it->second;
        right_to_left[b] = a;
      }
    for (const auto& [left, edge] : by_left) {
      const auto prev = right_to_left.find(left);
      if (prev != right_to_left.end() && mark_of.count(prev->second) && mark_of[prev->second] == mark_of[left]) continue;  // not a run start
      CableRun run;
      run.mark = mark_of[left];
      for (auto e = edge;;) {
        run.edges.push_back(e);
        const auto next = by_left.find(e.second);
        if (next == by_left.end() || !(mark_of[e.second] == run.mark) || run.edges.size() > by_left.size()) break;
        e = next->second;
      }
      m_cable_runs.push_back(std::move(run));
    }
    std::sort(m_cable_runs.begin(), m_cable_runs.end(), [](const CableRun& x, const CableRun& y) { return x.edges < y.edges; });
  }

  /// Yuksel 2012 §4.5 places the cable face between two rows (Fig. 9, right). The stitch mesh has no room
  /// there, so the face takes kCableRoom of the height of the stitches on either side: each vertex inside a
  /// cable run is seen kCableRoom down its wale edge by the stitches below (m_lowered) and as far up by those
  /// above (m_raised), and their models are emitted in what is left. The crossing then takes most of a row's
  /// height, as in a real cable, not a flat band along the course line. A run's end vertices, and any vertex
  /// that is also on an uncabled course edge or lacks a wale edge on either side, stay where they are.
  void open_cable_faces() {
    m_lowered = m_raised = m_mesh.vertices;
    if (m_cable_runs.empty()) return;
    std::unordered_set<int> fixed;
    std::unordered_map<int, std::pair<Eigen::Vector3d, int>> down, up;  // sum and count of wale edges' far ends
    for (const auto& face : m_mesh.faces) {
      const int n = face.size(), nb = face.bottom;
      for (int j = 0; j < face.top(); ++j)
        if (!is_cable(face.vertex(n - 1 - j), face.vertex(n - 2 - j))) fixed.insert(face.vertex(n - 1 - j)), fixed.insert(face.vertex(n - 2 - j));
      for (int j = 0; j < nb; ++j)
        if (!is_cable(face.vertex(j), face.vertex(j + 1))) fixed.insert(face.vertex(j)), fixed.insert(face.vertex(j + 1));
      const auto add = [](auto& to, int v, const Eigen::Vector3d& far) {
        auto& [sum, count] = to.try_emplace(v, Eigen::Vector3d::Zero(), 0).first->second;
        sum += far, ++count;
      };
      add(down, face.vertex(nb + 1), m_mesh.vertices[face.vertex(nb)]);
      add(down, face.vertex(n - 1), m_mesh.vertices[face.vertex(0)]);
      add(up, face.vertex(nb), m_mesh.vertices[face.vertex(nb + 1)]);
      add(up, face.vertex(0), m_mesh.vertices[face.vertex(n - 1)]);
    }
    for (const auto& run : m_cable_runs)
      for (size_t i = 1; i < run.edges.size(); ++i) {
        const int v = run.edges[i].first;
        const auto d = down.find(v), u = up.find(v);
        if (fixed.count(v) || d == down.end() || u == up.end()) continue;
        const Eigen::Vector3d& p = m_mesh.vertices[v];
        m_lowered[v] = p + kCableRoom * (d->second.first / d->second.second - p);
        m_raised[v] = p + kCableRoom * (u->second.first / u->second.second - p);
      }
  }

  void emit_cable(const CableRun& run, EmitReport& report) {
    const int n = static_cast<int>(run.edges.size());
    const int s = run.mark.shift;
    // shift > 0: the first s loops move right over the rest; shift < 0: the last |s| loops move left over.
    const int a = s > 0 ? s : n + s, b = n - a;
    const double front = (s > 0 ? 1.0 : -1.0) * run.mark.order;
    const std::string name = "cable" + std::to_string(a) + "x" + std::to_string(b);
    const StitchModel* model = m_library.find(name);
    if (!model || a < 1 || b < 1)
      throw Error("", "cable edge " + std::to_string(run.edges[0].first) + "-" + std::to_string(run.edges[0].second),
                  "a cable of " + std::to_string(a) + " over " + std::to_string(b) + " stitches has no model (1 to 3 over 1 to 3)");
    const int type = type_id(name);
    // The cable face: u runs along the run's edges, v from the line as the stitches below see it to the line
    // as those above do (open_cable_faces), h along the normal. Its crossings sit one more yarn radius
    // toward their stitches; its strands cross from kBandLow to kBandHigh radii past those lines, so that two
    // strands of one side (equal bumps in h, shifted along u) pass each other at different heights instead of
    // meeting, and all of them pass below the feet of the heads of the stitches above.
    constexpr double kBandLow = -0.8, kBandHigh = 0.2;
    std::vector<Eigen::Vector3d> wale(n);
    for (int i = 0; i < n; ++i) {
      const auto [va, vb] = run.edges[i];
      const Eigen::Vector3d mid = 0.5 * (m_mesh.vertices[va] + m_mesh.vertices[vb]);
      const Eigen::Vector3d along = (m_mesh.vertices[vb] - m_mesh.vertices[va]).normalized();
      const Eigen::Vector3d nrm = (m_normal[va] + m_normal[vb]).normalized();
      Eigen::Vector3d w = toward_stitch(va, vb, false, mid) - toward_stitch(va, vb, true, mid);
      w -= w.dot(along) * along + w.dot(nrm) * nrm;
      wale[i] = w.norm() > 0 ? Eigen::Vector3d(w.normalized()) : Eigen::Vector3d(nrm.cross(along));
    }
    const auto on_band = [&](const Eigen::Vector3d& uvh) {
      const double x = std::clamp(uvh.x(), 0.0, 1.0) * n;
      const int i = std::min(n - 1, static_cast<int>(x));
      const double t = x - i, v = uvh.y();
      const auto [va, vb] = run.edges[i];
      const Eigen::Vector3d low = (1 - t) * m_lowered[va] + t * m_lowered[vb], high = (1 - t) * m_raised[va] + t * m_raised[vb];
      const Eigen::Vector3d nrm = ((1 - t) * m_normal[va] + t * m_normal[vb]).normalized();
      return Eigen::Vector3d(low + v * (high - low) + m_radius * (front * uvh.z() * nrm + (kBandLow + (kBandHigh - kBandLow) * v) * wale[i]));
    };
    add_model(
        *model, -1, type, on_band,
        [&](const Crossing& c) {
          const auto [va, vb] = run.edges[c.edge];
          return node(va, vb, kCourseSlots[c.slot], false, c.side == Crossing::Side::Bottom ? 1 : 2);
        },
        keep);
    ++report.cables;
  }

  // ---- borders ----------------------------------------------------------------------------------------------
  /// Yuksel §4.3, Fig. 6: at the side borders of a flat piece the yarn of one row turns into the next, on
  /// alternate sides (rows 0→1 on the right, 1→2 on the left, ...); the remaining loose ends stay tied.
  void join_turns(EmitReport& report) {
    const auto rows = faces_by_row(m_mesh);
    const auto levels = row_order(m_mesh, rows, m_table).level;
    struct End {
      int node, face, level, top_vertex;
    };
    std::unordered_map<int, End> right_by_bottom, left_by_bottom;  // keyed by the wale edge's bottom vertex
    for (int f = 0; f < static_cast<int>(m_mesh.faces.size()); ++f) {
      const auto& face = m_mesh.faces[f];
      const int n = face.size(), nb = face.bottom;
      const int level = levels[face.row];
      if (m_table.at(edge_key(face.vertex(nb), face.vertex(nb + 1))).count == 1)
        right_by_bottom[face.vertex(nb)] = {node(face.vertex(nb), face.vertex(nb + 1), kWaleCrossing, true, 0), f, level, face.vertex(nb + 1)};
      if (m_table.at(edge_key(face.vertex(0), face.vertex(n - 1))).count == 1)
        left_by_bottom[face.vertex(0)] = {node(face.vertex(0), face.vertex(n - 1), kWaleCrossing, true, 0), f, level, face.vertex(n - 1)};
    }
    const int type = type_id("turn");
    const auto turn_side = [&](const std::unordered_map<int, End>& side, int parity) {
      std::vector<std::pair<int, End>> sorted(side.begin(), side.end());
      std::sort(sorted.begin(), sorted.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (const auto& [bottom, e] : sorted) {
        if (e.level % 2 != parity || m_node_ends[e.node].size() != 1) continue;
        const auto above = side.find(e.top_vertex);
        if (above == side.end() || m_node_ends[above->second.node].size() != 1) continue;
        const Eigen::Vector3d c1 = m_node_pos[e.node], c2 = m_node_pos[above->second.node];
        const Eigen::Vector3d along = (c2 - c1).normalized();
        Eigen::Vector3d out = c1 - centre(m_mesh.faces[e.face]);
        out -= out.dot(along) * along;
        out = out.norm() > 0 ? out.normalized() : out;
        Piece piece;
        piece.face = -1;
        piece.type = type;
        piece.points = {c1, 0.5 * (c1 + c2) + out * (0.35 * (c2 - c1).norm() + m_radius), c2};
        piece.start = e.node;
        piece.end = above->second.node;
        add_piece(std::move(piece));
        ++report.turns;
      }
    };
    turn_side(right_by_bottom, 0);
    turn_side(left_by_bottom, 1);
  }

  void check_wale_directions() const {
    for (const auto& [key, uses] : m_table) {
      if (uses.count != 2) continue;
      const auto &a = m_mesh.faces[uses.use[0].face], &b = m_mesh.faces[uses.use[1].face];
      if (!a.is_wale(uses.use[0].local)) continue;
      if ((uses.use[0].local == a.right_wale()) == (uses.use[1].local == b.right_wale()))
        throw Error("", "wale edge " + std::to_string(key >> 32) + "-" + std::to_string(key & 0xffffffffu),
                    "faces " + std::to_string(uses.use[0].face) + " and " + std::to_string(uses.use[1].face) +
                        " of one row have opposite wale directions; flip one of them");
    }
  }

  // ---- joining -------------------------------------------------------------------------------------------
  relax::YarnCurves join(EmitReport& report) {
    for (size_t id = 0; id < m_node_ends.size(); ++id)
      if (m_node_ends[id].size() > 2)
        throw Error("", "crossing near (" + std::to_string(m_node_pos[id].x()) + ", " + std::to_string(m_node_pos[id].y()) + ", " +
                            std::to_string(m_node_pos[id].z()) + ")",
                    std::to_string(m_node_ends[id].size()) + " yarn pieces meet where two should");
    relax::YarnCurves out;
    out.radius = m_radius;
    std::vector<char> used(m_pieces.size(), 0);
    const auto walk = [&](int piece, int enter_end) {
      const int first_piece = piece;
      bool closed = false;
      const size_t begin = out.points.size();
      for (;;) {
        used[piece] = 1;
        const Piece& p = m_pieces[piece];
        const int n = static_cast<int>(p.points.size());
        for (int k = 0; k < n; ++k) {
          const int idx = enter_end == 0 ? k : n - 1 - k;
          if (k == 0 && out.points.size() > begin) continue;  // the crossing point is already there
          out.points.push_back(p.points[idx]);
          out.point_face.push_back(p.face);
          out.point_type.push_back(p.type);
          out.point_vertical.push_back(p.vertical);
        }
        const int exit_node = enter_end == 0 ? p.end : p.start;
        if (exit_node < 0 || m_node_ends[exit_node].size() < 2) break;  // a loose end
        const auto& ends = m_node_ends[exit_node];
        const auto next = ends[0].first == piece && ends[0].second == 1 - enter_end ? ends[1] : ends[0];
        if (next.first == first_piece || used[next.first]) {
          closed = true;
          break;
        }
        piece = next.first;
        enter_end = next.second;
      }
      if (closed && out.points.size() - begin > 1) {  // the last point repeats the first
        out.points.pop_back();
        out.point_face.pop_back();
        out.point_type.pop_back();
        out.point_vertical.pop_back();
      }
      out.curve_start.push_back(static_cast<int>(out.points.size()));
      out.closed.push_back(closed);
    };
    // Open yarns first, from their loose ends; every piece left over belongs to a closed loop.
    for (size_t id = 0; id < m_node_ends.size(); ++id)
      if (m_node_ends[id].size() == 1 && !used[m_node_ends[id][0].first]) walk(m_node_ends[id][0].first, m_node_ends[id][0].second);
    for (size_t i = 0; i < m_pieces.size(); ++i)
      if (!used[i]) walk(static_cast<int>(i), 0);
    for (const auto& ends : m_node_ends) report.tied_ends += ends.size() == 1;
    out.type_names = m_type_names;
    return out;
  }

  const StitchMesh& m_mesh;
  const StitchLibrary& m_library;
  double m_radius;
  EdgeTable m_table;
  std::vector<Eigen::Vector3d> m_normal;
  std::vector<Eigen::Vector3d> m_lowered, m_raised;  ///< vertices as the stitches below / above a cable face see them
  std::unordered_map<CrossingKey, int, CrossingHash> m_nodes;
  std::vector<Eigen::Vector3d> m_node_pos;
  std::vector<char> m_node_border;
  std::vector<std::vector<std::pair<int, int>>> m_node_ends;  // (piece, 0 = its start / 1 = its end)
  std::vector<Piece> m_pieces;
  std::vector<std::string> m_type_names;
  std::unordered_set<std::uint64_t> m_cable_edge;
  std::vector<CableRun> m_cable_runs;
};

}  // namespace

relax::YarnCurves emit_yarn(const StitchMesh& mesh, const StitchLibrary& library, const EmitOptions& options, EmitReport* report) {
  options.validate();
  const StitchReport check = validate(mesh);
  if (!check.valid()) throw Error("", "stitch mesh", "is not valid, so no yarn can be emitted:\n" + check.summary(5));
  EmitReport local;
  relax::YarnCurves yarn = Emitter(mesh, library, options).run(report ? *report : local);
  if (!mesh.palette.empty()) {  // each piece of yarn in its stitch's colour
    std::vector<int> face_colour;
    for (const auto& f : mesh.faces) face_colour.push_back(f.colour);
    colour_yarn(yarn, face_colour, mesh.palette);
  }
  return yarn;
}

}  // namespace skein::mesh
