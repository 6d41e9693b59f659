#include "main_window.hpp"
#include "smocking_dialog.hpp"
#include "woven_dialog.hpp"

#include <algorithm>
#include <set>

#include <QActionGroup>
#include <QApplication>
#include <QDockWidget>
#include <QFileDialog>
#include <QInputDialog>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QMessageBox>
#include <QPainter>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QStatusBar>
#include <QToolBar>

#include "common/error.hpp"
#include "render/stitch_view.hpp"
#include "skein/config.hpp"
#include "stitchmesh/fabric.hpp"
#include "stitchmesh/stitch_types.hpp"
#include "stitchmesh/tessellation.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/garment_fabric.hpp"
#include "workflow/yarn_io.hpp"
#include "workflow/yarn_standin.hpp"
#include "viewport.hpp"
#include "yarn_settings.hpp"

namespace skein::gui {
namespace {

/// The yarn of the state's stitch mesh as emitted: at a tenth of the stitch width, or with a yarn weight in the
/// settings at the weight's compressed contact radius and drawn at its full one (YarnRelaxJob relaxes it at the first).
relax::YarnCurves emitted_yarn(const EditState& state, const YarnSettings& settings) {
  if (settings.weight.empty()) return mesh::emit_yarn(*state.stitch, mesh::StitchLibrary::bundled(), {.yarn_radius = 0.1 * state.stitch_size.width});
  const auto fabric = workflow::garment_fabric(settings.weight, state.stitch_size);
  auto yarn = mesh::emit_yarn(*state.stitch, mesh::StitchLibrary::bundled(), {.yarn_radius = fabric.contact_radius});
  yarn.radius = fabric.radius;
  return yarn;
}

/// The radius emitted_yarn draws the yarn at.
double drawn_radius(const EditState& state, const YarnSettings& settings) {
  return settings.weight.empty() ? 0.1 * state.stitch_size.width : workflow::garment_fabric(settings.weight, state.stitch_size).radius;
}

std::filesystem::path fs_path(const QString& path) { return std::filesystem::path(path.toStdString()); }

QIcon swatch(const Eigen::Vector3f& color) {
  QPixmap pixmap(16, 16);
  pixmap.fill(QColor::fromRgbF(color.x(), color.y(), color.z()));
  return QIcon(pixmap);
}

bool fits(const mesh::StitchFace& face, const std::string& type) {
  const auto* t = mesh::find_stitch_type(type);
  return t && t->bottom == face.bottom && t->top == face.top();
}

const char* kFills[] = {"stockinette", "reverse", "rib", "rib2x2", "garter", "seed", "moss"};

}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  setWindowTitle(tr("skein"));
  m_view = new Viewport(this);
  setCentralWidget(m_view);
  connect(m_view, &Viewport::pressed, this, &MainWindow::on_pressed);
  connect(m_view, &Viewport::dragged, this, &MainWindow::on_dragged);
  connect(m_view, &Viewport::released, this, &MainWindow::on_released);
  connect(m_view, &Viewport::gl_failed, this, [this](const QString& reason) { show_error(tr("The 3D view cannot draw: %1").arg(reason)); });
  connect(&m_doc, &Document::changed, this, &MainWindow::refresh);
  connect(m_doc.undo_stack(), &QUndoStack::indexChanged, this, [this] {
    if (const auto text = m_doc.undo_stack()->undoText(); !text.isEmpty()) statusBar()->showMessage(text);
  });
  connect(&m_doc, &Document::opened, this, [this] {
    m_selected.clear();
    m_trace_end.reset();  // an end Shift+clicked on the mesh before, whose edge ids this one does not share
    set_layer(m_doc.state().stitch ? Layer::Stitch : Layer::Input);
    m_view->fit();
  });
  build_actions();
  build_docks();
  m_job_label = new QLabel(this);
  m_progress = new QProgressBar(this);
  m_progress->setRange(0, 1000);
  m_progress->setMaximumWidth(220);
  m_progress->hide();
  statusBar()->addPermanentWidget(m_job_label);
  statusBar()->addPermanentWidget(m_progress);
  statusBar()->showMessage(tr("Open a garment mesh or a .skein project (File > Open)"));
  resize(1280, 860);
  refresh();
}

MainWindow::~MainWindow() = default;

template <class F>
bool MainWindow::attempt(F&& edit) {
  try {
    edit();
    return true;
  } catch (const std::exception& e) {
    show_error(QString::fromStdString(e.what()));
    return false;
  }
}

void MainWindow::show_error(const QString& text) {
  m_last_error = text;
  statusBar()->showMessage(tr("Error: %1").arg(text));
  if (!m_error_box) {
    m_error_box = new QMessageBox(QMessageBox::Warning, tr("skein"), text, QMessageBox::Ok, this);
    m_error_box->setAttribute(Qt::WA_DeleteOnClose);
    m_error_box->setModal(false);
  }
  m_error_box->setText(text);
  m_error_box->show();
}

QString MainWindow::status_text() const { return statusBar()->currentMessage(); }
QString MainWindow::job_text() const { return m_job_label->text(); }

