#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "stitchmesh/colours.hpp"

namespace skein::mesh {

/// One stitch (Yuksel 2012 §4.1). The loop is counter-clockwise and starts at the bottom-left corner:
/// edges 0..bottom-1 are the bottom course edges (left to right), edge `bottom` is the right wale edge,
/// the next `top` edges are the top course edges (right to left) and the last edge is the left wale edge.
/// The wale direction points from the bottom edges to the top edges.
struct StitchFace {
  std::vector<int> vertices;
  int bottom = 1;
  int row = -1;         ///< stitch row: the faces joined by wale edges
  std::string type = "k";
  int input_face = -1;  ///< the input-mesh face it was tessellated from, -1 when made by an edit
  int colour = 0;       ///< the yarn's colour: an index into StitchMesh::palette (unused while it is empty)

  int size() const { return static_cast<int>(vertices.size()); }
  int top() const { return size() - bottom - 2; }
  int right_wale() const { return bottom; }
  int left_wale() const { return size() - 1; }
  bool is_wale(int k) const { return k == bottom || k == size() - 1; }
  bool is_bottom(int k) const { return k < bottom; }
  bool is_top(int k) const { return k > bottom && k < size() - 1; }
  int vertex(int k) const { return vertices[static_cast<size_t>(k) % vertices.size()]; }
  bool operator==(const StitchFace&) const = default;
};

/// A cable mark on a course edge (Yuksel 2012 §4.5): the marked run of edges becomes a cable face just
/// before yarn emission. `shift` moves the loops by that many stitches; `order` +1 crosses in front, -1 behind.
struct CableMark {
  int shift = 1;
  int order = 1;
  bool operator==(const CableMark&) const = default;
};

/// Key of the undirected edge between two vertices.
inline std::uint64_t edge_key(int u, int v) {
  if (u > v) std::swap(u, v);
  return (static_cast<std::uint64_t>(u) << 32) | static_cast<std::uint32_t>(v);
}

/// The stitch mesh: a plain value (no OpenMesh inside), so that edits copy, compare and undo cheaply.
struct StitchMesh {
  std::vector<Eigen::Vector3d> vertices;  ///< [mm]
  std::vector<StitchFace> faces;
  std::map<std::pair<int, int>, CableMark> cables;  ///< course edges marked as cable edges, lower vertex first
  std::vector<PatternColour> palette;  ///< the yarn's colours (issue 26): empty for yarn of one colour

  bool operator==(const StitchMesh&) const = default;
};

/// Where each undirected edge is used: up to two (face, local edge) pairs.
struct EdgeUses {
  struct Use {
    int face, local;
  };
  Use use[2];
  int count = 0;
};
using EdgeTable = std::unordered_map<std::uint64_t, EdgeUses>;
EdgeTable edge_table(const StitchMesh& mesh);

/// Every rule a stitch mesh keeps: each face has two wale edges and at least one bottom and one top edge,
/// a shape with a stitch type (1 bottom and up to 3 top, up to 3 bottom and 1 top, or lace: 2 and 2, 3 and 3) and a type that fits
/// it; each edge joins at most two faces, runs opposite ways in them and is wale in both or course in both;
/// cable marks sit on inner course edges.
struct StitchReport {
  std::vector<std::pair<int, std::string>> face_problems;  ///< face id, reason
  std::vector<std::string> other_problems;                 ///< edges, cables
  int invalid_faces() const;
  bool valid() const { return face_problems.empty() && other_problems.empty(); }
  std::string summary(size_t max_lines = 10) const;
};
StitchReport validate(const StitchMesh& mesh);

/// Counts for `skein stats`.
struct StitchStats {
  int faces = 0, vertices = 0, rows = 0, increases = 0, decreases = 0, cable_edges = 0, invalid_faces = 0;
  std::map<std::string, int> stitch_types;
  bool valid = false;
};
StitchStats stitch_stats(const StitchMesh& mesh);

/// The faces of each stitch row, left to right along the wale edges (a ring row starts at a fixed face).
std::vector<std::vector<int>> faces_by_row(const StitchMesh& mesh);

/// The vertices along the top edges of stitches [from, to) of a row (positions in faces_by_row), left to
/// right: the path a cable mark takes. Throws skein::Error when the row or the stitches do not exist.
std::vector<int> top_edge_path(const StitchMesh& mesh, int row, int from, int to);

/// The stitch below a face: across its first bottom edge, where that edge is the other face's top edge; -1 if none.
int stitch_below(const StitchMesh& mesh, const EdgeTable& table, int face);

/// A plain stitch: one bottom and one top edge.
inline bool is_plain(const StitchFace& face) { return face.bottom == 1 && face.top() == 1; }
/// Steps between plain stitches: along the row (right, left) and along the wale (up into the stitch worked into
/// this one, down to the one this one is worked into). -1 where there is none or it is not plain.
enum class Step { Right, Left, Up, Down };
int step(const StitchMesh& mesh, const EdgeTable& table, int face, Step s);
/// `n` steps the same way; -1 when one fails.
int steps(const StitchMesh& mesh, const EdgeTable& table, int face, Step s, int n);

/// Rows bottom-up along the wale direction (each row after the rows its stitches are worked into), with
/// each row's level: 0 for rows worked into nothing (cast-on), else one more than the highest row below.
/// Rows in a cycle of opposite wale directions come last, in id order.
struct RowOrder {
  std::vector<int> order;
  std::vector<int> level;
};
RowOrder row_order(const StitchMesh& mesh, const std::vector<std::vector<int>>& rows, const EdgeTable& table);

}  // namespace skein::mesh
