#include "document.hpp"

#include <QUndoCommand>

#include "common/error.hpp"
#include "stitchmesh/knit_field.hpp"
#include "stitchmesh/tessellation.hpp"

namespace skein::gui {

/// One undo step: the state before and after an edit.
class StateCommand : public QUndoCommand {
public:
  StateCommand(Document& doc, const QString& text, EditState before, EditState after)
      : QUndoCommand(text), m_doc(doc), m_before(std::move(before)), m_after(std::move(after)) {}
  void undo() override { m_doc.restore(m_before); }
  void redo() override { m_doc.restore(m_after); }

private:
  Document& m_doc;
  EditState m_before, m_after;
};

Document::Document(QObject* parent) : QObject(parent) {
  m_undo.setUndoLimit(100);
}

void Document::open(const std::filesystem::path& path) {
  EditState state;
  std::optional<mesh::InputMesh> input;
  std::filesystem::path project_path;
  auto settings = m_yarn_settings;
  if (path.extension() == ".skein") {
    auto project = mesh::read_project(path);
    if (!project.input) throw Error(path.string(), "", "holds no input mesh to open");
    settings = workflow::read_yarn_settings(project.settings, path.string());
    input = std::move(project.input);
    state.stitch_size = project.stitch_size;
    state.labels = std::move(project.labels);
    state.values = std::move(project.values);
    state.stitch = std::move(project.stitch);
    project_path = path;
  } else {
    input = mesh::load_mesh(path);
  }
  m_input = std::move(input);
  m_state = std::move(state);
  m_yarn_settings = settings;
  m_path = project_path;
  m_undo.clear();
  emit opened();
  emit changed();
}

void Document::save(const std::filesystem::path& path) {
  require_input();
  mesh::Project project;
  project.stitch_size = m_state.stitch_size;
  project.input = m_input;
  project.labels = m_state.labels;
  project.values = m_state.values;
  project.stitch = m_state.stitch;
  project.settings = workflow::yarn_setting_lines(m_yarn_settings);
  mesh::write_project(project, path);
  m_path = path;
  m_undo.setClean();
}

void Document::set_yarn_settings(const workflow::YarnSettings& settings) {
  settings.validate();
  m_yarn_settings = settings;
}

void Document::apply(const QString& text, EditState next) {
  m_undo.push(new StateCommand(*this, text, m_state, std::move(next)));
}

void Document::restore(const EditState& state) {
  m_state = state;
  emit changed();
}

void Document::require_input() const {
  if (!m_input) throw Error("open a mesh first");
}

void Document::require_labels() const {
  require_input();
  if (!m_state.labels) throw Error("label the mesh first (Label > Auto-label, or the row tools)");
}

void Document::require_stitch() const {
  if (!m_state.stitch) throw Error("generate the stitch mesh first (Stitch > Generate stitch mesh)");
}

EditState Document::with_stitch(mesh::StitchMesh stitch) const {
  EditState next = m_state;
  if (m_state.stitch && m_state.yarn && m_state.yarn_relaxed) next.previous = EditState::PreviousYarn{*m_state.stitch, *m_state.yarn};
  next.stitch = std::move(stitch);
  next.yarn.reset();
  next.yarn_relaxed = false;
  return next;
}

EditState Document::with_labels(mesh::Labeling labels) const {
  EditState next = m_state;
  next.values.reset();
  if (mesh::validate_labels(*m_input, labels).valid()) next.values = mesh::initial_values(*m_input, labels, m_state.stitch_size);
  next.labels = std::move(labels);
  next.stitch.reset();
  next.rest.reset();
  next.yarn.reset();
  next.yarn_relaxed = false;
  next.previous.reset();
  return next;
}

void Document::auto_label(int border_edge) {
  require_input();
  const int start = border_edge >= 0 ? border_edge : mesh::default_start_edge(*m_input);
  apply(tr("Auto-label"), with_labels(mesh::auto_label(*m_input, start)));
}

void Document::trace_field(const mesh::KnitStart& start, const std::optional<mesh::KnitStart>& end) {
  require_input();
  auto traced = mesh::trace_stitch_mesh(*m_input, start, m_state.stitch_size, end);
  EditState state;
  state.stitch_size = m_state.stitch_size;
  state.stitch = mesh::tessellate(traced.mesh, traced.labels, traced.values);
  state.labels = std::move(traced.labels);
  state.values = std::move(traced.values);
  m_input = std::move(traced.mesh);
  m_state = std::move(state);
  m_undo.clear();
  emit opened();
  emit changed();
}

void Document::label_first_row(int border_edge) {
  require_input();
  auto labels = m_state.labels ? *m_state.labels : mesh::Labeling(*m_input);
  mesh::label_first_row(*m_input, labels, border_edge);
  apply(tr("Label first row"), with_labels(std::move(labels)));
}

void Document::label_next_row(int course_edge) {
  require_labels();
  auto labels = *m_state.labels;
  mesh::label_next_row(*m_input, labels, course_edge);
  apply(tr("Label next row"), with_labels(std::move(labels)));
}

void Document::flip_row(int row) {
  require_labels();
  auto labels = *m_state.labels;
  mesh::flip_row(labels, row);
  apply(tr("Flip row %1").arg(row), with_labels(std::move(labels)));
}

void Document::set_stitch_size(const mesh::StitchSize& size) {
  size.validate();
  EditState next = m_state;
  next.stitch_size = size;
  if (m_state.labels && mesh::validate_labels(*m_input, *m_state.labels).valid()) {
    next.values = mesh::initial_values(*m_input, *m_state.labels, size);
    if (m_state.stitch) {
      mesh::check_stitch_count(*m_input, size, mesh::kDefaultMaxStitches);
      next.stitch = mesh::tessellate(*m_input, *m_state.labels, *next.values);
      next.rest.reset();
      next.yarn.reset();
      next.yarn_relaxed = false;
    }
  }
  apply(tr("Stitch size %1 x %2 mm").arg(size.width).arg(size.height), std::move(next));
}

namespace {

/// The values and, when there was one, the stitch mesh regenerated from them.
EditState retessellated(const mesh::InputMesh& input, EditState next) {
  if (next.stitch) {
    next.stitch = mesh::tessellate(input, *next.labels, *next.values);
    next.rest.reset();
    next.yarn.reset();
    next.yarn_relaxed = false;
    next.previous.reset();
  }
  return next;
}

}  // namespace

void Document::set_edge_value(int edge, int n) {
  require_labels();
  if (!m_state.values) throw Error("the labeling is not valid yet: tessellation values need every face labeled");
  if (edge < 0 || edge >= m_input->num_edges()) throw Error("", "edge " + std::to_string(edge), "no such edge");
  EditState next = m_state;
  QString text;
  if (m_state.labels->edges[edge] == mesh::EdgeLabel::Wale) {
    const int row = m_state.labels->faces[m_input->edge_uses(edge).front().face].row;
    mesh::set_row_value(*m_input, *m_state.labels, *next.values, row, n);
    text = tr("Row %1: %2 stitch rows").arg(row).arg(n);
  } else {
    mesh::set_course_value(*m_input, *m_state.labels, *next.values, edge, n);
    text = tr("Edge %1: %2 stitches").arg(edge).arg(n);
  }
  apply(text, retessellated(*m_input, std::move(next)));
}

void Document::toggle_wale_mark(int edge) {
  require_labels();
  if (!m_state.values) throw Error("the labeling is not valid yet: tessellation values need every face labeled");
  if (edge < 0 || edge >= m_input->num_edges()) throw Error("", "edge " + std::to_string(edge), "no such edge");
  EditState next = m_state;
  const bool mark = !m_state.values->marked[edge];
  mesh::mark_wale_edge(*m_input, *m_state.labels, *next.values, edge, mark);
  apply(mark ? tr("Mark wale edge %1").arg(edge) : tr("Unmark wale edge %1").arg(edge), retessellated(*m_input, std::move(next)));
}

void Document::generate_stitch_mesh() {
  require_labels();
  const auto report = mesh::validate_labels(*m_input, *m_state.labels);
  if (!report.valid())
    throw Error("", "face " + std::to_string(report.face_problems.front().first),
                report.face_problems.front().second + " (" + std::to_string(report.face_problems.size()) + " faces cannot be tessellated)");
  EditState next = m_state;
  mesh::check_stitch_count(*m_input, m_state.stitch_size, mesh::kDefaultMaxStitches);
  if (!next.values) next.values = mesh::initial_values(*m_input, *m_state.labels, m_state.stitch_size);
  next.stitch = mesh::tessellate(*m_input, *m_state.labels, *next.values);
  next.rest.reset();
  next.previous.reset();
  next.yarn.reset();
  next.yarn_relaxed = false;
  apply(tr("Generate stitch mesh"), std::move(next));
}

void Document::paint(const std::vector<int>& faces, const std::string& type, const QString& text) {
  require_stitch();
  apply(text, with_stitch(mesh::set_stitch_type(*m_state.stitch, faces, type)));
}

void Document::fill(const std::vector<int>& faces, const mesh::Fill& pattern, const QString& name) {
  require_stitch();
  if (faces.empty()) throw Error("select the stitches to fill first (the Select tool)");
  apply(tr("Fill %1").arg(name), with_stitch(mesh::fill(*m_state.stitch, faces, pattern)));
}

mesh::TileReport Document::tile_pattern(const std::vector<int>& faces, const mesh::Pattern& pattern, int origin) {
  require_stitch();
  if (faces.empty()) throw Error("select the stitches to tile the pattern over first (the Select tool)");
  mesh::TileReport report;
  apply(tr("Tile pattern %1").arg(QString::fromStdString(pattern.name)), with_stitch(mesh::tile_pattern(*m_state.stitch, faces, pattern, origin, &report)));
  return report;
}

void Document::mark_cable(const std::vector<int>& path, int shift, int order) {
  require_stitch();
  apply(tr("Mark cable"), with_stitch(mesh::mark_cable(*m_state.stitch, path, shift, order)));
}

void Document::unmark_cable(const std::vector<int>& path) {
  require_stitch();
  apply(tr("Unmark cable"), with_stitch(mesh::unmark_cable(*m_state.stitch, path)));
}

void Document::split_course_edge(int u, int v) {
  require_stitch();
  apply(tr("Split course edge"), with_stitch(mesh::split_course_edge(*m_state.stitch, u, v)));
}

void Document::collapse_course_edge(int u, int v) {
  require_stitch();
  apply(tr("Collapse course edge"), with_stitch(mesh::collapse_course_edge(*m_state.stitch, u, v)));
}

void Document::add_wale_edge(int face) {
  require_stitch();
  apply(tr("Add wale edge"), with_stitch(mesh::add_wale_edge(*m_state.stitch, face)));
}

void Document::remove_wale_edge(int u, int v) {
  require_stitch();
  apply(tr("Remove wale edge"), with_stitch(mesh::remove_wale_edge(*m_state.stitch, u, v)));
}

void Document::shift_wale_edge(int u, int v, mesh::WaleEnd end, int direction) {
  require_stitch();
  apply(tr("Shift wale edge"), with_stitch(mesh::shift_wale_edge(*m_state.stitch, u, v, end, direction)));
}

void Document::set_relaxed_mesh(mesh::StitchMesh relaxed, const RestSize& rest) {
  require_stitch();
  EditState next = with_stitch(std::move(relaxed));
  next.rest = rest;
  next.previous.reset();  // every stitch moved: no yarn point would be emitted where it was
  apply(tr("Relax stitch mesh"), std::move(next));
}

void Document::set_yarn(relax::YarnCurves yarn, bool relaxed, const QString& text) {
  require_stitch();
  EditState next = m_state;
  next.yarn = std::move(yarn);
  next.yarn_relaxed = relaxed;
  next.yarn_preview = false;
  apply(text, std::move(next));
}

void Document::set_yarn_preview(relax::YarnCurves yarn, const QString& text) {
  require_stitch();
  EditState next = m_state;
  next.yarn = std::move(yarn);
  next.yarn_relaxed = false;
  next.yarn_preview = true;
  apply(text, std::move(next));
}

}  // namespace skein::gui