void MainWindow::build_actions() {
  const auto add = [this](QMenu* menu, const QString& text, const char* name, auto slot, QKeySequence key = {}, bool edits = false) {
    auto* action = menu->addAction(text);
    action->setObjectName(name);
    if (!key.isEmpty()) action->setShortcut(key);
    connect(action, &QAction::triggered, this, slot);
    if (edits) m_edit_actions.push_back(action);
    return action;
  };

  auto* file = menuBar()->addMenu(tr("&File"));
  add(file, tr("&Open mesh or project..."), "open", [this] {
    const auto path = QFileDialog::getOpenFileName(this, tr("Open"), {}, tr("Meshes and projects (*.skein *.obj *.ply *.off *.stl *.gltf *.glb *.fbx *.dae);;All files (*)"));
    if (!path.isEmpty()) open_file(path);
  }, QKeySequence::Open, true);
  add(file, tr("&Save project"), "save", [this] {
    if (!m_doc.path().empty()) save_project(QString::fromStdString(m_doc.path().string()));
    else if (const auto path = QFileDialog::getSaveFileName(this, tr("Save project"), {}, tr("skein projects (*.skein)")); !path.isEmpty()) save_project(path);
  }, QKeySequence::Save);
  add(file, tr("Save project &as..."), "saveAs", [this] {
    if (const auto path = QFileDialog::getSaveFileName(this, tr("Save project"), {}, tr("skein projects (*.skein)")); !path.isEmpty()) save_project(path);
  }, QKeySequence::SaveAs);
  file->addSeparator();
  add(file, tr("Export &yarn (.bcc, .obj tubes)..."), "exportYarn", [this] {
    if (const auto path = QFileDialog::getSaveFileName(this, tr("Export yarn"), {}, tr("Yarn (*.bcc *.obj)")); !path.isEmpty()) export_yarn(path);
  });
  add(file, tr("Export &stitch mesh (.ply)..."), "exportStitch", [this] {
    if (const auto path = QFileDialog::getSaveFileName(this, tr("Export stitch mesh"), {}, tr("PLY with face colours (*.ply)")); !path.isEmpty())
      export_stitch_ply(path);
  });
  add(file, tr("Export &picture (.png)..."), "exportPicture", [this] {
    if (const auto path = QFileDialog::getSaveFileName(this, tr("Export picture"), {}, tr("PNG (*.png)")); !path.isEmpty()) export_picture(path);
  });
  file->addSeparator();
  add(file, tr("S&mocking preview..."), "smockingPreview", [this] {
    auto* dialog = new SmockingDialog(this);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    dialog->show();
  });
  add(file, tr("&Woven preview..."), "wovenPreview", [this] {
    auto* dialog = new WovenDialog(this);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    dialog->show();
  });
  file->addSeparator();
  add(file, tr("&Quit"), "quit", [this] { close(); }, QKeySequence::Quit);

  auto* edit = menuBar()->addMenu(tr("&Edit"));
  auto* undo = m_doc.undo_stack()->createUndoAction(this, tr("&Undo"));
  undo->setShortcut(QKeySequence::Undo);
  undo->setObjectName("undo");
  auto* redo = m_doc.undo_stack()->createRedoAction(this, tr("&Redo"));
  redo->setShortcut(QKeySequence::Redo);
  redo->setObjectName("redo");
  edit->addAction(undo);
  edit->addAction(redo);
  m_edit_actions.push_back(undo);
  m_edit_actions.push_back(redo);

  auto* view = menuBar()->addMenu(tr("&View"));
  auto* layers = new QActionGroup(this);
  for (auto [text, name, layer] : {std::tuple{tr("&Input mesh and labels"), "layerInput", Layer::Input},
                                   std::tuple{tr("&Stitch mesh"), "layerStitch", Layer::Stitch}, std::tuple{tr("&Yarn"), "layerYarn", Layer::Yarn}}) {
    auto* a = add(view, text, name, [this, layer = layer] { set_layer(layer); });
    a->setCheckable(true);
    a->setData(static_cast<int>(layer));
    layers->addAction(a);
  }
  view->addSeparator();
  auto* colorings = new QActionGroup(this);
  for (auto [text, name, coloring] : {std::tuple{tr("Colour by stitch &type"), "colorType", Coloring::StitchType},
                                      std::tuple{tr("Colour by &row"), "colorRow", Coloring::Row},
                                      std::tuple{tr("Colour by s&tretch"), "colorStretch", Coloring::Stretch},
                                      std::tuple{tr("Colour by &yarn colour"), "colorYarn", Coloring::YarnColour}}) {
    auto* a = add(view, text, name, [this, coloring = coloring] { set_coloring(coloring); });
    a->setCheckable(true);
    a->setData(static_cast<int>(coloring));
    colorings->addAction(a);
  }
  view->addSeparator();
  add(view, tr("&Fit view"), "fit", [this] { m_view->fit(); }, QKeySequence(Qt::Key_F));

  m_tools = new QActionGroup(this);
  auto* toolbar = addToolBar(tr("Tools"));
  toolbar->setObjectName("tools");
  const auto tool = [&](QMenu* menu, const QString& text, const char* name, Tool t, const QString& tip) {
    auto* a = add(menu, text, name, [this, t] { set_tool(t); }, {}, true);
    a->setCheckable(true);
    a->setData(static_cast<int>(t));
    a->setStatusTip(tip);
    a->setToolTip(tip);
    m_tools->addAction(a);
    toolbar->addAction(a);
    return a;
  };
  auto* label = menuBar()->addMenu(tr("&Label"));
  tool(label, tr("&Orbit"), "toolOrbit", Tool::Orbit, tr("Left-drag turns the view"))->setChecked(true);
  add(label, tr("&Auto-label"), "autoLabel", [this] { attempt([&] { m_doc.auto_label(); }); }, QKeySequence(tr("Ctrl+L")), true);
  add(label, tr("&Trace rows from the knitting field (any surface)"), "traceField", [this] { attempt([&] { m_doc.trace_field(); }); }, {}, true);
  tool(label, tr("Trace rows from &here"), "toolTraceFrom", Tool::TraceFrom,
       tr("Click a border edge (or, on a closed surface, a point) where knitting starts: rows are traced from there by the knitting "
          "field; Shift+click first where they should end"));
  tool(label, tr("&First row"), "toolFirstRow", Tool::FirstRow, tr("Click a border edge: its border becomes the first row"));
  tool(label, tr("&Next row"), "toolNextRow", Tool::NextRow, tr("Click a course edge of a labeled row: label the row across it"));
  tool(label, tr("F&lip row"), "toolFlipRow", Tool::FlipRow, tr("Click a face: flip the wale direction of its row"));
  toolbar->addSeparator();

  auto* stitch = menuBar()->addMenu(tr("&Stitch"));
  add(stitch, tr("Stitch &size..."), "stitchSize", [this] {
    bool ok = false;
    const double w = QInputDialog::getDouble(this, tr("Stitch size"), tr("Stitch width along the course [mm]"), m_doc.state().stitch_size.width, 0.1, 1000, 2, &ok);
    if (!ok) return;
    const double h = QInputDialog::getDouble(this, tr("Stitch size"), tr("Stitch height along the wale [mm]"), m_doc.state().stitch_size.height, 0.1, 1000, 2, &ok);
    if (ok) attempt([&] { m_doc.set_stitch_size({w, h}); });
  }, {}, true);
  add(stitch, tr("Stitch size from &gauge..."), "stitchGauge", [this] {
    // A gauge as a yarn label gives it: stitches and rows in 10 cm of stockinette (rows 0: Munden's loop shape, 1.3 x).
    const auto now = mesh::gauge_of(m_doc.state().stitch_size);
    bool ok = false;
    const double st = QInputDialog::getDouble(this, tr("Gauge"), tr("Stitches in 10 cm of stockinette"), now.stitches, 0.1, 1000, 1, &ok);
    if (!ok) return;
    const double rows = QInputDialog::getDouble(this, tr("Gauge"), tr("Rows in 10 cm (0: %1 x the stitches, relaxed plain knit)").arg(mesh::kLoopShapeFactor),
                                                0, 0, 1000, 1, &ok);
    if (!ok) return;
    attempt([&] {
      const mesh::Gauge gauge{st, rows > 0 ? rows : mesh::kLoopShapeFactor * st};
      gauge.validate();
      m_doc.set_stitch_size(gauge.stitch_size());
    });
  }, {}, true);
  add(stitch, tr("Stitch size from &needle..."), "stitchNeedle", [this] {
    const std::string weight = m_doc.yarn_settings().weight;
    const double middle = weight.empty() ? 4 : mesh::find_yarn_weight(weight).needle_mm;
    bool ok = false;
    const double needle = QInputDialog::getDouble(this, tr("Needle"), tr("Needle diameter [mm] (the yarn: Relax > Yarn settings > Yarn weight)"), middle, 0.5, 50, 2, &ok);
    if (ok) set_stitch_size_from_needle(needle);
  }, {}, true);
  tool(stitch, tr("Tessellation &value"), "toolEdgeValue", Tool::EdgeValue, tr("Click an edge: set how many stitches (course) or stitch rows (wale) it gets"));
  tool(stitch, tr("&Mark wale edge"), "toolMarkWale", Tool::MarkWale, tr("Click a wale edge: increases and decreases of its faces go next to it"));
  add(stitch, tr("&Generate stitch mesh"), "generate", [this] {
    if (attempt([&] { m_doc.generate_stitch_mesh(); })) set_layer(Layer::Stitch);
  }, QKeySequence(tr("Ctrl+G")), true);
  toolbar->addSeparator();

  auto* paint = menuBar()->addMenu(tr("&Paint"));
  tool(paint, tr("&Paint stitches"), "toolPaint", Tool::Paint, tr("Click or drag over stitches: give them the palette's stitch type"));
  tool(paint, tr("&Select stitches"), "toolSelect", Tool::Select, tr("Click or drag: select stitches (Shift adds, Ctrl removes)"));
  add(paint, tr("Select &all"), "selectAll", [this] {
    if (m_doc.state().stitch) m_selected.assign(m_doc.state().stitch->faces.size(), 1);
    refresh();
  }, QKeySequence::SelectAll);
  add(paint, tr("Select &border rows"), "selectBorder", [this] {
    if (!m_doc.state().stitch) return;
    set_selection(mesh::faces_near_border(*m_doc.state().stitch, 4));
  });
  add(paint, tr("&Clear selection"), "selectNone", [this] { set_selection({}); });
  auto* fills = paint->addMenu(tr("&Fill selection"));
  for (const char* name : kFills) add(fills, QString::fromLatin1(name), (std::string("fill_") + name).c_str(), [this, name] { fill_selection(name); }, {}, true);
  add(paint, tr("&Tile pattern on selection..."), "tilePattern", [this] {
    const auto path = QFileDialog::getOpenFileName(this, tr("Pattern"), QString::fromLatin1(SKEIN_SOURCE_DIR "/patterns"), tr("Knitting patterns (*.knit)"));
    if (!path.isEmpty()) tile_pattern_file(path);
  }, {}, true);
  paint->addSeparator();
  add(paint, tr("Cable over selection, crossing in &front"), "cableFront", [this] { mark_cable_on_selection(1); }, {}, true);
  add(paint, tr("Cable over selection, crossing &behind"), "cableBehind", [this] { mark_cable_on_selection(-1); }, {}, true);
  add(paint, tr("&Unmark cables over selection"), "cableUnmark", [this] { mark_cable_on_selection(0); }, {}, true);
  paint->addSeparator();
  tool(paint, tr("Split course edge"), "toolSplit", Tool::SplitCourse, tr("Click a course edge: split it (an increase below, a decrease above)"));
  tool(paint, tr("Collapse course edge"), "toolCollapse", Tool::CollapseCourse, tr("Click a course edge: collapse it"));
  tool(paint, tr("Add wale edge"), "toolAddWale", Tool::AddWale, tr("Click a stitch: split it in two with a wale edge"));
  tool(paint, tr("Remove wale edge"), "toolRemoveWale", Tool::RemoveWale, tr("Click a wale edge: merge its two stitches"));
  tool(paint, tr("Shift wale edge"), "toolShiftWale", Tool::ShiftWale, tr("Click near an end of a wale edge: move that end right (Shift: left)"));

  auto* relax = menuBar()->addMenu(tr("&Relax"));
  add(relax, tr("Relax &stitch mesh"), "relaxMesh", [this] { relax_mesh(); }, QKeySequence(tr("Ctrl+R")), true);
  add(relax, tr("&Emit yarn"), "emitYarn", [this] { emit_yarn(); }, QKeySequence(tr("Ctrl+E")), true);
  add(relax, tr("Relax &yarn"), "relaxYarn", [this] { relax_yarn(); }, QKeySequence(tr("Ctrl+Y")), true);
  add(relax, tr("Pre&view yarn (stand-in)"), "previewYarn", [this] { preview_yarn(); }, {}, true);
  m_pause = add(relax, tr("&Pause"), "pause", [this] { pause_or_resume(); });
  m_stop = add(relax, tr("S&top"), "stop", [this] { stop_job(); });
  m_pause->setEnabled(false);
  m_stop->setEnabled(false);
  relax->addSeparator();
  add(relax, tr("Yarn &settings..."), "yarnSettings", [this] {
    YarnSettingsDialog dialog(m_doc.yarn_settings(), this);
    if (dialog.exec() == QDialog::Accepted) set_yarn_settings(dialog.settings());
  });
  auto* backends = new QActionGroup(this);
  auto* backend_menu = relax->addMenu(tr("Yarn &backend"));
  for (auto [text, name, backend] : {std::tuple{tr("&Auto (GPU when one answers)"), "backendAuto", relax::Backend::Auto},
                                     std::tuple{tr("&CPU"), "backendCpu", relax::Backend::Cpu}, std::tuple{tr("C&UDA"), "backendCuda", relax::Backend::Cuda}}) {
    auto* a = add(backend_menu, text, name, [this, backend = backend] { m_backend = backend; });
    a->setCheckable(true);
    a->setChecked(backend == relax::Backend::Auto);
    backends->addAction(a);
  }

  auto* help = menuBar()->addMenu(tr("&Help"));
  add(help, tr("&Controls"), "controls", [this] {
    QMessageBox::information(this, tr("Controls"),
                             tr("Right-drag: orbit. Middle-drag or Shift+right-drag: pan. Wheel: zoom. F: fit the view.\n"
                                "Left button: the active tool (Orbit turns the view).\n"
                                "Label: Auto-label, or First row on a border edge, then Next row on course edges;\n"
                                "any surface (triangles, poles, branches): Trace rows from the knitting field.\n"
                                "Stitch: Generate the stitch mesh; Tessellation value and Mark wale edge change it.\n"
                                "Paint: pick a stitch type in the palette and paint; fills and patterns act on the selection."));
  });
}

