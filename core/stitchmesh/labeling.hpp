#pragma once
#include <string>
#include <vector>

#include "stitchmesh/input_mesh.hpp"

namespace skein::mesh {

enum class EdgeLabel : unsigned char { None, Wale, Course };

/// A labeled face: its row and its two wale edges as local edge indices (edge k runs from face vertex k
/// to k+1). Walking the face loop counter-clockwise: left wale, bottom course edges, right wale, top course
/// edges. The wale direction points from the bottom edges to the top edges (Yuksel 2012 §4.1).
struct FaceLabel {
  int row = -1;
  int left = -1;
  int right = -1;
  bool labeled() const { return row >= 0; }
};

/// Labels of an input mesh (Yuksel 2012 §5.1): every edge wale or course, every face in a row, rows in
/// labeling order. Indexed by InputMesh face and edge ids.
struct Labeling {
  std::vector<EdgeLabel> edges;
  std::vector<FaceLabel> faces;
  int rows = 0;  ///< row ids are 0..rows-1, in labeling order

  explicit Labeling(const InputMesh& mesh) : edges(mesh.num_edges(), EdgeLabel::None), faces(mesh.num_faces()) {}
  Labeling() = default;
};

/// Local edge indices of a labeled face's bottom and top course edges, each in loop order.
std::vector<int> bottom_edges(const InputMesh& mesh, const FaceLabel& label, int face);
std::vector<int> top_edges(const InputMesh& mesh, const FaceLabel& label, int face);

/// The border run through a border edge: the border edges reached from it through border vertices that
/// continue straight on (exactly one inner edge meets them), so a tube end gives its whole loop and a flat
/// piece stops at its corners. Edge ids, in order along the border.
std::vector<int> border_run(const InputMesh& mesh, int border_edge);

/// Labels the first row from a border edge: its border run becomes course, the faces on it form the
/// first row with the run as their bottom, and the row grows through its wale edges (Yuksel Fig. 11).
/// Returns the ids of the rows made. Throws skein::Error when the edge is not a border edge.
std::vector<int> label_first_row(const InputMesh& mesh, Labeling& labels, int border_edge);

/// Labels the row across a course edge of a labeled row: above it when the edge is a top edge there,
/// below it when it is a bottom edge. Returns the new row id. Throws skein::Error when the edge is not a
/// course edge between a labeled and an unlabeled face.
int label_next_row(const InputMesh& mesh, Labeling& labels, int course_edge);

/// Flips the wale direction of every face of a row (its labeling order reversed).
void flip_row(Labeling& labels, int row);

/// Labels the whole mesh starting from one border edge (every piece without a labeled neighbour starts
/// again from its own lowest border edge), then orients the rows so that as few course edges as possible
/// separate rows of opposite wale direction. Faces that cannot be labeled stay unlabeled and are named by
/// validate_labels.
Labeling auto_label(const InputMesh& mesh, int border_edge);
/// A border edge to start from when the user gives none: the lowest border edge (smallest y, then id).
int default_start_edge(const InputMesh& mesh);

/// What is wrong with a labeling. Faces in `face_problems` block tessellation; mismatched wale directions
/// are allowed (they give closed yarn loops, Yuksel §4.4) and are listed so the user can flip rows.
struct LabelReport {
  std::vector<std::pair<int, std::string>> face_problems;  ///< face id, reason
  std::vector<std::pair<int, std::string>> mismatches;     ///< edge id, which faces disagree
  bool valid() const { return face_problems.empty(); }
};
LabelReport validate_labels(const InputMesh& mesh, const Labeling& labels);

}  // namespace skein::mesh
