#pragma once
// What the skein subcommands and jobs share: inputs, reports, pictures, progress and the yarn run.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "relax/yarn_relax.hpp"
#include "render/raster.hpp"
#include "render/stitch_view.hpp"
#include "render/yarn_view.hpp"
#include "stitchmesh/fabric.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/project.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "surface/mesh_relax.hpp"
#include "workflow/garment_fabric.hpp"

namespace skein::cli {

namespace fs = std::filesystem;
using nlohmann::json;

class Stopwatch {
public:
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count(); }

private:
  std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
};

/// A one-line progress bar with an ETA on a terminal; nothing otherwise.
class ProgressBar {
public:
  explicit ProgressBar(bool enabled) : m_enabled(enabled) {}
  /// `done` in [0, 1].
  void show(double done, const std::string& text) {
    if (!m_enabled || m_last.seconds() < 0.2) return;
    m_last = {};
    done = std::clamp(done, 0.0, 1.0);
    const int width = 30, filled = static_cast<int>(done * width);
    const double elapsed = m_started.seconds();
    const double eta = done > 0 ? elapsed * (1 - done) / done : 0;
    std::fprintf(stderr, "\r[%s%s] %3.0f%% %s ETA %dm%02ds ", std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(),
                 100 * done, text.c_str(), static_cast<int>(eta) / 60, static_cast<int>(eta) % 60);
    std::fflush(stderr);
  }
  ~ProgressBar() {
    if (m_enabled) std::fprintf(stderr, "\n");
  }

private:
  bool m_enabled;
  Stopwatch m_started, m_last;
};

bool is_project(const fs::path& path);
bool is_bcc(const fs::path& path);
/// A mesh file or the input mesh of a project; with `repair`, a mesh file mended by mesh::repair_mesh_soup (what
/// changed is logged).
mesh::InputMesh load_input(const fs::path& path, bool repair = false);
/// Labels (and tessellation values, when stored) in `path` for `mesh`: the same faces, corner for corner
/// (vertex ids may differ).
std::pair<mesh::Labeling, std::optional<mesh::TessellationValues>> labels_for(const mesh::InputMesh& mesh, const fs::path& path);

/// A labeling's face problems in the log at `level`: the first ten one by one, then how many more, and what
/// the faces that are not quads have to do with it (labeling works on quads, Yuksel 2012 §5).
void log_face_problems(const std::string& file, const mesh::InputMesh& mesh, const mesh::LabelReport& report, spdlog::level::level_enum level);

json stats_json(const mesh::StitchMesh& sm);
json labels_json(const mesh::InputMesh& m, const mesh::Labeling& labels);
json mesh_json(const mesh::InputMesh& m);
json yarn_json(const relax::YarnCurves& yarn);
json guard_json(const relax::GuardCounters& g);
/// Writes JSON atomically, or to stdout for "-".
void write_json(const json& j, const std::string& path);
/// JSON as "key.sub: value" lines; long lists show their first entries and a count.
void print_text(const json& j, const std::string& prefix);

/// "garment": three-quarter front and back-side; "flat": straight front and back (for swatches); "front": the
/// straight front alone; "three": front, back and a three-quarter view from above the front.
render::View view_named(const std::string& name);
void render_yarn_tubes(const relax::YarnCurves& yarn, const std::string& path, render::YarnColor color, const std::string& views = "garment",
                       int panel = 900);
void render_stitch_mesh(const mesh::StitchMesh& sm, const std::string& path, render::ColorBy color, const std::string& views = "garment");
/// Area-strain colours per face (blue compressed, white at rest, red stretched).
std::vector<Eigen::Vector3f> stretch_colors(const surface::FaceStretch& strain);
/// The stretch picture of a stitch mesh against the rest size of mesh relaxation.
void render_stretch(const mesh::StitchMesh& sm, double r_course, double r_wale, const std::string& path);