void MainWindow::build_docks() {
  auto* palette_dock = new QDockWidget(tr("Stitch palette"), this);
  palette_dock->setObjectName("palette");
  m_palette = new QListWidget(palette_dock);
  for (const auto& type : mesh::stitch_types()) {
    auto* item = new QListWidgetItem(swatch(render::stitch_color(type.name)), QString::fromStdString(type.name), m_palette);
    item->setToolTip(tr("%1: %2 bottom, %3 top edges").arg(QString::fromStdString(type.name)).arg(type.bottom).arg(type.top));
  }
  connect(m_palette, &QListWidget::currentTextChanged, this, [this](const QString& type) {
    if (!type.isEmpty()) m_paint_type = type;
  });
  palette_dock->setWidget(m_palette);
  addDockWidget(Qt::LeftDockWidgetArea, palette_dock);
  set_paint_type(m_paint_type);

  auto* info_dock = new QDockWidget(tr("Garment"), this);
  info_dock->setObjectName("info");
  m_info = new QPlainTextEdit(info_dock);
  m_info->setReadOnly(true);
  m_info->setMinimumWidth(260);
  info_dock->setWidget(m_info);
  addDockWidget(Qt::RightDockWidgetArea, info_dock);
}

void MainWindow::set_tool(Tool tool) {
  if (tool != m_tool) m_trace_end.reset();
  m_tool = tool;
  for (auto* a : m_tools->actions())
    if (a->data().toInt() == static_cast<int>(tool)) a->setChecked(true);
  m_view->set_left_orbits(tool == Tool::Orbit);
  const bool on_input = tool == Tool::FirstRow || tool == Tool::NextRow || tool == Tool::FlipRow || tool == Tool::EdgeValue || tool == Tool::MarkWale ||
                        tool == Tool::TraceFrom;
  if (on_input && m_layer != Layer::Input) set_layer(Layer::Input);
  if (!on_input && tool != Tool::Orbit && m_layer != Layer::Stitch) set_layer(Layer::Stitch);
}

