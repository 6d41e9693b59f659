#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <QObject>
#include <QUndoStack>

#include "relax/yarn_curves.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/knit_field.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/project.hpp"
#include "workflow/yarn_settings.hpp"

namespace skein::gui {

/// The rest size of a stitch found by mesh relaxation, for the stretch colours.
struct RestSize {
  double r_course = 0, r_wale = 0;
  bool operator==(const RestSize&) const = default;
};

/// Everything an edit can change, as one plain value: an edit computes the next value from the current one
/// (core edits return copies), so undo is putting the previous value back.
struct EditState {
  mesh::StitchSize stitch_size;
  std::optional<mesh::Labeling> labels;
  std::optional<mesh::TessellationValues> values;
  std::optional<mesh::StitchMesh> stitch;
  std::optional<RestSize> rest;         ///< after mesh relaxation; dropped with the stitch mesh it belongs to
  std::optional<relax::YarnCurves> yarn;  ///< emitted (or relaxed) from the current stitch mesh
  bool yarn_relaxed = false;
  bool yarn_preview = false;  ///< the yarn is a stand-in preview (workflow::stand_in_preview), neither emitted nor relaxed
  /// The last relaxed yarn and the stitch mesh it was emitted from, kept through stitch edits: relaxing the
  /// yarn again starts from it and relaxes only the stitches changed since (workflow::relax_locally). Dropped
  /// when the stitch mesh is made anew or relaxed (every stitch moves).
  struct PreviousYarn {
    mesh::StitchMesh stitch;
    relax::YarnCurves relaxed;
  };
  std::optional<PreviousYarn> previous;
};

/// The open garment: its input mesh and the undoable edit state. Every edit is a method that throws
/// skein::Error with the reason when it is refused, leaving the state as it was; a successful edit is one step
/// on the undo stack. Edits keep the state consistent: new labels drop the stitch mesh, new tessellation
/// values regenerate it, a stitch-mesh edit drops the yarn.
class Document : public QObject {
  Q_OBJECT
public:
  explicit Document(QObject* parent = nullptr);

  const std::optional<mesh::InputMesh>& input() const { return m_input; }
  const EditState& state() const { return m_state; }
  QUndoStack* undo_stack() { return &m_undo; }
  /// The project file the document was opened from or saved to; empty for a mesh not yet saved.
  const std::filesystem::path& path() const { return m_path; }

  /// Opens a mesh (any format assimp reads) or a `.skein` project; clears the undo history.
  void open(const std::filesystem::path& path);
  /// Writes the project (`.skein`, atomically), the yarn settings with it, and remembers the path.
  void save(const std::filesystem::path& path);
  /// What the yarn relaxations and the preview run with (Relax > Yarn settings), saved with the project: a
  /// project opened brings its own (the defaults when it has none), a mesh opened keeps the current ones.
  const workflow::YarnSettings& yarn_settings() const { return m_yarn_settings; }
  void set_yarn_settings(const workflow::YarnSettings& settings);  ///< throws skein::Error for a value out of range

  // Labeling (Yuksel 2012 §5.1)
  void auto_label(int border_edge = -1);  ///< -1: the lowest border edge
  /// Traces the rows on any surface from the knitting field (mesh::trace_stitch_mesh, from `start`: a border
  /// edge, a point, or by default the lowest border edge; toward `end` when given): the traced rows, one face a
  /// stitch, replace the input mesh, labeled, with the stitch mesh generated. Like opening a file, this clears
  /// the undo history.
  void trace_field(const mesh::KnitStart& start = {}, const std::optional<mesh::KnitStart>& end = {});
  void label_first_row(int border_edge);
  void label_next_row(int course_edge);
  void flip_row(int row);

  // Tessellation (§5.2)
  void set_stitch_size(const mesh::StitchSize& size);
  void set_edge_value(int edge, int n);  ///< a course edge's stitch count, or the stitch rows of a wale edge's row
  void toggle_wale_mark(int edge);
  void generate_stitch_mesh();

  // Stitch-mesh edits (§5.3)
  void paint(const std::vector<int>& faces, const std::string& type, const QString& text);
  void fill(const std::vector<int>& faces, const mesh::Fill& fill, const QString& name);
  /// Face ids change where the pattern re-meshes (report.repeats > 0).
  mesh::TileReport tile_pattern(const std::vector<int>& faces, const mesh::Pattern& pattern, int origin);
  void mark_cable(const std::vector<int>& path, int shift, int order);
  void unmark_cable(const std::vector<int>& path);
  void split_course_edge(int u, int v);
  void collapse_course_edge(int u, int v);
  void add_wale_edge(int face);
  void remove_wale_edge(int u, int v);
  void shift_wale_edge(int u, int v, mesh::WaleEnd end, int direction);

  // Results of the relaxations and of yarn emission (undoable too)
  void set_relaxed_mesh(mesh::StitchMesh relaxed, const RestSize& rest);
  void set_yarn(relax::YarnCurves yarn, bool relaxed, const QString& text);
  /// The yarn shown as a stand-in preview, as one undo step.
  void set_yarn_preview(relax::YarnCurves yarn, const QString& text);

  /// Makes `next` the state, as one undo step named `text` (what the other edits call).
  void apply(const QString& text, EditState next);

signals:
  /// The state changed (an edit, undo or redo).
  void changed();
  /// A new file was opened: views fit the camera to it.
  void opened();

private:
  void require_input() const;
  void require_labels() const;
  void require_stitch() const;
  /// `next` with its stitch mesh replaced by `stitch`: the yarn made from the old one goes.
  EditState with_stitch(mesh::StitchMesh stitch) const;
  /// `next` with new labels: fresh tessellation values when the labels are valid, no stitch mesh.
  EditState with_labels(mesh::Labeling labels) const;

  friend class StateCommand;
  void restore(const EditState& state);

  std::optional<mesh::InputMesh> m_input;
  EditState m_state;
  QUndoStack m_undo;
  std::filesystem::path m_path;
  workflow::YarnSettings m_yarn_settings;
};

}  // namespace skein::gui