/// Yarn from a .bcc file, or emitted from a project's stitch mesh.
relax::YarnCurves yarn_of(const fs::path& path, double radius, const std::string& stitches, mesh::EmitReport* report = nullptr);
/// Writes yarn as .bcc or .obj polylines, by the extension; `preview` marks it as placed for a preview, not
/// relaxed (workflow::write_bcc).
void write_yarn(const relax::YarnCurves& yarn, const std::string& path, bool preview = false, const std::string& unit = "mm");
/// Refuses, before any work, a yarn output write_yarn would refuse at the end: a name that is not .bcc or .obj,
/// or a folder that cannot be written.
void check_yarn_output(const std::string& path);
/// How a yarn picture is coloured unless asked otherwise: in the yarn's own colours when it has them
/// (patterns/FORMAT.md, "Colour"), else by stitch type.
render::YarnColor own_colours(const relax::YarnCurves& yarn);
/// Writes the yarn's tubes for any renderer: glTF 2.0 when `path` ends in .glb or .gltf (in metres), else OBJ with
/// its coordinates times `scale`, said to be in `unit`; yarn in colours gets a material per colour (a .mtl beside the OBJ).
void write_tubes(const relax::YarnCurves& yarn, const std::string& path, double scale = 1, const std::string& unit = "mm");

/// "A:B" (inclusive) or "A" → row ids.
std::pair<int, int> parse_rows(const std::string& s);
/// "K=V" with two integers (edge or row id = tessellation value).
std::pair<int, int> parse_assignment(const std::string& option, const std::string& s);
/// TYPE=F pairs of --take-up-stitch.
std::map<std::string, double> parse_take_up(const std::string& option, const std::vector<std::string>& pairs);

/// What --yarn WEIGHT and --gauge S[xR] ask for (issue 24, part 1).
struct FabricChoice {
  std::string yarn, gauge, needle;
};
/// The stitch size and yarn radius a fabric choice sets: --gauge sets the size, and so does --needle with
/// --yarn (mesh::needle_gauge); --yarn the radius (half its diameter) and, without --gauge or --needle, the
/// size of its standard gauge. `size_given` and `radius_given` say whether
/// --stitch-size/--stitch-height or --yarn-radius came too: each pair is refused together. `report` describes
/// the fabric (yarn, gauge, Munden's loop length); null when nothing was asked.
struct Fabric {
  std::optional<mesh::StitchSize> size;
  std::optional<double> radius;
  json report;
};
Fabric resolve_fabric(const FabricChoice& choice, bool size_given, bool radius_given);

/// SIGINT and SIGTERM set the returned flag (relaxations stop after their step, checkpoint and return) and are
/// remembered for the exit status, 128 + the signal.
const std::atomic<bool>* install_interrupt_handlers();
int interrupt_signal();  ///< 0 when none came

/// The outputs of a yarn relaxation (relax-yarn, pattern --relax, run).
struct YarnRunOutputs {
  std::string input, output, backend, report, log, png, views;
  bool progress = false;  ///< a progress bar on the terminal
  json extra = json::object();  ///< more report fields
  int panel = 900;              ///< picture: pixels per view
  render::YarnColor color = render::YarnColor::StitchType;
  double scale = 1;             ///< the relaxed yarn is written scaled by this (1/gamma, Leaf §6.2)
  double radius_out = 0;        ///< the written yarn's radius where it is not the relaxed one's (a compressed contact); 0: that one
  /// A periodic patch's repeat in stitches (wales x courses; wovens: warps x wefts), for the gauge of a free period.
  std::array<int, 2> repeat = {0, 0};
  std::string tubes;  ///< the relaxed yarn's tubes too (write_tubes), unless empty
};

/// A yarn run as relax_and_write leaves it: its JSON report (with the residual history) and why it stopped.
struct RelaxOutcome {
  json report;
  relax::StopReason stopped_by = relax::StopReason::Converged;
};

/// Relaxes `state` with the backend asked for, with progress and the per-step log (appended to when the state
/// goes on from a checkpoint), then writes the yarn, the JSON report and the picture; an interrupted run writes
/// only its report (its checkpoint holds the state).
RelaxOutcome relax_and_write(const relax::YarnCurves& yarn, const relax::YarnSystem& system, const relax::ShapeTargets& targets,
                             const relax::YarnRelaxOptions& options, relax::YarnState& state, const YarnRunOutputs& run);
/// The exit status of a yarn run that stopped so: 0, 1 when it diverged, 128 + the signal when interrupted.
int exit_status(relax::StopReason stopped_by);

}  // namespace skein::cli