void MainWindow::set_layer(Layer layer) {
  m_layer = layer;
  for (auto* a : findChildren<QAction*>())
    if (a->objectName().startsWith("layer")) a->setChecked(a->data().toInt() == static_cast<int>(layer));
  refresh();
}

void MainWindow::set_coloring(Coloring coloring) {
  m_coloring = coloring;
  for (auto* a : findChildren<QAction*>())
    if (a->objectName().startsWith("color")) a->setChecked(a->data().toInt() == static_cast<int>(coloring));
  if (m_layer != Layer::Stitch) set_layer(Layer::Stitch);
  else refresh();
}

void MainWindow::set_paint_type(const QString& type) {
  m_paint_type = type;
  const auto items = m_palette->findItems(type, Qt::MatchExactly);
  if (!items.isEmpty()) m_palette->setCurrentItem(items.front());
}

void MainWindow::set_selection(const std::vector<int>& faces) {
  m_selected.assign(m_doc.state().stitch ? m_doc.state().stitch->faces.size() : 0, 0);
  for (int f : faces)
    if (f >= 0 && f < static_cast<int>(m_selected.size())) m_selected[f] = 1;
  refresh();
}

std::vector<int> MainWindow::selection() const {
  std::vector<int> faces;
  for (int f = 0; f < static_cast<int>(m_selected.size()); ++f)
    if (m_selected[f]) faces.push_back(f);
  return faces;
}

void MainWindow::refresh() {
  const auto& state = m_doc.state();
  const size_t faces = state.stitch ? state.stitch->faces.size() : 0;
  if (m_selected.size() != faces) m_selected.assign(faces, 0);
  Geometry g;
  if (m_layer == Layer::Yarn && state.yarn) g = yarn_geometry(*state.yarn);
  else if (m_layer != Layer::Input && state.stitch)
    g = stitch_geometry(m_stroke.empty() ? *state.stitch : m_stroke_preview, m_coloring, state.rest, m_selected);
  else if (m_doc.input()) g = input_geometry(*m_doc.input(), state.labels, state.values);
  m_view->show_geometry(std::move(g), false);
  refresh_info();
  setWindowTitle(m_doc.input() ? tr("skein — %1").arg(QString::fromStdString(
                                     m_doc.path().empty() ? m_doc.input()->source() : m_doc.path().filename().string()))
                               : tr("skein"));
}

