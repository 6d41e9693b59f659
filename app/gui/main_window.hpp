#pragma once
#include <functional>

#include <memory>
#include <optional>
#include <vector>

#include <QElapsedTimer>
#include <QMainWindow>
#include <QPointer>

#include "document.hpp"
#include "relax_jobs.hpp"
#include "scene_geometry.hpp"
#include "stitchmesh/knit_field.hpp"
#include "stitchmesh/pattern.hpp"

class QAction;
class QActionGroup;
class QLabel;
class QListWidget;
class QMessageBox;
class QPlainTextEdit;
class QProgressBar;

namespace skein::gui {

class Viewport;

/// What a left click in the view does.
enum class Tool {
  Orbit,           ///< nothing but turning the view
  FirstRow,        ///< click a border edge: it becomes the first row (Yuksel Fig. 11)
  NextRow,         ///< click a course edge of a labeled row: label the row across it
  FlipRow,         ///< click a face: flip its row's wale direction
  EdgeValue,       ///< click an edge: set its tessellation value
  MarkWale,        ///< click a wale edge: increases and decreases of its faces go next to it
  Paint,           ///< click or drag over stitches: give them the palette's stitch type
  Select,          ///< click or drag: select stitches (Shift adds, Ctrl removes)
  SplitCourse,     ///< click a course edge: split it (an increase below, a decrease above)
  CollapseCourse,  ///< click a course edge: collapse it
  AddWale,         ///< click a stitch: split it with a wale edge
  RemoveWale,      ///< click a wale edge: merge its two stitches
  TraceFrom,       ///< click a border edge or a point: trace rows from the knitting field from there (Shift+click: where they end)
  ShiftWale,       ///< click near one end of a wale edge: move that end right (Shift: left)
};

/// skein-gui's window: the 3D view, the stitch palette, the tools, the relaxation controls. Menu actions ask
/// for their input (a file, a number) and then call the public methods below, which tests drive directly.
/// Every failure lands in the status line and an error dialog; nothing throws out of the event loop.
class MainWindow : public QMainWindow {
  Q_OBJECT
public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  Document& document() { return m_doc; }
  Viewport& viewport() { return *m_view; }

  bool open_file(const QString& path);
  bool save_project(const QString& path);
  bool export_yarn(const QString& path);  ///< .bcc, or .obj tubes for renderers
  bool export_stitch_ply(const QString& path);  ///< the stitch mesh with its view colours per face
  bool export_picture(const QString& path);  ///< the view as PNG
  bool tile_pattern_file(const QString& path);  ///< over the selection, from its lowest-left stitch

  void set_tool(Tool tool);
  Tool tool() const { return m_tool; }
  void set_layer(Layer layer);
  Layer layer() const { return m_layer; }
  void set_coloring(Coloring coloring);
  void set_paint_type(const QString& type);
  void set_selection(const std::vector<int>& faces);
  std::vector<int> selection() const;
  bool fill_selection(const QString& fill);  ///< a parse_fill name: rib, rib2x2, garter, seed, moss, ...
  bool mark_cable_on_selection(int order);   ///< cable over the top edges of a selected run in one row; order +1 front, -1 behind

  /// What Relax yarn and Preview yarn run with (Relax > Yarn settings); false, with an error shown, for values
  /// out of range.
  bool set_yarn_settings(const YarnSettings& settings);
  const YarnSettings& yarn_settings() const { return m_doc.yarn_settings(); }
  /// Stitch > Stitch size from needle: the stitch size of the gauge that the Yarn settings' weight knits on a
  /// needle `needle_mm` across (mesh::needle_gauge); false, with an error shown, without a weight.
  bool set_stitch_size_from_needle(double needle_mm);

  bool relax_mesh();
  bool emit_yarn();
  bool relax_yarn();
  /// A stand-in preview of the relaxed yarn (workflow::stand_in_preview), in the foreground: seconds, not a relaxation.
  bool preview_yarn();
  void pause_or_resume();
  void stop_job();
  bool job_running() const { return m_job != nullptr; }

  /// The text of the last error shown (tests read it), empty when none.
  const QString& last_error() const { return m_last_error; }
  QString status_text() const;
  QString job_text() const;  ///< the job line in the status bar: what runs, or how the last job ended

signals:
  /// A relaxation job ended and its result is in the document (or it failed).
  void job_finished();

private:
  void build_actions();
  void build_docks();
  void refresh();          ///< geometry and panels from the document
  void refresh_info();
  void show_error(const QString& text);
  /// Runs an edit; a skein::Error (or any exception) becomes an error message. True when it went through.
  template <class F>
  bool attempt(F&& edit);
  /// A foreground action on the yarn of the stitch mesh: refused while a job runs or without a stitch mesh,
  /// under a wait cursor; the yarn layer shows afterwards.
  bool stitch_yarn_action(const std::function<void(const EditState&)>& body);

  void on_pressed(const Hit& hit, Qt::KeyboardModifiers modifiers);
  void on_dragged(const Hit& hit, Qt::KeyboardModifiers modifiers);
  void on_released();
  void on_job_updated();
  void on_job_finished();
  void start_job(RelaxJob* job);
  void set_editing_enabled(bool enabled);

  Document m_doc;
  Viewport* m_view = nullptr;
  Tool m_tool = Tool::Orbit;
  std::optional<mesh::KnitStart> m_trace_end;  ///< Tool::TraceFrom: where the rows end, Shift+clicked before the start
  Layer m_layer = Layer::Input;
  Coloring m_coloring = Coloring::StitchType;
  QString m_paint_type = "p";
  std::vector<char> m_selected;     ///< per stitch face
  std::vector<int> m_stroke;        ///< faces painted in the stroke under way
  mesh::StitchMesh m_stroke_preview;

  std::unique_ptr<RelaxJob> m_job;
  bool m_job_is_yarn = false, m_paused = false;
  relax::Backend m_backend = relax::Backend::Auto;
  std::vector<mesh::Pattern> m_tiled_patterns;  ///< the patterns tiled by re-meshing, whose repeats the stand-in looks for
  QElapsedTimer m_live_clock;  ///< since the last live redraw
  qint64 m_live_wait = 0;      ///< [ms] before the next one
  QElapsedTimer m_status_clock;  ///< since the job's progress was last shown

  QString m_last_error;
  QPointer<QMessageBox> m_error_box;
  QListWidget* m_palette = nullptr;
  QPlainTextEdit* m_info = nullptr;
  QLabel* m_job_label = nullptr;
  QProgressBar* m_progress = nullptr;
  QActionGroup* m_tools = nullptr;
  QAction *m_pause = nullptr, *m_stop = nullptr;
  std::vector<QAction*> m_edit_actions;  ///< off while a job runs
};

}  // namespace skein::gui