void MainWindow::refresh_info() {
  QStringList lines;
  const auto& state = m_doc.state();
  if (const auto& input = m_doc.input()) {
    lines << tr("Input mesh: %1 faces, %2 edges").arg(input->num_faces()).arg(input->num_edges());
    lines << tr("Stitch size: %1 x %2 mm").arg(state.stitch_size.width).arg(state.stitch_size.height);
    if (state.labels) {
      const auto report = mesh::validate_labels(*input, *state.labels);
      lines << tr("Rows labeled: %1").arg(state.labels->rows);
      if (report.valid()) lines << tr("Labels: valid");
      for (size_t i = 0; i < std::min<size_t>(report.face_problems.size(), 8); ++i)
        lines << tr("  face %1: %2").arg(report.face_problems[i].first).arg(QString::fromStdString(report.face_problems[i].second));
      if (report.face_problems.size() > 8) lines << tr("  ... %1 faces in all cannot be tessellated").arg(report.face_problems.size());
      if (!report.mismatches.empty()) lines << tr("Rows of opposite wale direction meet at %1 edges (closed loops)").arg(report.mismatches.size());
    } else {
      lines << tr("Not labeled: Label > Auto-label");
    }
  }
  if (state.stitch) {
    const auto stats = mesh::stitch_stats(*state.stitch);
    lines << "" << tr("Stitch mesh: %1 stitches in %2 rows").arg(stats.faces).arg(stats.rows);
    lines << tr("Increases %1, decreases %2, cable edges %3").arg(stats.increases).arg(stats.decreases).arg(stats.cable_edges);
    for (const auto& [type, count] : stats.stitch_types) lines << tr("  %1: %2").arg(QString::fromStdString(type)).arg(count);
    if (state.rest) lines << tr("Relaxed: rest course edge %1 mm, wale edge %2 mm").arg(state.rest->r_course, 0, 'f', 2).arg(state.rest->r_wale, 0, 'f', 2);
    const auto selected = std::count(m_selected.begin(), m_selected.end(), 1);
    if (selected > 0) lines << tr("Selected: %1 stitches").arg(selected);
  }
  if (state.yarn)
    lines << "" << tr("Yarn: %1 curves, %2 control points, %3").arg(state.yarn->curves()).arg(state.yarn->points.size())
                       .arg(state.yarn_relaxed ? tr("relaxed") : tr("as emitted"));
  m_info->setPlainText(lines.join('\n'));
}

bool MainWindow::open_file(const QString& path) {
  if (job_running()) return false;
  const bool ok = attempt([&] { m_doc.open(fs_path(path)); });
  if (ok) statusBar()->showMessage(tr("Opened %1").arg(path));
  return ok;
}

bool MainWindow::save_project(const QString& path) {
  const bool ok = attempt([&] { m_doc.save(fs_path(path)); });
  if (ok) {
    statusBar()->showMessage(tr("Saved %1").arg(path));
    refresh_info();
  }
  return ok;
}

bool MainWindow::export_yarn(const QString& path) {
  return attempt([&] {
    if (!m_doc.state().yarn) throw Error("there is no yarn yet: Relax > Emit yarn");
    const auto p = fs_path(path);
    if (p.extension() == ".bcc") workflow::write_bcc(*m_doc.state().yarn, p);
    else if (p.extension() == ".obj") workflow::write_tube_obj(*m_doc.state().yarn, p);
    else throw Error(path.toStdString(), "", "yarn is exported as .bcc or .obj");
    statusBar()->showMessage(tr("Wrote %1").arg(path));
  });
}

bool MainWindow::export_stitch_ply(const QString& path) {
  return attempt([&] {
    const auto& state = m_doc.state();
    if (!state.stitch) throw Error("there is no stitch mesh yet: Stitch > Generate stitch mesh");
    std::vector<std::pair<std::string, std::vector<double>>> values;
    if (state.rest) values.emplace_back("area_strain", surface::face_stretch(*state.stitch, state.rest->r_course, state.rest->r_wale).area_strain);
    render::write_ply(*state.stitch, face_colors(*state.stitch, m_coloring, state.rest), values, fs_path(path));
    statusBar()->showMessage(tr("Wrote %1").arg(path));
  });
}

bool MainWindow::export_picture(const QString& path) {
  return attempt([&] {
    const QImage image = m_view->grabFramebuffer();
    if (image.isNull()) throw Error(path.toStdString(), "", "the view could not be read back");
    // Written beside the target and renamed, so that a failed write leaves no partial file.
    const QString temporary = path + ".part";
    if (!image.save(temporary, "PNG")) {
      QFile::remove(temporary);
      throw Error(path.toStdString(), "", "cannot be written");
    }
    QFile::remove(path);
    if (!QFile::rename(temporary, path)) throw Error(path.toStdString(), "", "cannot be written");
    statusBar()->showMessage(tr("Wrote %1").arg(path));
  });
}

bool MainWindow::fill_selection(const QString& name) {
  return attempt([&] { m_doc.fill(selection(), mesh::parse_fill(name.toStdString()), name); });
}

bool MainWindow::tile_pattern_file(const QString& path) {
  return attempt([&] {
    const auto pattern = mesh::read_pattern(fs_path(path));
    const auto faces = selection();
    if (!m_doc.state().stitch) throw Error("generate the stitch mesh first (Stitch > Generate stitch mesh)");
    if (faces.empty()) throw Error("select the stitches to tile the pattern over first (the Select tool)");
    const auto tiled = m_doc.tile_pattern(faces, pattern, mesh::lowest_left(*m_doc.state().stitch, faces));
    if (tiled.repeats > 0) {
      if (std::none_of(m_tiled_patterns.begin(), m_tiled_patterns.end(), [&](const mesh::Pattern& p) { return p.rows == pattern.rows && p.cables == pattern.cables; }))
        m_tiled_patterns.push_back(pattern);
      set_selection({});  // the stitches were re-meshed: their ids are new
      statusBar()->showMessage(tr("Tiled %1: %2 whole repeats re-meshed (%3 of the %4 selected stitches)")
                                   .arg(QString::fromStdString(pattern.name)).arg(tiled.repeats).arg(tiled.stitches).arg(faces.size()));
    } else {
      statusBar()->showMessage(tr("Tiled %1 over %2 of the %3 selected stitches").arg(QString::fromStdString(pattern.name)).arg(tiled.stitches).arg(faces.size()));
    }
  });
}

bool MainWindow::mark_cable_on_selection(int order) {
  return attempt([&] {
    const auto& state = m_doc.state();
    if (!state.stitch) throw Error("generate the stitch mesh first (Stitch > Generate stitch mesh)");
    const auto faces = selection();
    if (faces.size() < 2) throw Error("select two or more neighbouring stitches of one row for a cable");
    const auto rows = mesh::faces_by_row(*state.stitch);
    const int row = state.stitch->faces[faces.front()].row;
    std::vector<int> positions;
    for (int f : faces) {
      if (state.stitch->faces[f].row != row) throw Error("a cable's stitches must all be in one row");
      positions.push_back(static_cast<int>(std::find(rows[row].begin(), rows[row].end(), f) - rows[row].begin()));
    }
    std::sort(positions.begin(), positions.end());
    if (positions.back() - positions.front() + 1 != static_cast<int>(positions.size())) throw Error("a cable's stitches must be neighbours");
    const auto path = mesh::top_edge_path(*state.stitch, row, positions.front(), positions.back() + 1);
    if (order == 0) m_doc.unmark_cable(path);
    else m_doc.mark_cable(path, static_cast<int>(faces.size()) / 2, order);
  });
}

void MainWindow::on_pressed(const Hit& hit, Qt::KeyboardModifiers modifiers) {
  if (job_running()) return;
  const auto& state = m_doc.state();
  if (m_layer == Layer::Input && m_doc.input()) {
    const int edge = m_doc.input()->face_edge(hit.face, hit.local_edge);
    switch (m_tool) {
      case Tool::FirstRow: attempt([&] { m_doc.label_first_row(edge); }); return;
      case Tool::NextRow: attempt([&] { m_doc.label_next_row(edge); }); return;
      case Tool::FlipRow:
        attempt([&] {
          if (!state.labels || !state.labels->faces[hit.face].labeled()) throw Error("", "face " + std::to_string(hit.face), "is not labeled yet");
          m_doc.flip_row(state.labels->faces[hit.face].row);
        });
        return;
      case Tool::EdgeValue:
        attempt([&] {
          if (!state.values) throw Error("label every face first: tessellation values need a valid labeling");
          bool ok = false;
          const bool wale = state.labels->edges[edge] == mesh::EdgeLabel::Wale;
          const int n = QInputDialog::getInt(this, tr("Tessellation value"),
                                             wale ? tr("Stitch rows in this row") : tr("Stitches along this edge"), state.values->edge[edge], 1, 10000, 1, &ok);
          if (ok) m_doc.set_edge_value(edge, n);
        });
        return;
      case Tool::MarkWale: attempt([&] { m_doc.toggle_wale_mark(edge); }); return;
      case Tool::TraceFrom: {
        // A border edge where the click is, else the point clicked (a closed surface, or inside a piece).
        mesh::KnitStart at;
        if (m_doc.input()->is_border(edge)) at.border_edge = edge;
        else at.point = hit.point;
        if (modifiers & Qt::ShiftModifier) {
          m_trace_end = at;
          statusBar()->showMessage(at.point ? tr("Rows will end at the point clicked: now click where they start")
                                            : tr("Rows will end at border edge %1: now click where they start").arg(edge));
          return;
        }
        attempt([&] { m_doc.trace_field(at, m_trace_end); });
        m_trace_end.reset();
        return;
      }
      default: return;
    }
  }
  if (m_layer != Layer::Stitch || !state.stitch) return;
  const auto& face = state.stitch->faces[hit.face];
  const int u = face.vertex(hit.local_edge), v = face.vertex(hit.local_edge + 1);
  const auto course_edge = [&] {
    if (face.is_wale(hit.local_edge)) throw Error("", "edge " + std::to_string(u) + "-" + std::to_string(v), "is a wale edge; click a course edge");
  };
  const auto wale_edge = [&] {
    if (!face.is_wale(hit.local_edge)) throw Error("", "edge " + std::to_string(u) + "-" + std::to_string(v), "is a course edge; click a wale edge");
  };
  switch (m_tool) {
    case Tool::Paint:
      m_stroke.clear();
      m_stroke_preview = *state.stitch;
      on_dragged(hit, modifiers);
      return;
    case Tool::Select:
      if (!(modifiers & (Qt::ShiftModifier | Qt::ControlModifier))) m_selected.assign(m_selected.size(), 0);
      on_dragged(hit, modifiers);
      return;
    case Tool::SplitCourse: attempt([&] { course_edge(); m_doc.split_course_edge(u, v); }); return;
    case Tool::CollapseCourse: attempt([&] { course_edge(); m_doc.collapse_course_edge(u, v); }); return;
    case Tool::AddWale: attempt([&] { m_doc.add_wale_edge(hit.face); }); return;
    case Tool::RemoveWale: attempt([&] { wale_edge(); m_doc.remove_wale_edge(u, v); }); return;
    case Tool::ShiftWale:
      attempt([&] {
        wale_edge();
        // The end nearer the click; the bottom corners of a face are loop vertices 0 and `bottom`.
        const int near = (hit.point - state.stitch->vertices[u]).norm() < (hit.point - state.stitch->vertices[v]).norm() ? u : v;
        const auto end = near == face.vertex(0) || near == face.vertex(face.bottom) ? mesh::WaleEnd::Bottom : mesh::WaleEnd::Top;
        m_doc.shift_wale_edge(u, v, end, modifiers & Qt::ShiftModifier ? -1 : 1);
      });
      return;
    default: return;
  }
}

void MainWindow::on_dragged(const Hit& hit, Qt::KeyboardModifiers modifiers) {
  if (m_layer != Layer::Stitch || !m_doc.state().stitch || job_running()) return;
  if (m_tool == Tool::Select) {
    m_selected[hit.face] = modifiers & Qt::ControlModifier ? 0 : 1;
    refresh();
  } else if (m_tool == Tool::Paint && !m_stroke_preview.faces.empty()) {
    if (std::find(m_stroke.begin(), m_stroke.end(), hit.face) != m_stroke.end()) return;
    m_stroke.push_back(hit.face);
    auto& face = m_stroke_preview.faces[hit.face];
    if (fits(face, m_paint_type.toStdString())) face.type = m_paint_type.toStdString();
    refresh();
  }
}

void MainWindow::on_released() {
  if (m_tool != Tool::Paint || m_stroke.empty()) return;
  std::vector<int> faces, refused;
  for (int f : m_stroke) (fits(m_doc.state().stitch->faces[f], m_paint_type.toStdString()) ? faces : refused).push_back(f);
  m_stroke.clear();
  m_stroke_preview = {};
  if (!faces.empty()) attempt([&] { m_doc.paint(faces, m_paint_type.toStdString(), tr("Paint %1 stitches %2").arg(faces.size()).arg(m_paint_type)); });
  else refresh();
  if (!refused.empty()) {
    const auto* type = mesh::find_stitch_type(m_paint_type.toStdString());
    statusBar()->showMessage(tr("%1 stitches kept their type: %2 fits faces with %3 bottom and %4 top edges")
                                 .arg(refused.size()).arg(m_paint_type).arg(type ? type->bottom : 0).arg(type ? type->top : 0));
  }
}

void MainWindow::set_editing_enabled(bool enabled) {
  for (auto* a : m_edit_actions) a->setEnabled(enabled);
  m_pause->setEnabled(!enabled && m_job_is_yarn);
  m_stop->setEnabled(!enabled);
  m_progress->setVisible(!enabled);
}

void MainWindow::start_job(RelaxJob* job) {
  m_job.reset(job);
  m_paused = false;
  m_pause->setText(tr("&Pause"));
  connect(job, &RelaxJob::updated, this, &MainWindow::on_job_updated, Qt::QueuedConnection);
  connect(job, &QThread::finished, this, &MainWindow::on_job_finished, Qt::QueuedConnection);
  set_editing_enabled(false);
  m_progress->setValue(0);
  m_live_clock.start();
  m_live_wait = 0;
  m_status_clock.invalidate();
  job->start();
}

bool MainWindow::set_yarn_settings(const YarnSettings& settings) {
  return attempt([&] {
    m_doc.set_yarn_settings(settings);
  });
}

bool MainWindow::set_stitch_size_from_needle(double needle_mm) {
  return attempt([&] {
    const std::string weight = m_doc.yarn_settings().weight;
    if (weight.empty())
      throw Error("a needle's gauge depends on the yarn knitted on it: choose a Yarn weight first (Relax > Yarn settings), or give the gauge (Stitch > Stitch size from gauge)");
    const auto& yarn = mesh::find_yarn_weight(weight);
    m_doc.set_stitch_size(mesh::needle_gauge(yarn, needle_mm, "needle").stitch_size());
    if (!mesh::needle_in_range(yarn, needle_mm))
      statusBar()->showMessage(tr("Needle %1 mm: %2").arg(needle_mm).arg(QString::fromStdString(mesh::needle_range_note(yarn))));
  });
}

bool MainWindow::relax_mesh() {
  if (job_running()) return false;
  return attempt([&] {
    const auto& state = m_doc.state();
    if (!state.stitch || !m_doc.input()) throw Error("generate the stitch mesh first (Stitch > Generate stitch mesh)");
    m_job_is_yarn = false;
    start_job(new MeshRelaxJob(*m_doc.input(), *state.stitch, surface::MeshRelaxOptions{}));
    set_coloring(Coloring::Stretch);
    m_job_label->setText(tr("Relaxing the stitch mesh..."));
  });
}

bool MainWindow::stitch_yarn_action(const std::function<void(const EditState&)>& body) {
  if (job_running()) return false;
  const bool ok = attempt([&] {
    const auto& state = m_doc.state();
    if (!state.stitch) throw Error("generate the stitch mesh first (Stitch > Generate stitch mesh)");
    QApplication::setOverrideCursor(Qt::WaitCursor);
    struct Restore {
      ~Restore() { QApplication::restoreOverrideCursor(); }
    } restore;
    body(state);
  });
  if (ok) set_layer(Layer::Yarn);
  return ok;
}

bool MainWindow::emit_yarn() {
  return stitch_yarn_action([&](const EditState& state) { m_doc.set_yarn(emitted_yarn(state, m_doc.yarn_settings()), false, tr("Emit yarn")); });
}

bool MainWindow::preview_yarn() {
  return stitch_yarn_action([&](const EditState& state) {
    if (!m_doc.yarn_settings().weight.empty())
      throw Error("the stand-in preview relaxes its repeats at the emitted radius, not a yarn weight's: set Yarn weight to none in Relax > Yarn settings");
    const auto yarn = emitted_yarn(state, m_doc.yarn_settings());
    auto options = m_doc.yarn_settings().relax;
    options.audit = false;  // the preview is certified on its own straight path from the emission
    workflow::StandInOptions stand_in;
    stand_in.take_up = m_doc.yarn_settings().take_up;
    stand_in.patterns = m_tiled_patterns;
    workflow::StandInReport report;
    const auto points = workflow::stand_in_preview(*state.stitch, yarn, mesh::StitchLibrary::bundled(), options, stand_in, report);
    // Not a relaxation: Relax yarn starts from the emission.
    m_doc.set_yarn_preview(relax::with_points(yarn, points), tr("Preview yarn"));
    QStringList repeats;
    for (const auto& t : report.repeats) repeats << QString::fromStdString(t.pattern);
    m_job_label->setText(report.repeats.empty()
                             ? tr("stand-in preview: no repeating pattern covers a region of %1 stitches; the yarn is as emitted").arg(workflow::StandInOptions{}.min_faces)
                             : tr("stand-in preview (not a relaxation) in %1 s: %2 of %3 control points from the patches of %4")
                                   .arg(report.seconds, 0, 'f', 1)
                                   .arg(report.placed)
                                   .arg(points.cols())
                                   .arg(repeats.join(", ")));
  });
}

bool MainWindow::relax_yarn() {
  if (job_running()) return false;
  return attempt([&] {
    const auto& state = m_doc.state();
    if (!state.stitch) throw Error("generate the stitch mesh first (Stitch > Generate stitch mesh)");
    if (!state.yarn) throw Error("emit the yarn first (Relax > Emit yarn)");
    if (state.yarn_relaxed) throw Error("the yarn is relaxed already; emit it again to start over");
    if (m_doc.yarn_settings().relax.active_set.enabled && m_backend == relax::Backend::Cuda)
      throw Error("the active set runs on the CPU only: choose Relax > Yarn backend > CPU or Auto, or turn it off in Relax > Yarn settings");
    if (m_doc.yarn_settings().relax.clipped_scale && m_backend == relax::Backend::Cuda)
      throw Error("the clipped stop scale runs on the CPU only: choose Relax > Yarn backend > CPU or Auto, or turn it off in Relax > Yarn settings");
    m_job_is_yarn = true;
    // A stand-in preview is only a look, and yarn emitted before the yarn weight changed is another yarn: then the
    // relaxation starts from the emission for the settings (its rest lengths).
    const bool emitted = !state.yarn_preview && state.yarn->radius == drawn_radius(state, m_doc.yarn_settings());
    const auto start = emitted ? *state.yarn : emitted_yarn(state, m_doc.yarn_settings());
    auto* job = new YarnRelaxJob(start, *state.stitch, state.stitch_size, m_doc.yarn_settings(), m_backend);
    // After stitch edits: only the changed stitches and rings around them, from the last relaxed yarn (at the emitted
    // radius: a yarn weight's garment relaxes whole, as relax-yarn --yarn refuses --warm-start).
    const bool local = state.previous && m_doc.yarn_settings().weight.empty() && state.previous->relaxed.radius == start.radius;
    if (local) job->warm_start(state.previous->stitch, state.previous->relaxed);
    start_job(job);
    set_layer(Layer::Yarn);
    m_job_label->setText(local ? tr("Relaxing the changed stitches...")
                         : m_doc.yarn_settings().weight.empty()
                             ? tr("Relaxing the yarn...")
                             : tr("Relaxing the yarn as %1 (Munden's loop length)...").arg(QString::fromStdString(m_doc.yarn_settings().weight)));
  });
}

void MainWindow::pause_or_resume() {
  if (!m_job || !m_job_is_yarn) return;
  if (!m_paused) {
    m_paused = true;
    m_job->interrupt();
    m_pause->setText(tr("&Resume"));
  } else {
    m_paused = false;
    m_pause->setText(tr("&Pause"));
    m_job_label->setText(tr("Relaxing the yarn..."));
    m_job->start();
  }
}

void MainWindow::stop_job() {
  if (!m_job) return;
  if (m_paused && m_job->isFinished()) {
    m_paused = false;
    on_job_finished();
  } else {
    m_paused = false;
    m_job->interrupt();
  }
}

void MainWindow::on_job_updated() {
  if (!m_job) return;
  // Each status change repaints the window; twice a second is enough to follow a run.
  if (m_status_clock.isValid() && m_status_clock.elapsed() < 500) return;
  m_status_clock.restart();
  const auto p = m_job->progress();
  if (m_job_is_yarn) {
    // Progress toward the stop rule |∇E| / |∇E_0| < 0.01, on a log scale.
    const double done = p.measure > 0 && p.measure < 1 ? std::log(p.measure) / std::log(0.01) : 0;
    m_progress->setValue(static_cast<int>(1000 * std::clamp(done, 0.0, 1.0)));
    m_job_label->setText(tr("yarn step %1, residual %2").arg(p.step).arg(p.measure, 0, 'g', 3));
    // The live view costs the relaxation CPU time: redraw no more often than every 8x what the last
    // redraw took (building the tubes and drawing them).
    if (m_layer == Layer::Yarn && m_live_clock.elapsed() >= m_live_wait) {
      QElapsedTimer build;
      build.start();
      m_view->show_geometry(yarn_geometry(static_cast<YarnRelaxJob&>(*m_job).yarn(), YarnDetail::Live), false);
      m_live_wait = std::max<qint64>(200, 8 * (build.elapsed() + m_view->last_paint_ms()));
      m_live_clock.restart();
    }
  } else {
    m_progress->setValue(static_cast<int>(1000 * p.step / std::max<long>(p.max_steps, 1)));
    m_job_label->setText(tr("mesh step %1, largest move %2 mm").arg(p.step).arg(p.measure, 0, 'g', 3));
    auto& job = static_cast<MeshRelaxJob&>(*m_job);
    const RestSize rest = job.rest();
    if (m_layer == Layer::Stitch && rest.r_course > 0) m_view->show_geometry(stitch_geometry(job.stitch(), m_coloring, rest, m_selected), false);
  }
}

void MainWindow::on_job_finished() {
  if (!m_job || m_job->isRunning()) return;
  const auto p = m_job->progress();
  if (m_paused) {
    m_job_label->setText(tr("paused at step %1").arg(p.step));
    return;
  }
  const QString error = m_job->error();
  std::unique_ptr<RelaxJob> job = std::move(m_job);
  set_editing_enabled(true);
  if (!error.isEmpty()) {
    m_job_label->clear();
    show_error(error);
  } else if (m_job_is_yarn) {
    auto& yarn_job = static_cast<YarnRelaxJob&>(*job);
    attempt([&] { m_doc.set_yarn(yarn_job.yarn(), true, tr("Relax yarn")); });
    const QString ended = p.stopped_by == "interrupted" ? tr("stopped") : p.stopped_by;
    const QString audit = p.pull_through < 0 ? tr("not audited") : tr("%1 pull-through events").arg(p.pull_through);
    if (const auto local = yarn_job.local()) {
      m_job_label->setText(tr("yarn %1 after %2 steps: %3 changed stitches relaxed locally (%4 rings, %5 points), %6")
                               .arg(ended)
                               .arg(p.step)
                               .arg(local->changed_stitches)
                               .arg(local->rings)
                               .arg(local->relaxed_points)
                               .arg(audit));
    } else {
      QString active;
      if (const auto a = yarn_job.active_set(); a && p.step > 0)
        active = tr(", %1 % of the point-steps integrated (active set)")
                     .arg(100.0 * a->point_steps / (static_cast<double>(p.step) * yarn_job.yarn().points.size()), 0, 'f', 1);
      // Leaf's relative stop rule set by a few spots of the emission (kinks): the run may have stopped early.
      const QString peak = p.first_residual_peak > 0.5 && p.stopped_by == "converged"
                               ? tr("; %1 % of the first residual came from 0.1 % of the points, so it may have stopped early "
                                    "(relax the stitch mesh first, or lower the stop tolerance)")
                                     .arg(100 * p.first_residual_peak, 0, 'f', 0)
                               : QString();
      const QString fabric = yarn_job.weight().empty()
                                 ? QString()
                                 : tr(", as %1 yarn (take-up %2: Munden's loop length)")
                                       .arg(QString::fromStdString(yarn_job.weight()))
                                       .arg(yarn_job.take_up(), 0, 'f', 3);
      m_job_label->setText(tr("yarn %1 after %2 steps on %3, %4%5%6%7")
                               .arg(ended)
                               .arg(p.step)
                               .arg(yarn_job.backend())
                               .arg(audit)
                               .arg(fabric)
                               .arg(active)
                               .arg(peak));
    }
  } else {
    auto& mesh_job = static_cast<MeshRelaxJob&>(*job);
    attempt([&] { m_doc.set_relaxed_mesh(mesh_job.stitch(), mesh_job.rest()); });
    m_job_label->setText(tr("stitch mesh %1 after %2 steps").arg(p.stopped_by == "interrupted" ? tr("stopped") : p.stopped_by).arg(p.step));
  }
  emit job_finished();
}

}  // namespace skein::gui
