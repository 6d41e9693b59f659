// skein's command line, callable in-process (skein's main, and skein-mpi's sweep cases). Thin: parses
// arguments, calls the library, prints what happened.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "command_line.hpp"
#include "commands.hpp"
#include "job.hpp"
#include "smock.hpp"
#include "weave.hpp"
#include "sweep.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "cuda/device.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_checkpoint.hpp"
#include "relax/yarn_relax.hpp"
#include "render/chart_view.hpp"
#include "render/stitch_view.hpp"
#include "render/yarn_view.hpp"
#include "skein/config.hpp"
#include "stitchmesh/chart_pattern.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/knit_field.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/project.hpp"
#include "stitchmesh/tessellation.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "surface/mesh_relax.hpp"
#include "workflow/yarn_io.hpp"
#include "workflow/yarn_local.hpp"
#include "workflow/yarn_options.hpp"
#include "workflow/yarn_periodic.hpp"
#include "workflow/yarn_settings.hpp"
#include "workflow/yarn_shape.hpp"
#include "workflow/yarn_standin.hpp"

namespace fs = std::filesystem;
using namespace skein;
using nlohmann::json;

namespace skein::cli {
namespace {

/// A number flag's check in the words every skein message uses: "expected a (whole) number, found TEXT" or "must be
/// in [LOW, HIGH] UNIT, found TEXT (WHY)"; `allows` says whether a number is in range, `range` how to name it.
CLI::Validator number_check(bool whole, std::function<bool(double)> allows, std::string range, std::string unit = "", std::string why = "") {
  const std::string shown = range + (unit.empty() ? "" : " " + unit);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const std::string expected = whole ? "expected a whole number, found " : "expected a number, found ";
        if (text.empty()) return expected + "nothing";
        double x = 0;
        try {
          size_t used = 0;
          x = std::stod(text, &used);
          if (used != text.size()) return expected + text;
        } catch (const std::exception&) {
          return expected + text;
        }
        if (!std::isfinite(x) || (whole && x != std::floor(x))) return expected + text;
        if (!allows(x)) return "must be in " + shown + ", found " + text + (why.empty() ? "" : " (" + why + ")");
        if (whole) text = std::to_string(static_cast<long long>(x));  // 1e3 and 3.0 as the integer the option stores
        return {};
      },
      range);
}

/// A number in [low, high] (inclusive).
CLI::Validator in_range(double low, double high, const std::string& unit = "") {
  const auto text = [](double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  };
  return number_check(false, [=](double x) { return x >= low && x <= high; }, "[" + text(low) + ", " + text(high) + "]", unit);
}

/// A whole number in [low, high]; give it to `transform`, not `check`, so that 1e3 and 3.0 reach the option as 1000 and 3.
CLI::Validator whole_in_range(long low, long high, const std::string& unit = "") {
  return number_check(true, [=](double x) { return x >= low && x <= high; }, "[" + std::to_string(low) + ", " + std::to_string(high) + "]", unit);
}

/// A yarn option's flag as the schema declares it (relax/yarn_options.hpp): its help, unit and range, the same as
/// in jobs, sweeps, projects and the app. `prefix` says when it applies ("with --relax: "), `suffix` adds what only this command does.
template <class T>
CLI::Option* add_yarn_option(CLI::App* app, const std::string& key, T& target, const std::string& prefix = "", const std::string& suffix = "") {
  const auto& spec = workflow::yarn_option(key);
  const std::string unit = spec.unit.empty() ? "" : " [" + spec.unit + "]";
  auto* option = app->add_option(spec.flag(), target, prefix + spec.help + unit + suffix);
  if (spec.kind == workflow::YarnOption::Kind::Choice) return option->check(CLI::IsMember(spec.choices))->capture_default_str();
  const bool whole = spec.kind == workflow::YarnOption::Kind::Integer;
  const auto check = number_check(whole, [&spec](double x) { return spec.allows(x); }, spec.range(), spec.unit, spec.help);
  whole ? option->transform(check) : option->check(check);  // a transform may hand 1e3 on as 1000
  return option->capture_default_str();
}

/// A positive number (a radius, a size): the value named when it is not one.
CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          size_t used = 0;
          const double x = std::stod(text, &used);
          if (used == text.size() && std::isfinite(x) && x > 0) return {};
        } catch (const std::exception&) {
        }
        return "expected a positive number, found " + text;
      },
      "> 0");
}

}  // namespace

int run_command_line(int argc, char** argv) {
  CLI::App app{"skein: polygon mesh → knitted garment with yarn-level detail (Yuksel et al. 2012 stitch meshes)"};
  app.set_version_flag("--version", SKEIN_VERSION);
  app.require_subcommand(1);
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "print warnings and errors only");
  // --yarn and --gauge (issue 24): the yarn and the fabric as a knitter gives them (docs/yarn.md, "Yarn and gauge").
  const auto add_fabric = [](CLI::App* cmd, FabricChoice& f, const char* yarn_sets, bool gauge) {
    cmd->add_option("--yarn", f.yarn, std::string("yarn weight (lace, fingering, sport, dk, worsted, bulky, super-bulky, jumbo or the CYC number 0-7): ") + yarn_sets);
    if (!gauge) return;
    cmd->add_option("--gauge", f.gauge, "stockinette gauge, stitches (x rows) in 10 cm, e.g. 18x24 (rows: 1.3 x the stitches when left out): sets the stitch size");
    cmd->add_option("--needle", f.needle, "needle diameter [mm], with --yarn: the gauge of that yarn knitted on it (a stitch is one wrap of yarn around the needle); sets the stitch size");
  };
  const auto size_given = [](CLI::App* cmd) { return cmd->count("--stitch-size") + cmd->count("--stitch-height") > 0; };

  // skein stitch
  auto* stitch = app.add_subcommand("stitch", "label a mesh and tessellate it into a stitch mesh (.skein)");
  std::string stitch_in, stitch_out, stitch_labels, stitch_png, stitch_png_types, stitch_stats;
  bool auto_label = false;
  int start_edge = -1;
  mesh::StitchSize size;
  bool height_given = false;
  stitch->add_option("MESH", stitch_in, "mesh (OBJ, PLY, glTF, FBX, ... or a .skein project)")->required();
  auto* auto_opt = stitch->add_flag("--auto-label", auto_label, "label every row automatically from the lowest border edge");
  auto* labels_opt = stitch->add_option("--labels", stitch_labels, "use the labels stored in this .skein file");
  bool trace_field = false, stitch_repair = false;
  std::vector<double> start_point;
  stitch->add_flag("--repair", stitch_repair, "mend the mesh first where CGAL can (duplicate points and faces, degenerate faces, orientation, bow ties) and say what changed");
  auto* field_opt = stitch->add_flag("--field", trace_field,
                                     "trace rows on any surface (triangles, poles, closed) as isolines of the knitting distance from the start (docs/stitch-a-garment.md)");
  auto_opt->excludes(labels_opt);
  field_opt->excludes(auto_opt)->excludes(labels_opt);
  auto* start_edge_opt = stitch->add_option("--start-edge", start_edge, "with --auto-label or --field: the border edge to start from (default: the lowest)");
  stitch->add_option("--start-point", start_point, "with --field: knit in the round outwards from the surface point nearest X,Y,Z")
      ->expected(3)->delimiter(',')->needs(field_opt)->excludes(start_edge_opt);
  int end_edge = -1;
  std::vector<double> end_point;
  auto* end_edge_opt = stitch->add_option("--end-edge", end_edge, "with --field: the border edge where knitting ends; the rows turn to lie along its run (default: no end)")
                           ->needs(field_opt);
  stitch->add_option("--end-point", end_point, "with --field: knitting ends at the surface point nearest X,Y,Z (a toe, a crown); the rows close round it")
      ->expected(3)->delimiter(',')->needs(field_opt)->excludes(end_edge_opt);
  stitch->add_option("--stitch-size", size.width, "stitch width along the course [mm]")->capture_default_str();
  stitch->add_option("--stitch-height", size.height, "stitch height along the wale [mm] (default: the width × 5/6)");
  stitch->add_option("-o,--output", stitch_out, "project to write (.skein)")->required();
  stitch->add_option("--png", stitch_png, "picture of the stitch mesh coloured by row");
  stitch->add_option("--png-types", stitch_png_types, "picture of the stitch mesh coloured by stitch type");
  stitch->add_option("--stats", stitch_stats, "write the stitch-mesh statistics as JSON here ('-' for stdout)");
  FabricChoice stitch_fabric;
  double max_stitches = mesh::kDefaultMaxStitches;
  stitch->add_option("--max-stitches", max_stitches, "refuse a mesh that would make more stitches than this (its area over the stitch's)")
      ->check(positive())->capture_default_str();
  add_fabric(stitch, stitch_fabric, "without --gauge, sets the stitch size of its standard gauge", true);

  // skein label
  auto* label = app.add_subcommand("label", "label a mesh's knitting rows and save the labels (.skein)");
  std::string label_in, label_out;
  int label_start = -1;
  std::vector<int> flips;
  label->add_option("MESH", label_in, "mesh or .skein project")->required();
  bool label_repair = false;
  label->add_flag("--repair", label_repair, "mend the mesh first where CGAL can (duplicate points and faces, degenerate faces, orientation, bow ties) and say what changed");
  std::vector<int> first_rows, next_rows;
  auto* start_opt = label->add_option("--start-edge", label_start, "auto-label from this border edge (default: the lowest)");
  auto* first_opt = label->add_option("--first-row", first_rows, "label by hand: first rows from these border edges (instead of auto-label)");
  label->add_option("--next-row", next_rows, "then the next row across each of these course edges, in order")->needs(first_opt);
  first_opt->excludes(start_opt);
  label->add_option("--flip-row", flips, "flip these rows' wale direction after labeling");
  mesh::StitchSize label_size;
  std::vector<std::string> course_values, row_values;
  std::vector<int> marked_wales;
  label->add_option("--stitch-size", label_size.width, "stitch width for the tessellation values [mm]")->capture_default_str();
  label->add_option("--stitch-height", label_size.height, "stitch height [mm] (default: the width × 5/6)");
  label->add_option("--course-value", course_values, "set a course edge's stitch count: EDGE=N (repeatable)");
  label->add_option("--row-value", row_values, "set a row's stitch-row count: ROW=N (repeatable)");
  label->add_option("--mark-wale", marked_wales, "wale edges next to which increases and decreases go");
  label->add_option("-o,--output", label_out, "labels and tessellation values to write (.skein)")->required();
  FabricChoice label_fabric;
  bool label_partial = false;
  label->add_flag("--partial", label_partial, "write the labels even when some faces are not labeled yet (to go on later, by hand or in the app); exit 1");
  add_fabric(label, label_fabric, "without --gauge, sets the stitch size of its standard gauge", true);

  // skein edit
  auto* edit = app.add_subcommand("edit", "change stitch types of a stitch mesh: fills over rows, single faces");
  std::string edit_in, edit_out, edit_fill, edit_rows, edit_type, edit_png;
  std::vector<int> edit_faces;
  edit->add_option("PROJECT", edit_in, ".skein project with a stitch mesh")->required();
  edit->add_option("--fill", edit_fill, "stockinette, reverse, garter, seed, moss, rib or ribKxP");
  int near_border = -1;
  auto* rows_opt = edit->add_option("--rows", edit_rows, "rows A:B the fill covers (default: all)");
  edit->add_option("--near-border", near_border, "the fill covers the N stitch rows next to each border (hems, cuffs, necklines)")
      ->excludes(rows_opt);
  edit->add_option("--set-type", edit_type, "stitch type for --faces");
  edit->add_option("--faces", edit_faces, "face ids for --set-type");
  edit->add_option("--png-types", edit_png, "picture coloured by stitch type");
  edit->add_option("-o,--output", edit_out, "project to write")->required();

  // skein yarn
  auto* yarn_cmd = app.add_subcommand("yarn", "emit yarn curves from a stitch mesh (.bcc or OBJ polylines)");
  std::string yarn_in, yarn_out, yarn_tubes, yarn_png, yarn_color, stitches_dir;
  double yarn_radius = 0;
  yarn_cmd->add_option("PROJECT", yarn_in, ".skein project with a stitch mesh")->required();
  yarn_cmd->add_option("-o,--output", yarn_out, "yarn to write: .bcc (Catmull-Rom curves) or .obj (polylines)")->required();
  yarn_cmd->add_option("--tubes", yarn_tubes, "also write a tube mesh with normals for any renderer: OBJ, or glTF 2.0 when it ends in .glb or .gltf (in metres, "
                                              "glTF's unit)");
  std::string yarn_ids;
  yarn_cmd->add_option("--ids", yarn_ids, "also write each control point's stitch face, row and type as CSV (docs/FORMATS.md), for outside checks");
  std::string yarn_units = "mm";
  yarn_cmd->add_option("--units", yarn_units, "units of the OBJ outputs (polylines and --tubes): mm, cm or m (Blender reads OBJ as metres); .bcc stays in mm")
      ->check(CLI::IsMember({"mm", "cm", "m"}))->capture_default_str();
  yarn_cmd->add_option("--yarn-radius", yarn_radius, "yarn radius [mm] (default: a tenth of the stitch width)");
  FabricChoice yarn_fabric;
  add_fabric(yarn_cmd, yarn_fabric, "sets the yarn radius", false);
  yarn_cmd->add_option("--png", yarn_png, "picture of the yarn as shaded tubes");
  yarn_cmd->add_option("--color", yarn_color, "tube colour: type (stitch type), yarn (one per yarn) or colour (the yarn's own; the default when it has them, else type)")
      ->check(CLI::IsMember({"type", "yarn", "colour"}));
  yarn_cmd->add_option("--stitches", stitches_dir, "stitch library folder (default: the bundled stitches/)");

  // skein relax-mesh
  auto* relax_cmd = app.add_subcommand("relax-mesh", "relax a stitch mesh on the limit surface of its input mesh (Yuksel 2012 §6.1)");
  std::string relax_in, relax_out, relax_png, relax_png_before, relax_ply, relax_report;
  surface::MeshRelaxOptions relax_options;
  relax_cmd->add_option("PROJECT", relax_in, ".skein project with an input mesh and a stitch mesh")->required();
  relax_cmd->add_option("-o,--output", relax_out, "project to write, with the relaxed stitch mesh")->required();
  relax_cmd->add_option("--png", relax_png, "stretch picture after relaxation (area strain: blue compressed, red stretched)");
  relax_cmd->add_option("--png-before", relax_png_before, "the same picture before relaxation");
  relax_cmd->add_option("--ply", relax_ply, "relaxed stitch mesh as PLY with stretch colours and strains per face");
  relax_cmd->add_option("--report", relax_report, "JSON report: rest lengths, steps, energy and displacement history");
  relax_cmd->add_option("--alpha", relax_options.alpha, "rest-size scale α of N r_wale r_course = α A")->capture_default_str();
  relax_cmd->add_option("--aspect", relax_options.aspect, "stitch aspect a = r_wale / r_course")->capture_default_str();
  relax_cmd->add_option("--steps", relax_options.max_steps, "step cap")->capture_default_str();
  relax_cmd->add_option("--tolerance", relax_options.tolerance, "stop when no vertex moves more than this × r_course in a step")->capture_default_str();
  relax_cmd->add_option("--time-step", relax_options.time_step, "backward Euler step h [mm] (0: 1000 r_course)")->capture_default_str();
  relax_cmd->add_option("--k-stretch", relax_options.k_stretch, "stretch stiffness κ_stretch")->capture_default_str();
  relax_cmd->add_option("--k-shear", relax_options.k_shear, "shear stiffness κ_shear")->capture_default_str();
  relax_cmd->add_option("--k-wale", relax_options.k_wale, "wale strut stiffness κ_wale")->capture_default_str();
  relax_cmd->add_option("--k-fold", relax_options.k_fold, "stiffness of the guard against stitches turning over (0: off)")->capture_default_str();
  relax_cmd->add_option("--max-move", relax_options.max_move, "largest move of a vertex in one step, × r_course")->capture_default_str();
  relax_cmd->add_option("--cg-iterations", relax_options.cg_iterations, "conjugate-gradient iterations per step, at most")->capture_default_str();

  // skein relax-yarn
  auto* ry = app.add_subcommand("relax-yarn", "relax yarn at yarn level without letting one yarn pass through another (Yuksel 2012 §6.3, Leaf 2018 §3)");
  std::string ry_in, ry_out, ry_method = "fire", ry_resume, ry_report, ry_log, ry_png, ry_stitches;
  relax::YarnRelaxOptions ry_options;
  double ry_radius = 0, ry_take_up = 1;
  bool ry_no_guard = false, ry_no_shape = false, ry_no_audit = false, ry_no_bounds = false, ry_no_boundary = false, ry_no_patches = false;
  std::string ry_checkpoint;
  ry->add_option("INPUT", ry_in, ".skein project (its stitch faces drive shape preservation) or .bcc yarn")->required();
  ry->add_option("-o,--output", ry_out, "relaxed yarn to write (.bcc or .obj polylines)")->required();
  add_yarn_option(ry, "method", ry_method);
  std::string ry_backend = "auto";
  ry->add_option("--backend", ry_backend, "auto (the GPU when one answers, else the CPU), cpu or cuda (an error without a GPU)")
      ->check(CLI::IsMember({"auto", "cpu", "cuda"}))->capture_default_str();
  ry->add_option("--checkpoint", ry_checkpoint, "checkpoint file, written atomically every --checkpoint-every steps or minutes");
  add_yarn_option(ry, "checkpoint_every", ry_options.checkpoint_every, "", " (500 with --checkpoint when neither this nor --checkpoint-minutes is given)");
  add_yarn_option(ry, "checkpoint_minutes", ry_options.checkpoint_minutes);
  ry->add_option("--resume", ry_resume, "continue from this checkpoint (same input and method)");
  ry->add_option("--report", ry_report, "JSON report: converged, steps, wall_seconds, residual, guard_events, pull_through_events");
  ry->add_option("--log", ry_log, "per-step log as CSV: step, energy, residual, time step, largest move, contacts, guard hits, held points, crossings");
  ry->add_option("--png", ry_png, "picture of the relaxed yarn");
  std::string ry_ids;
  ry->add_option("--ids", ry_ids, "also write each control point's stitch face, row and type as CSV (docs/FORMATS.md), for outside checks; a project's yarn");
  std::string ry_views = "garment";
  ry->add_option("--views", ry_views, "garment (three-quarter front, back-side), flat (front, back) or three (front, back, three-quarter) for --png")
      ->check(CLI::IsMember({"garment", "flat", "three"}))->capture_default_str();
  add_yarn_option(ry, "max_steps", ry_options.max_steps);
  add_yarn_option(ry, "max_seconds", ry_options.max_seconds);
  add_yarn_option(ry, "tolerance", ry_options.tolerance);
  add_yarn_option(ry, "stall", ry_options.stall);
  std::string ry_stop_rule = "leaf";
  add_yarn_option(ry, "stop_rule", ry_stop_rule);
  add_yarn_option(ry, "force_tolerance", ry_options.force_tolerance);
  add_yarn_option(ry, "stall_window", ry_options.stall_window);
  add_yarn_option(ry, "energy_stall", ry_options.energy_stall);
  std::string ry_stop_scale = "first";
  add_yarn_option(ry, "stop_scale", ry_stop_scale);
  add_yarn_option(ry, "jam_steps", ry_options.jam_steps);
  add_yarn_option(ry, "jam_drop", ry_options.jam_drop);
  add_yarn_option(ry, "max_move", ry_options.guard.max_move);
  add_yarn_option(ry, "contact_margin", ry_options.contact_margin);
  ry->add_option("--guard-depth", ry_options.guard.max_depth, "bounding-sphere levels of the guard (pieces of 1/2^depth of a segment)")->capture_default_str();
  add_yarn_option(ry, "take_up", ry_take_up);
  std::string ry_rest_lengths;
  ry->add_option("--rest-lengths", ry_rest_lengths,
                 "a .bcc of the same yarn in another shape whose lengths (× --take-up) are the rest lengths, instead of the input's own "
                 "(e.g. a swatch relaxed flat, then bent: the bent one relaxes with the flat yarn's lengths)");
  std::vector<std::string> ry_take_up_stitch;
  ry->add_option("--take-up-stitch", ry_take_up_stitch, "TYPE=F scales the yarn of one stitch type (e.g. s=0.8), TYPE:vertical=F or TYPE:horizontal=F only its loop carried up or its row's yarn (s:vertical=0.5; Leaf 2018 §6.1)");
  ry->add_option("--yarn-radius", ry_radius, "yarn radius [mm] for a project (default: a tenth of the stitch width)")->check(positive());
  FabricChoice ry_fabric;
  add_fabric(ry, ry_fabric, "a project's yarn, relaxed at its compressed contact radius with each stitch cut to Munden's loop length (docs/yarn.md)", false);
  ry->add_option("--stitches", ry_stitches, "stitch library folder (default: the bundled stitches/)");
  add_yarn_option(ry, "k_bend", ry_options.params.k_bend);
  add_yarn_option(ry, "k_stretch", ry_options.params.k_stretch);
  add_yarn_option(ry, "k_length", ry_options.params.k_length);
  add_yarn_option(ry, "k_contact", ry_options.params.k_contact);
  add_yarn_option(ry, "k_global", ry_options.params.k_global);
  add_yarn_option(ry, "k_dt", ry_options.params.k_dt);
  add_yarn_option(ry, "k_dn", ry_options.params.k_dn);
  add_yarn_option(ry, "time_step", ry_options.time_step);
  ry->add_flag("--no-guard", ry_no_guard, "only the movement limit, no pull-through tests (to measure what the guard costs)");
  ry->add_flag("--no-safe-bounds", ry_no_bounds, "test every contact pair on every step (Yuksel eqs. 8-10 off)");
  ry->add_flag("--no-shape", ry_no_shape, "no boundary constraints or patch-tracking forces");
  ry->add_flag("--no-boundary", ry_no_boundary, "no hard moment constraint on border loops (Yuksel eq. 5)");
  ry->add_flag("--no-patches", ry_no_patches, "no patch-tracking forces (Yuksel eqs. 6-7)");
  ry->add_flag("--no-audit", ry_no_audit, "skip the per-step topology audit (pull_through_events is then null)");
  auto* active_set = ry->add_flag("--active-set", ry_options.active_set.enabled,
                                  "converged points stop being integrated until their force grows or a neighbour moves (CPU only; the stop rule still sees every point)");
  const double wake_force = relax::ActiveSetOptions{}.wake_force;  // a sleeping point wakes above it: sleep below it
  ry->add_option("--sleep-force", ry_options.active_set.sleep_force,
                 "with --active-set: a point sleeps below this × ε1 |∇E_0| / √N (under the wake force, " + std::to_string(static_cast<int>(wake_force)) + ")")
      ->check(number_check(false, [wake_force](double x) { return x > 0 && x < wake_force; }, "(0, " + std::to_string(static_cast<int>(wake_force)) + ")"))
      ->needs(active_set)->capture_default_str();
  ry->add_option("--wake-move", ry_options.active_set.wake_move, "with --active-set: a sleeping point wakes when its neighbours moved this × r")
      ->check(positive())->needs(active_set)->capture_default_str();
  add_yarn_option(ry, "contact_spacing", ry_options.sampling.spacing);
  std::string ry_warm, ry_warm_project;
  workflow::LocalRelaxOptions ry_local;
  ry->add_option("--warm-start", ry_warm, "the relaxed yarn (.bcc) of --warm-project: start from it and relax only the stitches changed since, "
                                          "and --rings rings around them");
  ry->add_option("--warm-project", ry_warm_project, "with --warm-start: the project its yarn was emitted from, before the edits");
  add_yarn_option(ry, "rings", ry_local.rings, "with --warm-start: ");
  add_yarn_option(ry, "halo", ry_local.halo, "with --warm-start: ");
  bool ry_stand_in = false;
  workflow::StandInOptions ry_stand_in_options;
  ry->add_flag("--stand-in", ry_stand_in,
               "a fast preview, not a relaxation: each repeating pattern's periodic patch (stockinette, rib, seed ...) relaxed and mapped over "
               "the faces knitted in it; the output is marked as a preview");
  ry->add_option("--stand-in-min-faces", ry_stand_in_options.min_faces, "with --stand-in: fewest faces of a repeat for it to get a patch")
      ->capture_default_str();
  ry->add_option("--stand-in-max-period", ry_stand_in_options.max_period,
                 "with --stand-in: longest repeat looked for, in stitches along the row and the wale (1 to 16)")
      ->capture_default_str();
  ry->add_option("--stand-in-reach", ry_stand_in_options.reach,
                 "with --stand-in: rings of stitches beyond a region that join it where their type is the pattern's there")
      ->capture_default_str();
  std::vector<std::string> ry_stand_in_patterns;
  ry->add_option("--stand-in-pattern", ry_stand_in_patterns,
                 "with --stand-in: a pattern tiled onto the garment that re-meshes (cables, lace, increases, decreases; patterns/FORMAT.md): "
                 "its whole repeats get a stand-in too (repeat the option for several)");

  // skein pattern
  auto* pat = app.add_subcommand("pattern", "a knitting or weaving pattern written as text, tiled and optionally relaxed (Yuksel 2012 §5.3, Leaf 2018 §4)");
  std::string pat_in, pat_out, pat_tile = "4x4", pat_report, pat_png, pat_log, pat_stitches, pat_backend = "auto";
  mesh::StitchSize pat_size;
  double pat_radius = 0, pat_take_up = 1;
  bool pat_relax = false;
  relax::YarnRelaxOptions pat_options;
  pat->add_option("FILE", pat_in, "pattern text (patterns/FORMAT.md): format knit, tiles or woven, written instructions, a chart or a WIF weaving draft")->required();
  pat->add_option("-o,--output", pat_out, "yarn to write (.bcc or .obj polylines); not needed when only --chart-png, --write-chart or --write-instructions is asked");
  pat->add_option("--tile", pat_tile, "repeats across x up (NxM) of the emitted yarn, of --relax --tiled, or of --preview (the periodic patch has its own)")
      ->capture_default_str();
  std::string pat_preview, pat_preview_png;
  pat->add_option("--preview", pat_preview, "with --relax: the relaxed repeat tiled NxM (--tile) as yarn (.bcc or .obj), a preview of the fabric");
  pat->add_option("--preview-png", pat_preview_png, "with --relax: picture of the --tile NxM preview, front and back");
  bool pat_tiled = false;
  pat->add_flag("--relax", pat_relax, "relax the pattern's periodic patch (Leaf 2018 §5; FIRE, pull-through guard) and write it");
  pat->add_flag("--tiled", pat_tiled, "with --relax: relax the NxM tiling with free borders instead of the periodic patch");
  pat->add_option("--report", pat_report, "JSON report: the pattern and its yarn; with --relax the same report as relax-yarn");
  pat->add_option("--png", pat_png, "picture of the yarn, front and back");
  std::string pat_tubes;
  pat->add_option("--tubes", pat_tubes, "also write the yarn (relaxed with --relax) as tubes for any renderer: OBJ in mm, or glTF 2.0 (.glb, .gltf) in metres; "
                                        "a pattern in colours gets a material per colour");
  std::string pat_ids, pat_chart_png;
  pat->add_option("--chart-png", pat_chart_png, "the repeat drawn as a knitting chart in the Craft Yarn Council's symbols (patterns/FORMAT.md), as skein "
                                                "read it; knits and tiles");
  std::string pat_write_chart, pat_write_instructions;
  pat->add_option("--write-chart", pat_write_chart, "the repeat as chart text (format chart: the Craft Yarn Council's symbols, patterns/FORMAT.md) that "
                                                    "skein reads back as the same stitches; knits and tiles");
  pat->add_option("--write-instructions", pat_write_instructions, "the repeat as written instructions (\"Row 1 (RS): k2, p2.\") that skein reads back "
                                                                  "as the same stitches; knits and tiles");
  pat->add_option("--ids", pat_ids, "also write each control point's stitch face, row and type as CSV (docs/FORMATS.md): knits and tiles, "
                                    "emitted or relaxed --tiled");
  pat->add_option("--log", pat_log, "with --relax: per-step CSV log as relax-yarn writes it");
  pat->add_option("--stitch-size", pat_size.width, "knits: stitch width [mm]; wovens: yarn spacing is 4 yarn radii")->capture_default_str();
  pat->add_option("--stitch-height", pat_size.height, "knits: stitch height [mm]")->capture_default_str();
  pat->add_option("--yarn-radius", pat_radius, "yarn radius [mm] (default: a tenth of the stitch width)")->check(positive());
  FabricChoice pat_fabric;
  add_fabric(pat, pat_fabric, "sets the yarn radius and, without --gauge, the stitch size of its standard gauge", true);
  add_yarn_option(pat, "take_up", pat_take_up, "with --relax: ");
  std::vector<std::string> pat_take_up_stitch;
  pat->add_option("--take-up-stitch", pat_take_up_stitch, "with --relax: TYPE=F scales the yarn of one stitch type (s=0.8), TYPE:vertical=F or TYPE:horizontal=F only its loop carried up or its row's yarn (s:vertical=0.5), or weft=F, warp=F (Leaf 2018 §6.1)");
  std::string pat_period;
  pat->add_option("--period", pat_period, "with --relax: the repeat's period x its emitted size, along the course x the wale (e.g. 0.9x1)");
  double pat_gamma = 1;
  pat->add_option("--gamma", pat_gamma, "with --relax: relax at gamma x the yarn radius and scale back by 1/gamma: 1/gamma of the yarn length (Leaf 2018 §6.2)")
      ->check(in_range(relax::kMinGamma, relax::kMaxGamma))->capture_default_str();
  pat->add_option("--stitches", pat_stitches, "stitch library folder (default: the bundled stitches/)");
  pat->add_option("--backend", pat_backend, "with --relax: auto, cpu or cuda")->check(CLI::IsMember({"auto", "cpu", "cuda"}))->capture_default_str();
  add_yarn_option(pat, "max_steps", pat_options.max_steps, "with --relax: ");
  add_yarn_option(pat, "max_seconds", pat_options.max_seconds, "with --relax: ");
  add_yarn_option(pat, "tolerance", pat_options.tolerance, "with --relax: ");
  std::string pat_method = "lbfgs";
  add_yarn_option(pat, "method", pat_method, "with --relax: ");
  std::string pat_stop_rule = "force";
  add_yarn_option(pat, "stop_rule", pat_stop_rule, "with --relax: ");
  add_yarn_option(pat, "force_tolerance", pat_options.force_tolerance);
  add_yarn_option(pat, "stall_window", pat_options.stall_window);
  add_yarn_option(pat, "energy_stall", pat_options.energy_stall);
  std::string pat_free_axes;
  pat->add_option("--free-period", pat_free_axes,
                  "with --relax: the repeat's period relaxes too, to zero mean stress (variable-cell): the pattern's own gauge, in the report; "
                  "x (no value: the width, the rows held at the height of the gauge), y or xy (frictionless yarn's rows may slide apart: "
                  "docs/patterns.md)")
      ->expected(0, 1)->default_str("x")->check(CLI::IsMember({"xy", "x", "y"}));
  pat->add_option("--period-tolerance", pat_options.period.tolerance, "with --free-period: the largest stress left, × B/r³")->capture_default_str();
  add_yarn_option(pat, "k_bend", pat_options.params.k_bend, "with --relax: ");
  add_yarn_option(pat, "k_contact", pat_options.params.k_contact, "with --relax: ");
  add_yarn_option(pat, "k_stretch", pat_options.params.k_stretch, "with --relax: ");
  pat->add_flag("--shear", pat_options.period.shear, "with --free-period: the repeat may shear too (a diagonal pattern); without it only its two lengths relax");
  add_yarn_option(pat, "contact_spacing", pat_options.sampling.spacing, "with --relax: ");
  std::string pat_views = "flat";
  int pat_panel = 900;
  pat->add_option("--views", pat_views, "flat (front and back), front, or three (front, back, three-quarter), for --png and --preview-png")
      ->check(CLI::IsMember({"flat", "front", "three"}))->capture_default_str();
  pat->add_option("--png-size", pat_panel, "pixels per view of --png")->transform(whole_in_range(64, 4096))->capture_default_str();
  std::string pat_onto, pat_rows;
  int pat_face = 0;
  auto* onto_opt = pat->add_option("--onto", pat_onto, "tile the pattern onto this project's stitch mesh instead (-o writes the project)");
  pat->add_option("--face", pat_face, "with --onto: the stitch that takes the pattern's first stitch")->needs(onto_opt)->capture_default_str();
  pat->add_option("--rows", pat_rows, "with --onto: the rows A:B the pattern covers (default: all)")->needs(onto_opt);
  bool pat_no_audit = false;
  pat->add_flag("--no-audit", pat_no_audit, "with --relax: skip the per-step topology audit");

  // skein smock (issue 30)
  auto* smock = app.add_subcommand("smock", "gather a smocking pattern by its threads: Italian, Canadian or English smocking (Zhou 2024 §4.1; docs/smocking.md)");
  SmockArgs sm;
  smock->add_option("PATTERN", sm.input, "smocking pattern (.smock, docs/smocking.md), or an .svg drawing of its stitches (front solid, back dashed)")->required();
  smock->add_option("--style", sm.style, "an .svg drawing's style: italian (default), canadian or english");
  smock->add_option("--svg-grid", sm.svg.grid, "an .svg drawing's grid spacing in its own units (default: the smallest step between stitch ends)")
      ->check(in_range(1e-9, 1e9));
  smock->add_option("--svg-margin", sm.svg.margin, "grid squares of fabric around an .svg drawing's stitches")->capture_default_str()->transform(whole_in_range(0, 1000));
  smock->add_option("--svg-spacing", sm.svg.spacing, "mm between grid points of an .svg drawing's pattern")->capture_default_str()->check(in_range(0.1, 1000.0));
  smock->add_option("--write-smock", sm.write_smock, "the pattern as .smock text (what an .svg drawing was read as)");
  smock->add_option("-o,--output", sm.output, "the embedding as JSON: grid points flat and gathered, each stitch's lifted midpoint (eqs. 6-8)");
  smock->add_option("--obj", sm.obj, "the threads' positional constraints in 3-D as OBJ lines (z towards the front)");
  smock->add_option("--png", sm.png, "picture: the pattern as drawn, the --snapshots, and the gathered fabric, at one scale");
  smock->add_option("--chart-png", sm.chart_png, "picture: the threads' length over the iterations, the goal dashed");
  smock->add_option("--report", sm.report, "report (JSON; - for stdout)");
  smock->add_option("--cloth", sm.cloth, "the smocked fabric in 3-D (§4.2) as a triangle mesh (.obj, or glTF .glb/.gltf): a fine mesh guided to the lifted stitches, "
                    "never passing through itself, certified by an exact triangle test");
  smock->add_option("--cloth-png", sm.cloth_png, "picture of the 3-D fabric, from the front and from the side");
  smock->add_option("--subdivisions", sm.cloth_options.subdivisions, "with --cloth: fine squares per side of a pattern square (even)")->capture_default_str();
  smock->add_option("--gamma", sm.gamma, "pull the threads to this fraction of their sewn length (default: the pattern's gamma line)")->check(in_range(1e-6, 1.0));
  smock->add_option("--thickness", sm.options.thickness, "fabric thickness [mm] (default: 1 % of the grid's longer side, the paper's setting)")
      ->check(in_range(1e-6, 1e4));
  smock->add_option("--pull", sm.pull, "pulling direction X,Y, or \"along\": each stitch pulled along itself (the paper's CURVE pattern)")->capture_default_str();
  smock->add_option("--snapshots", sm.options.snapshots, "also keep and draw the fabric when the threads first reach these fractions, e.g. 0.8,0.6,0.4")
      ->delimiter(',')->check(in_range(1e-6, 1.0));
  bool smock_raw = false;
  smock->add_flag("--no-settle", smock_raw, "leave the pleat points where Algorithm 1 stops (the paper's output; the fabric may be stretched there)")
      ->each([&](const std::string&) { sm.options.settle = false; });
  smock->add_option("--max-iterations", sm.options.max_iterations, "stop after this many iterations")->capture_default_str()->transform(whole_in_range(0, 1000000000));

  // skein weave-exemplar and weave-volume (issue 29)
  auto* wex = app.add_subcommand("weave-exemplar", "relax small woven patches and voxelize them as exemplars for weave-volume (Zhao 2012 §4, §6; docs/woven.md)");
  WeaveExemplarArgs wx;
  wex->add_option("PATTERN", wx.patterns, "woven patterns (.weave or .wif), one exemplar each")->required();
  wex->add_option("-o,--output", wx.output, "folder for the exemplars (one .vdb per pattern file, named as it)")->required();
  wex->add_option("--report", wx.report, "report (JSON; - for stdout)");
  wex->add_option("--crossings", wx.options.crossings, "crossings along each side of an exemplar")->capture_default_str()->transform(whole_in_range(2, 64));
  wex->add_option("--radius", wx.options.radius, "yarn radius [mm]")->capture_default_str()->check(in_range(0.01, 10.0));
  wex->add_option("--spacing", wx.options.spacing, "crossing spacing [mm] (default: 3 radii)")->check(in_range(0.02, 100.0));
  wex->add_option("--tension", wx.options.tension, "the loom's tension: rest lengths are the emitted lengths times 1 - tension")
      ->capture_default_str()->check(in_range(0.0, 0.19));
  wex->add_option("--voxels", wx.options.voxels_per_crossing, "voxels per crossing along x and y")->capture_default_str()->transform(whole_in_range(4, 256));
  wex->add_option("--jitter", wx.options.jitter, "random displacement of the emitted yarn along each axis (a share of the spacing) and spread of the yarns' radii (a share of the radius)")
      ->capture_default_str()->check(in_range(0.0, 0.19));
  wex->add_option("--plies", wx.options.plies, "plies twisted into each yarn")->capture_default_str()->transform(whole_in_range(1, 8));
  wex->add_option("--twist", wx.options.twist, "length of one ply turn [mm] (default: 8 radii)")->check(in_range(0.01, 1000.0));
  wex->add_option("--migration", wx.options.migration, "how far fibres migrate across a ply over one ply turn, a share of its radius")
      ->capture_default_str()->check(in_range(0.0, 1.0));
  wex->add_option("--seed", wx.options.seed, "random seed of the jitter and the fibres")->capture_default_str();
  wex->add_option("--max-steps", wx.options.max_steps, "relaxation steps at most")->capture_default_str()->transform(whole_in_range(0, 1000000));

  auto* wvol = app.add_subcommand("weave-volume", "synthesize the volumetric appearance of a woven design from exemplars and render it (Zhao 2012 §5; docs/woven.md)");
  WeaveVolumeArgs wv;
  wvol->add_option("PATTERN", wv.pattern, "the design: a woven pattern (.weave or .wif), tiled to --size");
  wvol->add_option("--picture", wv.picture, "or a posterized picture (PNG), one crossing per pixel, each colour woven with one of --weaves (§5.2)");
  wvol->add_option("--weaves", wv.weaves, "with --picture: one elementary weave (.weave or .wif) per colour, in the order the colours first appear (top row first)")
      ->delimiter(',');
  wvol->add_option("--exemplars", wv.exemplars, "folder of exemplars from weave-exemplar (default: the bundled set, made on the fly)");
  wvol->add_option("--size", wv.size, "WxH crossings (default: the repeat tiled to about 48 x 48)");
  wvol->add_option("-o,--output", wv.output, "a region of the synthesized volume as OpenVDB (grids density, orientation, yarn)");
  wvol->add_option("--region", wv.region, "X,Y,W,H: the crossings -o writes (default: all up to 16 x 16, else the centre 16 x 16; at most 64 M voxels)");
  wvol->add_option("--png", wv.png, "rendering: volumetric path tracing with the microflake phase function");
  wvol->add_option("--report", wv.report, "report (JSON; - for stdout)");
  wvol->add_option("--assignment", wv.assignment, "text: each crossing's exemplar block");
  wvol->add_option("--warp-colors", wv.warp_colors, "warp colours #rrggbb, cycled over the warps")->capture_default_str();
  wvol->add_option("--weft-colors", wv.weft_colors, "weft colours #rrggbb, cycled over the wefts")->capture_default_str();
  wvol->add_flag("--compare-truth", wv.compare_truth, "also relax the design directly as one patch (square, up to 32 x 32 crossings) and report how far "
                                                    "the synthesized volume is from it; with --png, both rendered side by side (PNG-truth.png)");
  wvol->add_option("--edge-rank", wv.edge_rank, "edge fixing's rank r (§5.5); 0: no edge fixing")->capture_default_str()->transform(whole_in_range(0, 256));
  bool wv_fixed = false;
  wvol->add_flag("--no-randomize", wv_fixed, "keep the dynamic program's blocks (no random shifts by the exemplars' symmetries)")
      ->each([&](const std::string&) { wv.synthesis.randomize = false; });
  wvol->add_option("--seed", wv.synthesis.seed, "random seed of the randomization")->capture_default_str();
  wvol->add_option("--width", wv.render.width, "picture width [pixels]")->capture_default_str()->transform(whole_in_range(8, 8192));
  wvol->add_option("--height", wv.render.height, "picture height [pixels]")->capture_default_str()->transform(whole_in_range(8, 8192));
  wvol->add_option("--samples", wv.render.samples, "paths per pixel")->capture_default_str()->transform(whole_in_range(1, 65536));
  wvol->add_option("--field", wv.render.field, "the picture's width on the fabric [mm] (default: the whole fabric)")->check(in_range(0.01, 1e6));
  wvol->add_option("--tilt", wv.render.tilt, "the view's angle from straight down [degrees]")->capture_default_str()->check(in_range(0.0, 80.0));

  // skein audit
  auto* audit = app.add_subcommand("audit", "what changed between two states of one yarn: crossings and linking numbers");
  std::string audit_before, audit_after;
  audit->add_option("BEFORE", audit_before, "yarn before (.bcc)")->required();
  audit->add_option("AFTER", audit_after, "yarn after (.bcc), the same curves and point counts")->required();
  std::string audit_ids;
  audit->add_option("--ids", audit_ids, "the stitch ids side file of BEFORE's yarn (skein yarn/relax-yarn/pattern --ids): name each crossing's stitches "
                                        "(face, row, type)");
  double audit_deviation = 0.1;
  audit->add_option("--deviation", audit_deviation, "the linking numbers' polylines stay this close to the curves, × r (refined further where curves come close); "
                                                   "the crossing test is exact and has no deviation")
      ->capture_default_str()->check(in_range(1e-4, 1.0));

  // skein run
  auto* run_cmd = app.add_subcommand("run", "run a job file: the whole pipeline from a mesh to relaxed yarn, unattended (docs/jobs.md)");
  std::string run_file, run_output;
  bool run_resume = false;
  run_cmd->add_option("JOB", run_file, "job file (.json)")->required();
  run_cmd->add_option("-o,--output", run_output, "output folder (default: the job's \"output\")");
  run_cmd->add_flag("--resume", run_resume, "go on from the yarn checkpoint in the output folder");
  double run_seconds = -1;
  run_cmd->add_option("--yarn-seconds", run_seconds, "wall-time cap of the yarn relaxation [s], in place of the job's (0: none; for overnight runs)");

  // skein sweep
  auto* sweep_cmd = app.add_subcommand("sweep", "relax each case of a sweep file (patterns x yarns x gauges x gamma x take-up) in this process: one report, "
                                                "table and chart (docs/sweeps.md; skein-mpi sweep shares the cases among MPI ranks)");
  std::string sweep_file, sweep_output;
  sweep_cmd->add_option("SWEEP", sweep_file, "sweep file (.json)")->required();
  sweep_cmd->add_option("-o,--output", sweep_output, "output folder (default: the sweep's \"output\")");

  // skein stats
  auto* stats = app.add_subcommand("stats", "counts and validity of a mesh, labeling, stitch mesh or yarn (.bcc)");
  std::string stats_in;
  bool stats_json_flag = false;
  stats->add_option("FILE", stats_in, "mesh or .skein project")->required();
  std::string stats_out;
  stats->add_flag("--json", stats_json_flag, "print JSON (default: text)");
  stats->add_option("-o,--output", stats_out, "write the JSON here instead of printing it");

  // skein render
  auto* render_cmd = app.add_subcommand("render", "draw a project's stitch mesh to PNG");
  std::string render_in, render_out, render_color = "row";
  bool render_yarn = false;
  double render_radius = 0;
  render_cmd->add_option("INPUT", render_in, ".skein project (its stitch mesh, or with --yarn its yarn) or .bcc yarn")->required();
  render_cmd->add_option("-o,--output", render_out, "PNG to write")->required();
  render_cmd->add_flag("--yarn", render_yarn, "draw the project's yarn as tubes instead of its stitch mesh");
  render_cmd->add_option("--yarn-radius", render_radius, "yarn radius [mm] for --yarn (default: a tenth of the stitch width)");
  render_cmd->add_option("--color", render_color, "row, type or colour (the yarn's colours, patterns/FORMAT.md) for stitch meshes; type, yarn or colour for yarn")
      ->check(CLI::IsMember({"row", "type", "yarn", "colour"}));
  std::string render_views = "garment";
  render_cmd->add_option("--views", render_views, "garment (three-quarter front, back-side), flat (front, back) or three (front, back, three-quarter)")
      ->check(CLI::IsMember({"garment", "flat", "three"}));

  // skein devices
  auto* devices = app.add_subcommand("devices", "say which CUDA devices answer");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a bad option or value is a user's error like any other: exit 2 (README).
    return app.exit(e) == 0 ? 0 : 2;
  }
  // The log goes to stderr, so that what a command prints as data (--stats -, a script's CSV) stays clean.
  if (!spdlog::get("skein")) spdlog::set_default_logger(spdlog::stderr_color_mt("skein"));  // once a process
  spdlog::set_pattern("[%H:%M:%S.%e] %^%l%$ %v");
  spdlog::set_level(quiet ? spdlog::level::warn : spdlog::level::info);
  height_given = stitch->count("--stitch-height") > 0;

  try {
    if (*stitch) {
      if (!auto_label && !trace_field && stitch_labels.empty()) throw Error("", "skein stitch", "give --auto-label, --field or --labels FILE");
      if (start_edge >= 0 && !auto_label && !trace_field) throw Error("", "skein stitch", "--start-edge needs --auto-label or --field");
      if (!height_given) size.height = size.width * 5.0 / 6.0;
      const auto fabric = resolve_fabric(stitch_fabric, size_given(stitch), false);
      if (fabric.size) size = *fabric.size;
      if (!stitch_fabric.yarn.empty()) spdlog::info("stitch size {:.3g} x {:.3g} mm for {} yarn; give --yarn to skein yarn too", size.width, size.height, stitch_fabric.yarn);
      size.validate();
      for (const auto& p : {stitch_out, stitch_png, stitch_png_types})
        if (!p.empty()) check_writable(p);
      Stopwatch total, t;
      mesh::Project project;
      project.stitch_size = size;
      project.input = load_input(stitch_in, stitch_repair);
      const auto& m = *project.input;
      spdlog::info("loaded {}: {} vertices, {} faces ({:.3f} s)", stitch_in, m.num_vertices(), m.num_faces(), t.seconds());
      mesh::check_stitch_count(m, size, max_stitches);  // before any work that grows with the stitch count
      t = {};
      std::optional<mesh::TessellationValues> stored_values;
      if (trace_field) {
        mesh::KnitStart knit_start;
        knit_start.border_edge = start_edge;  // -1: the lowest
        if (!start_point.empty()) knit_start.point = Eigen::Vector3d(start_point[0], start_point[1], start_point[2]);
        std::optional<mesh::KnitStart> knit_end;
        if (end_edge >= 0) knit_end = mesh::KnitStart{end_edge, {}};
        if (!end_point.empty()) knit_end = mesh::KnitStart{-1, Eigen::Vector3d(end_point[0], end_point[1], end_point[2])};
        auto traced = mesh::trace_stitch_mesh(m, knit_start, size, knit_end);
        spdlog::info("traced {} rows on {} isolines of the knitting distance (farthest {:.1f} mm): {} faces, {} cast-on and {} closed-off rows ({:.3f} s)",
                     traced.labels.rows, traced.levels, traced.field_max, traced.mesh.num_faces(), traced.row_starts, traced.row_ends, t.seconds());
        project.input = std::move(traced.mesh);
        project.labels = std::move(traced.labels);
        stored_values = std::move(traced.values);
      } else if (auto_label) {
        project.labels = mesh::auto_label(m, start_edge >= 0 ? start_edge : mesh::default_start_edge(m));
      } else {
        auto stored = labels_for(m, stitch_labels);
        project.labels = std::move(stored.first);
        stored_values = std::move(stored.second);
      }
      const mesh::InputMesh& rows_mesh = *project.input;  // the traced rows with --field, else the mesh read
      const auto report = mesh::validate_labels(rows_mesh, *project.labels);
      spdlog::info("labeled {} rows ({:.3f} s); {} edges with opposite wale directions on their two sides", project.labels->rows, t.seconds(),
                   report.mismatches.size());
      log_face_problems(stitch_in, rows_mesh, report, spdlog::level::err);
      t = {};
      if (trace_field) {
        project.values = std::move(stored_values);  // one stitch a traced face
      } else if (stored_values && !size_given(stitch) && !fabric.size) {
        project.values = std::move(stored_values);
        spdlog::info("using the tessellation values stored in {}", stitch_labels);
      } else {
        project.values = mesh::initial_values(rows_mesh, *project.labels, size);
      }
      project.stitch = mesh::tessellate(rows_mesh, *project.labels, *project.values);
      const auto s = mesh::stitch_stats(*project.stitch);
      spdlog::info("tessellated: {} stitch faces, {} rows, {} increases, {} decreases ({:.3f} s)", s.faces, s.rows, s.increases, s.decreases,
                   t.seconds());
      if (!s.valid) spdlog::error("the stitch mesh breaks rules:\n{}", mesh::validate(*project.stitch).summary());
      mesh::write_project(project, stitch_out);
      spdlog::info("wrote {} (total {:.2f} s)", stitch_out, total.seconds());
      if (!stitch_png.empty()) render_stitch_mesh(*project.stitch, stitch_png, render::ColorBy::Row);
      if (!stitch_png_types.empty()) render_stitch_mesh(*project.stitch, stitch_png_types, render::ColorBy::StitchType);
      if (!stitch_stats.empty()) write_json(stats_json(*project.stitch), stitch_stats);
      return s.valid ? 0 : 1;
    }
    if (*label) {
      check_writable(label_out);
      const auto label_fabric_size = resolve_fabric(label_fabric, size_given(label), false).size;
      mesh::Project project;
      project.input = load_input(label_in, label_repair);
      const auto& m = *project.input;
      if (first_rows.empty()) {
        project.labels = mesh::auto_label(m, label_start >= 0 ? label_start : mesh::default_start_edge(m));
      } else {
        project.labels = mesh::Labeling(m);
        for (int e : first_rows) mesh::label_first_row(m, *project.labels, e);
        for (int e : next_rows) mesh::label_next_row(m, *project.labels, e);
      }
      for (int r : flips) {
        if (r < 0 || r >= project.labels->rows) throw Error("", "--flip-row " + std::to_string(r), "no such row (there are " + std::to_string(project.labels->rows) + ")");
        mesh::flip_row(*project.labels, r);
      }
      const auto report = mesh::validate_labels(m, *project.labels);
      log_face_problems(label_in, m, report, label_partial ? spdlog::level::warn : spdlog::level::err);
      for (const auto& [e, why] : report.mismatches) spdlog::warn("{}: edge {}: {}", label_in, e, why);
      if (!report.valid() && !label_partial)
        throw Error(label_in, "face " + std::to_string(report.face_problems.front().first),
                    std::to_string(report.face_problems.size()) + " of " + std::to_string(m.num_faces()) +
                        " faces are not labeled (listed above); nothing written. --partial writes the labels made so far");
      if (label->count("--stitch-height") == 0) label_size.height = label_size.width * 5.0 / 6.0;
      if (label_fabric_size) label_size = *label_fabric_size;
      project.stitch_size = label_size;
      if (report.valid()) {
        project.values = mesh::initial_values(m, *project.labels, label_size);
        for (const auto& a : course_values) {
          const auto [e, n] = parse_assignment("--course-value", a);
          mesh::set_course_value(m, *project.labels, *project.values, e, n);
        }
        for (const auto& a : row_values) {
          const auto [r, n] = parse_assignment("--row-value", a);
          mesh::set_row_value(m, *project.labels, *project.values, r, n);
        }
        for (int e : marked_wales) mesh::mark_wale_edge(m, *project.labels, *project.values, e, true);
      }
      mesh::write_project(project, label_out);
      spdlog::info("{} rows; wrote {}", project.labels->rows, label_out);
      return report.valid() ? 0 : 1;
    }
    if (*edit) {
      check_writable(edit_out);
      auto project = mesh::read_project(edit_in);
      if (!project.stitch) throw Error(edit_in, "", "holds no stitch mesh; run 'skein stitch' first");
      auto& sm = *project.stitch;
      if (!edit_fill.empty()) {
        const auto pattern = mesh::parse_fill(edit_fill);
        std::vector<int> faces;
        if (near_border >= 0) {
          faces = mesh::faces_near_border(sm, near_border);
        } else {
          const auto [a, b] = edit_rows.empty() ? std::pair{0, INT32_MAX} : parse_rows(edit_rows);
          for (int f = 0; f < static_cast<int>(sm.faces.size()); ++f)
            if (sm.faces[f].row >= a && sm.faces[f].row <= b) faces.push_back(f);
        }
        sm = mesh::fill(sm, faces, pattern);
        spdlog::info("filled {} faces with {}", faces.size(), edit_fill);
      }
      if (!edit_type.empty()) sm = mesh::set_stitch_type(sm, edit_faces, edit_type);
      mesh::write_project(project, edit_out);
      if (!edit_png.empty()) render_stitch_mesh(sm, edit_png, render::ColorBy::StitchType);
      return 0;
    }
    if (*run_cmd) {
      auto job = read_job(run_file);
      if (!run_output.empty()) job.output = run_output;
      if (run_seconds >= 0 && job.relax_yarn) job.relax_yarn->max_seconds = run_seconds;
      return run_job(job, run_resume, !quiet && isatty(fileno(stderr)));
    }
    if (*sweep_cmd) {
      auto sweep = read_sweep(sweep_file);
      if (!sweep_output.empty()) sweep.output = sweep_output;
      prepare_sweep_output(sweep);
      Stopwatch t;
      auto rows = run_sweep_cases(sweep, 0, 1);
      return write_sweep(sweep, std::move(rows), t.seconds(), 1);
    }
    if (*stats) {
      json j;
      if (is_bcc(stats_in)) {
        j = yarn_json(workflow::read_bcc(stats_in));
      } else if (is_project(stats_in)) {
        const auto project = mesh::read_project(stats_in);
        if (project.stitch) j = stats_json(*project.stitch);
        else if (project.labels) j = {{"kind", "labeled-mesh"}, {"mesh", mesh_json(*project.input)}, {"labels", labels_json(*project.input, *project.labels)}};
        else if (project.input) j = mesh_json(*project.input);
      } else {
        j = mesh_json(mesh::load_mesh(stats_in));
      }
      if (!stats_out.empty()) {
        write_json(j, stats_out);
      } else if (stats_json_flag) {
        std::cout << j.dump(2) << "\n";
      } else {
        print_text(j, "");
      }
      return 0;
    }
    if (*render_cmd) {
      check_writable(render_out);
      if (render_yarn || is_bcc(render_in)) {
        render_yarn_tubes(yarn_of(render_in, render_radius, ""), render_out,
                          render_color == "yarn"     ? render::YarnColor::Yarn
                          : render_color == "colour" ? render::YarnColor::Colour
                                                     : render::YarnColor::StitchType,
                          render_views);
        return 0;
      }
      const auto project = mesh::read_project(render_in);
      if (!project.stitch) throw Error(render_in, "", "holds no stitch mesh to draw");
      render_stitch_mesh(*project.stitch, render_out,
                         render_color == "type" ? render::ColorBy::StitchType : render_color == "colour" ? render::ColorBy::Colour : render::ColorBy::Row,
                         render_views);
      return 0;
    }
    if (*relax_cmd) {
      for (const auto& p : {relax_out, relax_png, relax_png_before, relax_ply, relax_report})
        if (!p.empty()) check_writable(p);
      auto project = mesh::read_project(relax_in);
      if (!project.input || !project.stitch) throw Error(relax_in, "", "needs an input mesh and a stitch mesh (run 'skein stitch' first)");
      Stopwatch t;
      surface::MeshRelaxer relaxer(project.input->points(), project.input->faces(), *project.stitch, relax_options);
      spdlog::info("attached {} stitch vertices to the limit surface; rest r_course = {:.3f} mm, r_wale = {:.3f} mm ({:.2f} s)",
                   project.stitch->vertices.size(), relaxer.r_course(), relaxer.r_wale(), t.seconds());
      if (!relax_png_before.empty()) render_stretch(relaxer.relaxed(), relaxer.r_course(), relaxer.r_wale(), relax_png_before);
      t = {};
      const auto report = relaxer.run([&](const surface::MeshRelaxStep& s) {
        spdlog::info("step {:4d}  energy {:.6g}  largest move {:.4f} mm  cg {:3d}  h {:.3g}", s.step, s.energy, s.max_displacement, s.cg_iterations, s.time_step);
      });
      spdlog::info("{} after {} steps ({:.2f} s)", report.converged ? "converged" : "stopped at the step cap", report.steps.size(), t.seconds());
      spdlog::log(report.turned_over_after > 0 ? spdlog::level::warn : spdlog::level::info, "stitches turned over: {} after attachment, {} after relaxation",
                  report.turned_over_before, report.turned_over_after);
      project.stitch = relaxer.relaxed();
      mesh::write_project(project, relax_out);
      spdlog::info("wrote {}", relax_out);
      if (!relax_png.empty()) render_stretch(*project.stitch, relaxer.r_course(), relaxer.r_wale(), relax_png);
      if (!relax_ply.empty()) {
        const auto strain = surface::face_stretch(*project.stitch, relaxer.r_course(), relaxer.r_wale());
        render::write_ply(*project.stitch, stretch_colors(strain), {{"edge_strain", strain.edge_strain}, {"area_strain", strain.area_strain}}, relax_ply);
        spdlog::info("wrote {}", relax_ply);
      }
      if (!relax_report.empty()) {
        json steps = json::array();
        for (const auto& s : report.steps)
          steps.push_back({{"step", s.step}, {"energy", s.energy}, {"max_displacement", s.max_displacement}, {"cg_iterations", s.cg_iterations}, {"time_step", s.time_step}});
        write_json({{"r_course", report.r_course}, {"r_wale", report.r_wale}, {"initial_energy", report.initial_energy}, {"converged", report.converged},
                    {"turned_over_before", report.turned_over_before}, {"turned_over_after", report.turned_over_after}, {"steps", steps}},
                   relax_report);
      }
      return 0;
    }
    if (*yarn_cmd) {
      for (const auto& p : {yarn_out, yarn_tubes, yarn_png, yarn_ids})
        if (!p.empty()) check_writable(p);
      check_yarn_output(yarn_out);
      if (yarn_units != "mm" && is_bcc(yarn_out)) throw Error("", "--units " + yarn_units, "applies to OBJ outputs; a .bcc is in millimetres");
      Stopwatch t;
      mesh::EmitReport report;
      if (const auto fabric = resolve_fabric(yarn_fabric, false, yarn_cmd->count("--yarn-radius") > 0); fabric.radius) yarn_radius = *fabric.radius;
      const auto yarn = yarn_of(yarn_in, yarn_radius, stitches_dir, &report);
      spdlog::info("emitted {} yarns ({} closed), {} control points, radius {:.4g} mm ({:.3f} s)", yarn.curves(),
                   std::count(yarn.closed.begin(), yarn.closed.end(), 1), yarn.points.size(), yarn.radius, t.seconds());
      spdlog::info("borders: {} cast-on stitches, {} bind-off pieces, {} turns, {} tied ends; {} cable faces", report.cast_on, report.bind_off,
                   report.turns, report.tied_ends, report.cables);
      // OBJ carries no units: scaled here to the ones asked for. A .bcc says "radius R mm" and stays in mm.
      const double unit = yarn_units == "m" ? 1e-3 : yarn_units == "cm" ? 0.1 : 1.0;
      auto scaled = yarn;
      for (auto& p : scaled.points) p *= unit;
      scaled.radius *= unit;
      write_yarn(scaled, yarn_out, false, yarn_units);
      spdlog::info("wrote {}", yarn_out);
      if (!yarn_tubes.empty()) {
        write_tubes(yarn, yarn_tubes, unit, yarn_units);
        spdlog::info("wrote {}", yarn_tubes);
      }
      if (!yarn_ids.empty()) {
        workflow::write_point_ids(yarn, *mesh::read_project(yarn_in).stitch, yarn_ids);
        spdlog::info("wrote {}", yarn_ids);
      }
      if (!yarn_png.empty()) render_yarn_tubes(yarn, yarn_png,
                                               yarn_color == "yarn"   ? render::YarnColor::Yarn
                                               : yarn_color == "type" ? render::YarnColor::StitchType
                                                                      : own_colours(yarn));
      return 0;
    }
    if (*ry) {
      for (const auto& p : {ry_out, ry_report, ry_log, ry_png, ry_checkpoint})
        if (!p.empty()) check_writable(p);
      if (!ry_out.empty()) check_yarn_output(ry_out);
      bool ry_take_up_given = ry->count("--take-up") > 0;
      std::string ry_weight_option = "--yarn";  // where the yarn weight came from, for its errors
      if (is_project(ry_in) && std::filesystem::exists(ry_in)) {
        // The yarn settings the app saved with the project stand where the command line gives none.
        const auto project = mesh::read_project(ry_in);
        if (!project.settings.empty()) {
          const auto saved = workflow::read_yarn_settings(project.settings, ry_in);
          std::set<std::string> present;  // the keys the project sets: only those stand in for flags
          for (const auto& line : project.settings) present.insert(line.key);
          std::vector<std::string> taken;
          const auto take = [&](const char* key, auto apply) {
            const std::string flag = workflow::yarn_option(key).flag();
            if (present.count(std::string("yarn.") + key) && ry->count(flag) == 0) apply(), taken.push_back(flag);
          };
          take("method", [&] { ry_method = relax::to_string(saved.relax.method); });
          take("tolerance", [&] { ry_options.tolerance = saved.relax.tolerance; });
          take("stop_scale", [&] { ry_stop_scale = saved.relax.clipped_scale ? "clipped" : "first"; });
          take("max_steps", [&] { ry_options.max_steps = saved.relax.max_steps; });
          // A yarn weight the app saved: relaxed as --yarn WEIGHT. A weight's take-up is Munden's unless the command line
          // gives one: the app's take-up is not used with a weight, saved or given.
          if (!saved.weight.empty() && ry->count("--yarn") == 0 && ry->count("--yarn-radius") == 0)
            ry_fabric.yarn = saved.weight, ry_weight_option = "set yarn.weight " + saved.weight, taken.push_back("--yarn");
          else if (!saved.weight.empty())
            spdlog::info("{} saves the yarn weight {}: not used, the command line gives {}", ry_in, saved.weight, ry->count("--yarn") ? "--yarn" : "--yarn-radius");
          if (ry_fabric.yarn.empty())
            take("take_up", [&] { ry_take_up = saved.take_up, ry_take_up_given = true; });
          else if (present.count("yarn.take_up") && ry->count("--take-up") == 0)
            spdlog::info("{} saves a take-up of {}: not used with the yarn weight {}, whose take-up is Munden's", ry_in, saved.take_up, ry_fabric.yarn);
          take("audit", [&] { ry_no_audit = !saved.relax.audit; });
          take("active_set", [&] { ry_options.active_set.enabled = saved.relax.active_set.enabled; });
          take("contact_spacing", [&] { ry_options.sampling.spacing = saved.relax.sampling.spacing; });
          take("jam_steps", [&] { ry_options.jam_steps = saved.relax.jam_steps; });
          take("rings", [&] { ry_local.rings = saved.local.rings; });
          take("halo", [&] { ry_local.halo = saved.local.halo; });
          std::string list;
          for (const auto& flag : taken) list += (list.empty() ? "" : " ") + flag;
          spdlog::info("{} carries yarn settings (saved by the app): using them for {}", ry_in, list);
        }
      }
      double ry_radius_out = 0;  // a yarn weight's yarn: relaxed at its compressed contact radius, written at its full one
      if (const auto fabric = resolve_fabric(ry_fabric, false, ry->count("--yarn-radius") > 0); fabric.radius) {
        if (is_bcc(ry_in)) throw Error("", "--yarn", "sets the radius of yarn emitted from a project; a .bcc keeps its own");
        if (ry_stand_in || !ry_warm.empty())
          throw Error(ry_weight_option == "--yarn" ? "" : ry_in, ry_weight_option,
                      "relaxes a whole garment at the weight's compressed contact radius, not --stand-in or --warm-start (give --yarn-radius" +
                          std::string(ry_weight_option == "--yarn" ? ")" : ", or set yarn.weight none)"));
        ry_radius_out = *fabric.radius;
        ry_radius = mesh::kYarnCompression * ry_radius_out;
      }
      ry_options.method = relax::parse_yarn_method(ry_method);
      ry_options.clipped_scale = ry_stop_scale == "clipped";
      ry_options.stop_rule = relax::parse_stop_rule(ry_stop_rule);
      ry_options.guard.enabled = !ry_no_guard;
      ry_options.guard.safe_bounds = !ry_no_bounds;
      ry_options.audit = !ry_no_audit;
      ry_options.shape.boundary = !ry_no_boundary;
      ry_options.shape.patches = !ry_no_patches;
      ry_options.checkpoint = ry_checkpoint;
      if (!ry_checkpoint.empty() && ry_options.checkpoint_every == 0 && ry_options.checkpoint_minutes == 0) ry_options.checkpoint_every = 500;
      ry_options.validate();
      Stopwatch t;
      relax::YarnCurves yarn;
      relax::ShapeTargets targets;
      if (!is_bcc(ry_in) && !is_project(ry_in)) throw Error(ry_in, "", "relax-yarn reads a .skein project or .bcc yarn");
      if (!ry_ids.empty() && is_bcc(ry_in)) throw Error("", "--ids", "names each control point's stitch face: give a .skein project (" + ry_in + " is bare yarn)");
      if (!ry_ids.empty()) check_writable(ry_ids);
      std::optional<mesh::StitchMesh> ids_mesh;  // the stitch mesh the yarn was emitted from, for --ids
      const auto write_ids = [&](const relax::YarnCurves& written) {
        if (ry_ids.empty()) return;
        workflow::write_point_ids(written, *ids_mesh, ry_ids);
        spdlog::info("wrote {}", ry_ids);
      };
      if (is_bcc(ry_in)) {
        yarn = workflow::read_bcc(ry_in);
        if (!ry_no_shape) spdlog::info("{} is bare yarn: no stitch faces, so no shape preservation", ry_in);
      } else {
        const auto project = mesh::read_project(ry_in);
        if (!project.stitch) throw Error(ry_in, "", "holds no stitch mesh; run 'skein stitch' first");
        yarn = yarn_of(ry_in, ry_radius, ry_stitches);
        if (!ry_no_shape) targets = workflow::shape_targets(*project.stitch, yarn, ry_options.shape);
        ids_mesh = *project.stitch;
      }
      if (!ry_rest_lengths.empty() && (ry_stand_in || !ry_warm.empty()))
        throw Error("", "--rest-lengths", "applies to a whole relaxation, not to --stand-in or --warm-start");
      if (!ry_warm.empty() || !ry_warm_project.empty()) {
        if (ry_warm.empty() || ry_warm_project.empty() || !is_project(ry_in))
          throw Error("", "--warm-start", "relaxes a .skein project from the relaxed yarn (--warm-start) of the project before the edits (--warm-project)");
        if (!ry_resume.empty()) throw Error("", "--warm-start", "does not go with --resume");
        const auto project = mesh::read_project(ry_in);
        const auto previous_emitted = yarn_of(ry_warm_project, ry_radius, ry_stitches);
        const auto previous = workflow::read_bcc(ry_warm);
        if (previous.curve_start != previous_emitted.curve_start)
          throw Error(ry_warm, "", "holds other curves than the yarn of " + ry_warm_project + " (curve or point counts differ): it was not relaxed from it");
        Eigen::Matrix3Xd previous_points(3, previous.points.size());
        for (size_t p = 0; p < previous.points.size(); ++p) previous_points.col(p) = previous.points[p];
        const auto splice = workflow::splice_previous(yarn, previous_emitted, previous_points);
        spdlog::info("warm start from {}: {} of {} control points emitted as before, {} new", ry_warm, yarn.points.size() - splice.changed(),
                     yarn.points.size(), splice.changed());
        workflow::LocalRelaxReport local;
        const auto points = workflow::relax_locally(*project.stitch, yarn, splice, ry_options, ry_local, ry_take_up,
                                                 parse_take_up("--take-up-stitch", ry_take_up_stitch), local);
        if (local.stopped_by != relax::StopReason::UnsafeSplice) {
          const auto out = relax::with_points(yarn, points);
          write_yarn(out, ry_out);
          write_ids(out);
          spdlog::info("{} after {} steps in {} rounds ({:.2f} s): {} stitches changed, {} rings, {} pull-through events; wrote {}", relax::to_string(local.stopped_by),
                       local.steps, local.rounds, local.wall_seconds, local.changed_stitches, local.rings,
                       local.pull_through_events < 0 ? std::string("unaudited") : std::to_string(local.pull_through_events), ry_out);
          if (!ry_report.empty())
            write_json({{"input", ry_in}, {"converged", local.converged}, {"stopped_by", relax::to_string(local.stopped_by)}, {"steps", local.steps},
                        {"wall_seconds", local.wall_seconds}, {"control_points", out.points.size()},
                        {"pull_through_events", local.pull_through_events < 0 ? json(nullptr) : json(local.pull_through_events)},
                        {"warm_start", {{"previous", ry_warm}, {"project", ry_warm_project}, {"changed_points", local.changed_points},
                                        {"changed_stitches", local.changed_stitches}, {"rings", local.rings}, {"rounds", local.rounds},
                                        {"relaxed_points", local.relaxed_points}, {"held_points", local.held_points},
                                        {"last_boundary_move_r", local.last_boundary_move}, {"splice_crossings", local.splice_crossings}}},
                        {"yarn", yarn_json(out)}},
                       ry_report);
          if (!ry_png.empty()) render_yarn_tubes(out, ry_png, own_colours(out), ry_views);
          return local.stopped_by == relax::StopReason::Diverged ? 1 : 0;
        }
        spdlog::warn("warm start: the splice would pass yarn through yarn at {} places; relaxing the whole garment from its emission instead",
                     local.splice_crossings);
      }
      if (ry_stand_in) {
        if (!is_project(ry_in)) throw Error(ry_in, "", "--stand-in maps patches over a project's stitch faces: give a .skein project");
        if (!ry_resume.empty()) throw Error("", "--stand-in", "does not go with --resume");
        const auto project = mesh::read_project(ry_in);
        const auto& library = ry_stitches.empty() ? mesh::StitchLibrary::bundled() : mesh::StitchLibrary::load(ry_stitches);
        workflow::StandInReport stand_in;
        ry_stand_in_options.take_up = ry_take_up;
        ry_stand_in_options.take_up_by_type = parse_take_up("--take-up-stitch", ry_take_up_stitch);
        for (const auto& file : ry_stand_in_patterns) ry_stand_in_options.patterns.push_back(mesh::read_pattern(file));
        const Eigen::Matrix3Xd points =
            workflow::stand_in_preview(*project.stitch, yarn, library, ry_options, ry_stand_in_options, stand_in);
        // What the preview is worth: its energy as the relaxer measures it, and the auditor on the straight path from the emission.
        const auto system = relax::make_yarn_system(yarn, ry_take_up, parse_take_up("--take-up-stitch", ry_take_up_stitch), ry_options.sampling);
        auto probe = ry_options;
        probe.max_steps = 0;
        probe.audit = false;
        probe.checkpoint.clear();
        probe.checkpoint_every = 0;
        probe.checkpoint_minutes = 0;
        auto state = relax::initial_state(system, probe);
        state.points = points;
        const double energy = relax::make_cpu_yarn_relaxer(system, targets, probe)->run(state).energy;
        const long crossings = static_cast<long>(relax::TopologyAuditor(system).crossings(system.points, points).size());
        const auto out = relax::with_points(yarn, points);
        write_yarn(out, ry_out, true);
        write_ids(out);
        spdlog::info("stand-in preview (not a relaxation) in {:.2f} s: {} repeats, {} of {} control points placed from their patches, {} following "
                     "their yarn; {} crossings on the way from the emission; wrote {}",
                     stand_in.seconds, stand_in.repeats.size(), stand_in.placed, out.points.size(), stand_in.following, crossings, ry_out);
        if (!ry_report.empty()) {
          json repeats = json::array();
          for (const auto& t : stand_in.repeats)
            repeats.push_back({{"pattern", t.pattern}, {"across", t.across}, {"up", t.up}, {"faces", t.faces}, {"patch_steps", t.patch_steps},
                               {"patch_converged", t.converged}, {"patch_seconds", t.patch_seconds}});
          write_json({{"input", ry_in}, {"preview", "stand-in"}, {"wall_seconds", stand_in.seconds}, {"energy", energy},
                      {"control_points", out.points.size()}, {"pull_through_events", crossings},
                      {"stand_in", {{"repeats", repeats}, {"placed_points", stand_in.placed}, {"following_points", stand_in.following},
                                    {"taken_back_points", stand_in.taken_back}}},
                      {"yarn", yarn_json(out)}},
                     ry_report);
        }
        if (!ry_png.empty()) render_yarn_tubes(out, ry_png, own_colours(out), ry_views);
        return 0;
      }
      const auto make_system = [&](double take_up) {
        const auto by_type = parse_take_up("--take-up-stitch", ry_take_up_stitch);
        return ry_rest_lengths.empty()
                   ? relax::make_yarn_system(yarn, take_up, by_type, ry_options.sampling)
                   : relax::with_rest_lengths_of(relax::make_yarn_system(workflow::read_bcc(ry_rest_lengths), take_up, by_type, ry_options.sampling),
                                                 yarn, ry_rest_lengths);
      };
      auto system = make_system(ry_take_up);
      json ry_extra = json::object();
      if (ry_radius_out > 0) {
        // A yarn weight's garment, as `skein pattern --yarn` relaxes a repeat (docs/yarn.md): contact at the compressed
        // radius and, unless a take-up is given, each stitch's yarn cut (or let out) to Munden's loop length for the
        // project's stitch width.
        const double munden = mesh::gauge_of(mesh::read_project(ry_in).stitch_size).loop_length();
        const int stitches = static_cast<int>(ids_mesh->faces.size());
        ry_extra["fabric"] = {{"yarn", ry_fabric.yarn}, {"radius_mm", ry_radius_out}, {"contact_radius_mm", ry_radius}, {"munden_loop_length_mm", munden}};
        if (!ry_take_up_given) {
          ry_take_up *= workflow::take_up_to_munden(workflow::garment_loop_length(system, stitches), munden, ry_in,
                                                 ry_weight_option == "--yarn" ? "--yarn " + ry_fabric.yarn : ry_weight_option);
          system = make_system(ry_take_up);
          ry_extra["fabric"]["take_up_to_munden"] = ry_take_up;
        }
        const double loop = workflow::garment_loop_length(system, stitches);
        ry_extra["fabric"]["yarn_per_stitch_mm"] = loop;
        spdlog::info("{} yarn: contact radius {:.3g} mm ({} of {:.3g}), take-up {:.3f}: {:.2f} mm a stitch (Munden's loop length {:.2f} mm)",
                     ry_fabric.yarn, ry_radius, mesh::kYarnCompression, ry_radius_out, ry_take_up, loop, munden);
      }
      spdlog::info("{} yarns, {} control points, {} segments, r = {:.3g} mm, up to {} contact samples per segment; {} boundary loops, {} patches ({:.2f} s)",
                   system.num_curves(), system.num_points(), system.num_segments(), system.radius, *std::max_element(system.contact_samples.begin(), system.contact_samples.end()),
                   targets.boundary_loops.size(), targets.patches.size(), t.seconds());
      auto state = relax::initial_state(system, ry_options);
      if (!ry_resume.empty()) {
        state = relax::read_checkpoint(ry_resume, relax::checkpoint_fingerprint(system, ry_options.method), system.num_points());
        spdlog::info("resuming {} at step {}", ry_resume, state.step);
      }
      ry_options.interrupt = install_interrupt_handlers();
      const auto run = relax_and_write(yarn, system, targets, ry_options, state,
                                       {ry_in, ry_out, ry_backend, ry_report, ry_log, ry_png, ry_views, !quiet && isatty(fileno(stderr)),
                                        ry_extra, 900, own_colours(yarn), 1, ry_radius_out, {}, {}});
      if (run.stopped_by != relax::StopReason::Interrupted) write_ids(yarn);  // the relaxed yarn's points are the emitted ones, in order
      return exit_status(run.stopped_by);
    }
    if (*pat) {
      int across = 0, up = 0;
      char tail = 0;
      if (std::sscanf(pat_tile.c_str(), "%dx%d%c", &across, &up, &tail) != 2 || across < 1 || up < 1)
        throw Error("", "--tile", "expected NxM with N and M at least 1 (e.g. 4x4), found '" + pat_tile + "'");
      const auto pattern = mesh::read_pattern(pat_in);
      if (pattern.whole) {
        // A shaped piece is knitted once (patterns/FORMAT.md): not tiled, and relaxed with its free borders.
        if (pat->count("--tile") > 0 && (across != 1 || up != 1))
          throw Error(pat_in, "--tile", "is a shaped piece (it casts on and shapes its rows), knitted once: it takes --tile 1x1 or none");
        across = up = 1;
        if (pat_relax && !pat_tiled && pat_onto.empty())
          throw Error(pat_in, "--relax", "is a shaped piece: it has no periodic repeat; relax it whole with free borders (--relax --tiled)");
        if (!pat_onto.empty()) throw Error(pat_in, "--onto", "is a shaped piece: it is knitted as its own fabric, not tiled onto a garment");
      }
      std::optional<render::Image> chart;  // drawn now (a woven pattern is refused before any work), written with the outputs
      if (!pat_chart_png.empty()) {
        check_writable(pat_chart_png);
        chart = render::draw_chart(pattern);
      }
      // The pattern in the other notations, made now (a stitch no chart can say is refused before any work).
      std::string chart_text, instructions;
      try {
        if (!pat_write_chart.empty()) check_writable(pat_write_chart), chart_text = mesh::write_chart_pattern(pattern);
        if (!pat_write_instructions.empty()) check_writable(pat_write_instructions), instructions = mesh::write_written_pattern(pattern);
      } catch (const Error& e) {
        if (!e.file().empty()) throw;
        throw Error(pat_in, e.place(), e.rule());
      }
      const auto write_chart = [&] {
        if (chart) {
          render::write_png(*chart, pat_chart_png);
          spdlog::info("wrote {}", pat_chart_png);
        }
        for (const auto& written : {std::pair{pat_write_chart, chart_text}, {pat_write_instructions, instructions}}) {
          if (written.first.empty()) continue;
          write_file_atomically(written.first, [&](std::ostream& out) { out << written.second; });  // (clang 14: no structured binding in a lambda)
          spdlog::info("wrote {}", written.first);
        }
      };
      if (pat_out.empty()) {
        if (pat_relax || !pat_onto.empty() || !pat_png.empty() || !pat_report.empty() || !pat_ids.empty() ||
            (!chart && chart_text.empty() && instructions.empty()))
          throw Error("", "-o", "is required: the yarn (or with --onto the project) to write; only --chart-png, --write-chart and "
                                "--write-instructions go without it");
        write_chart();
        return 0;
      }
      if (!pat_onto.empty()) {
        check_writable(pat_out);
        auto project = mesh::read_project(pat_onto);
        if (!project.stitch) throw Error(pat_onto, "", "holds no stitch mesh; run 'skein stitch' first");
        const auto [a, b] = pat_rows.empty() ? std::pair{0, INT32_MAX} : parse_rows(pat_rows);
        std::vector<int> faces;
        for (int f = 0; f < static_cast<int>(project.stitch->faces.size()); ++f)
          if (project.stitch->faces[f].row >= a && project.stitch->faces[f].row <= b) faces.push_back(f);
        mesh::TileReport tiled;
        *project.stitch = mesh::tile_pattern(*project.stitch, faces, pattern, pat_face, &tiled);
        mesh::write_project(project, pat_out);
        write_chart();
        if (!pat_png.empty()) render_stitch_mesh(*project.stitch, pat_png, pattern.palette.empty() ? render::ColorBy::StitchType : render::ColorBy::Colour);
        if (tiled.repeats > 0)
          spdlog::info("tiled {} from face {}: {} whole {} x {} repeats re-meshed ({} of the {} chosen stitches); wrote {}", pattern.name, pat_face,
                       tiled.repeats, pattern.width(), pattern.height(), tiled.stitches, faces.size(), pat_out);
        else spdlog::info("tiled {} over {} of {} chosen stitches from face {}; wrote {}", pattern.name, tiled.stitches, faces.size(), pat_face, pat_out);
        return 0;
      }
      const auto fabric = resolve_fabric(pat_fabric, size_given(pat), pat->count("--yarn-radius") > 0);
      if (fabric.size) pat_size = *fabric.size;
      if (fabric.radius) pat_radius = *fabric.radius;
      const double radius = pat_radius > 0 ? pat_radius : 0.1 * pat_size.width;
      relax::YarnCurves yarn;
      relax::ShapeTargets targets;
      json pat_extra = {{"pattern", pattern.name}};
      const auto& library = pat_stitches.empty() ? mesh::StitchLibrary::bundled() : mesh::StitchLibrary::load(pat_stitches);
      // Leaf §6.2: the yarn is made and relaxed at gamma r, and the result scaled back by 1/gamma. A yarn weight's
      // yarn is relaxed at its compressed contact radius (kYarnCompression) and written at its full one.
      const bool compressed = pat_relax && !pat_fabric.yarn.empty() && pattern.format != mesh::PatternFormat::Woven;
      const double sim_radius = (pat_relax ? pat_gamma : 1.0) * (compressed ? mesh::kYarnCompression : 1.0) * radius;
      const bool preview = !pat_preview.empty() || !pat_preview_png.empty();
      if (preview && (!pat_relax || pat_tiled)) throw Error("", "--preview", "needs --relax on the periodic patch (not --tiled)");
      check_yarn_output(pat_out);  // before any work: a relaxation is not lost to a name the writer refuses
      if (!pat_preview.empty()) check_yarn_output(pat_preview);
      std::optional<workflow::PeriodicPatch> patch_kept;  // for the preview
      std::optional<mesh::StitchMesh> ids_mesh;        // for --ids: the tiling's stitch mesh
      if (!pat_ids.empty()) {
        if (pattern.format == mesh::PatternFormat::Woven) throw Error("", "--ids", "names each control point's stitch face, and a woven pattern has none");
        if (pat_relax && !pat_tiled)
          throw Error("", "--ids", "names each control point's stitch face in a tiling: the periodic patch is one repeat and its copies (add --tiled)");
        check_writable(pat_ids);
      }
      const auto write_ids = [&] {
        if (pat_ids.empty()) return;
        workflow::write_point_ids(yarn, *ids_mesh, pat_ids);
        spdlog::info("wrote {}", pat_ids);
      };
      Eigen::Vector2d period_scale(1, 1);
      if (pat_relax && !pat_tiled) {
        auto patch = pattern.format == mesh::PatternFormat::Woven ? workflow::periodic_woven_patch(pattern, 4 * radius, sim_radius)
                                                                  : workflow::periodic_patch(pattern, library, pat_size, sim_radius);
        if (preview) patch_kept = patch;
        spdlog::info("periodic patch: {} x {} repeats, {} real, {} virtual and {} frozen control points", patch.tiles, patch.tiles,
                     std::count(patch.ring.begin(), patch.ring.end(), 0), patch.map.virtual_points.size(), patch.map.frozen.size());
        pat_extra = {{"pattern", pattern.name},
                     {"periodic", {{"tiles", patch.tiles}, {"real_points", std::count(patch.ring.begin(), patch.ring.end(), 0)},
                                   {"virtual_points", patch.map.virtual_points.size()}, {"frozen_points", patch.map.frozen.size()}}}};
        yarn = std::move(patch.yarn);
        targets.periodic = std::move(patch.map);
      } else if (pattern.format == mesh::PatternFormat::Woven) {
        yarn = mesh::woven_yarn(pattern, across, up, 4 * radius, sim_radius);
        mesh::colour_woven_yarn(yarn, pattern, across, up);
      } else {
        const auto stitch_mesh = mesh::pattern_stitch_mesh(pattern, across, up, pat_size);
        mesh::EmitOptions emit;
        emit.yarn_radius = sim_radius;
        yarn = mesh::emit_yarn(stitch_mesh, library, emit);
        targets = workflow::shape_targets(stitch_mesh, yarn, pat_options.shape);
        ids_mesh = stitch_mesh;
      }
      if (!fabric.report.is_null()) pat_extra["fabric"] = fabric.report;
      spdlog::info("{}: {} x {} {}: {} yarns, {} control points", pattern.name, pattern.width(), pattern.height(),
                   pattern.whole ? "piece (cast on x rows)" : "repeat", yarn.curves(), yarn.points.size());
      // Yarn in colours: how much of each, as emitted (the tiling's, or with --relax the patch's).
      const auto colour_report = [&](const relax::YarnCurves& y) {
        json colours = json::array();
        const auto length = mesh::yarn_length_by_colour(y);
        for (size_t k = 0; k < pattern.palette.size(); ++k)
          colours.push_back({{"name", pattern.palette[k].name}, {"description", pattern.palette[k].description},
                             {"srgb", mesh::colour_code(pattern.palette[k].srgb)}, {"yarn_mm", k < length.size() ? length[k] : 0.0}});
        return colours;
      };
      const auto color = !pattern.palette.empty()                        ? render::YarnColor::Colour
                         : pattern.format == mesh::PatternFormat::Woven ? render::YarnColor::Yarn
                                                                        : render::YarnColor::StitchType;
      if (!pattern.palette.empty()) pat_extra["colours"] = colour_report(yarn);
      if (!pat_tubes.empty()) check_writable(pat_tubes);
      if (pat_relax) {
        pat_options.audit = !pat_no_audit;
        pat_options.stop_rule = relax::parse_stop_rule(pat_stop_rule);
        pat_options.method = relax::parse_yarn_method(pat_method);
        pat_options.period.free = pat->count("--free-period") > 0;
        pat_options.period.free_x = pat_free_axes != "y";
        pat_options.period.free_y = pat_free_axes == "y" || pat_free_axes == "xy";
        if (pat_options.period.free && pat_tiled) throw Error("", "--free-period", "needs the periodic patch (not --tiled)");
        pat_options.params = relax::radius_scaled(pat_options.params, pat_gamma);
        pat_options.validate();
        pat_extra["gamma"] = pat_gamma;
        const auto take_up_by_type = parse_take_up("--take-up-stitch", pat_take_up_stitch);
        auto system = relax::make_yarn_system(yarn, pat_take_up, take_up_by_type, pat_options.sampling);
        if (compressed) {
          // The yarn weight's fabric: contact at the compressed radius and, unless --take-up says otherwise, the
          // yarn of the periodic patch cut (or let out) to Munden's loop length for the gauge (docs/yarn.md).
          pat_extra["fabric"]["contact_radius_mm"] = sim_radius / pat_gamma;
          if (!targets.periodic.empty() && pat->count("--take-up") == 0 && pat_extra["fabric"].contains("munden_loop_length_mm")) {
            const double loop = patch_loop_length(system, targets.periodic, {pattern.width(), pattern.height()}) / pat_gamma;
            pat_take_up = workflow::take_up_to_munden(loop, pat_extra["fabric"]["munden_loop_length_mm"].get<double>(), pat_in, "--yarn " + pat_fabric.yarn);
            system = relax::make_yarn_system(yarn, pat_take_up, take_up_by_type, pat_options.sampling);
            pat_extra["fabric"]["take_up_to_munden"] = pat_take_up;
            spdlog::info("{} yarn: contact radius {:.3g} mm ({} of {:.3g}), take-up {:.3f} to Munden's loop length {:.2f} mm", pat_fabric.yarn,
                         sim_radius / pat_gamma, mesh::kYarnCompression, radius, pat_take_up,
                         pat_extra["fabric"]["munden_loop_length_mm"].get<double>());
          }
        }
        if (!pat_period.empty()) {
          double sx = 0, sy = 0;
          char tail = 0;
          if (targets.periodic.empty()) throw Error("", "--period", "needs the periodic patch (not --tiled)");
          if (std::sscanf(pat_period.c_str(), "%lfx%lf%c", &sx, &sy, &tail) != 2)
            throw Error("", "--period", "expected SXxSY (e.g. 0.9x1), found '" + pat_period + "'");
          relax::scale_period(targets.periodic, system.points, sx, sy);  // rest lengths stay those of the emitted yarn
          pat_extra["period"] = {sx, sy};
          period_scale = {sx, sy};
        }
        if (preview) pat_extra["preview"] = {{"output", pat_preview}, {"png", pat_preview_png}, {"tile", {across, up}}};
        auto state = relax::initial_state(system, pat_options);
        const auto run = relax_and_write(yarn, system, targets, pat_options, state,
                                         {pat_in, pat_out, pat_backend, pat_report, pat_log, pat_png, pat_views,
                                          !quiet && isatty(fileno(stderr)), pat_extra, pat_panel, color, 1 / pat_gamma,
                                          compressed ? radius : 0.0, {pattern.width(), pattern.height()}, pat_tubes});
        if (preview && run.stopped_by != relax::StopReason::Interrupted) {
          // The relaxed repeat tiled N x M: a preview of the fabric without relaxing the tiling.
          auto tiled = pattern.format == mesh::PatternFormat::Woven
                           ? mesh::woven_yarn(pattern, across, up, 4 * radius, sim_radius)
                           : mesh::emit_yarn(mesh::pattern_stitch_mesh(pattern, across, up, pat_size), library, {.yarn_radius = sim_radius});
          if (pattern.format == mesh::PatternFormat::Woven) mesh::colour_woven_yarn(tiled, pattern, across, up);
          const auto placed = workflow::tile_relaxed_patch(*patch_kept, state.points, tiled, period_scale, pat_options.period.free ? &state.period : nullptr);
          auto out = relax::with_points(tiled, placed.points / pat_gamma);
          out.radius = compressed ? radius : out.radius / pat_gamma;
          if (!pat_preview.empty()) write_yarn(out, pat_preview);
          if (!pat_preview_png.empty()) render_yarn_tubes(out, pat_preview_png, color, pat_views, pat_panel);
          spdlog::info("preview: the relaxed repeat tiled {} x {}, {} of {} control points placed from it (the rest, at the borders, follow their yarn){}",
                       across, up, placed.matched, out.points.size(), pat_preview.empty() ? std::string() : "; wrote " + pat_preview);
        }
        if (run.stopped_by != relax::StopReason::Interrupted) write_ids(), write_chart();
        return exit_status(run.stopped_by);
      }
      write_yarn(yarn, pat_out);
      write_ids();
      write_chart();
      if (!pat_report.empty()) {
        json j = {{"input", pat_in}, {"pattern", pattern.name}, {"source", pattern.note},
                  {"format", pattern.format == mesh::PatternFormat::Knit ? "knit" : pattern.format == mesh::PatternFormat::Tiles ? "tiles" : "woven"},
                  {"repeat", {pattern.width(), pattern.height()}}, {"tile", {across, up}}, {"yarn", yarn_json(yarn)}};
        if (!fabric.report.is_null()) j["fabric"] = fabric.report;
        if (pat_extra.contains("colours")) j["colours"] = pat_extra["colours"];
        if (pattern.whole) j["shaped_piece"] = true;
        write_json(j, pat_report);
      }
      if (!pat_png.empty()) render_yarn_tubes(yarn, pat_png, color, pat_views, pat_panel);
      if (!pat_tubes.empty()) write_tubes(yarn, pat_tubes), spdlog::info("wrote {}", pat_tubes);
      spdlog::info("wrote {}", pat_out);
      return 0;
    }
    if (*smock) return run_smock(sm);
    if (*wex) return weave_exemplar(wx), 0;
    if (*wvol) {
      if (!wv.pattern.empty() && !wv.picture.empty()) throw Error("", "weave-volume", "give a woven PATTERN or --picture, not both");
      weave_volume(wv);
      return 0;
    }
    if (*audit) {
      const auto before = workflow::read_bcc(audit_before), after = workflow::read_bcc(audit_after);
      if (before.curve_start != after.curve_start || before.closed != after.closed)
        throw Error(audit_after, "", "holds other curves than " + audit_before + " (curve count, point counts or closed flags differ)");
      const auto ids = audit_ids.empty() ? std::vector<workflow::PointId>{} : workflow::read_point_ids(audit_ids, before);
      const auto a = relax::audit_states(before, after, audit_deviation);
      const double r = before.radius;
      std::cout << "curves: " << a.curves << " (" << a.closed_curves << " closed), control points: " << a.points
                << "\nlargest control-point move: " << a.largest_move << " mm (" << a.largest_move / r << " r)\nRMS control-point move: " << a.rms_move
                << " mm (" << a.rms_move / r << " r)\n"
                << "centreline crossings on the straight path between the two states (exact test, Bezier hulls): " << a.crossings.size();
      if (a.unresolved > 0)
        std::cout << " (" << a.unresolved << " of them pairs the test could not settle in " << relax::kMaxAuditPieces
                  << " pieces, centrelines nearly touching along a stretch: counted as crossings)";
      std::cout << "\n";
      // A segment's points, and with the ids its stitch: its first point's, else its second's (a point of no face has none).
      const auto system = relax::make_yarn_system(before);
      const auto stitch_of = [&](int segment) -> const workflow::PointId* {
        for (int k : {1, 2})
          if (const int p = system.segment_points[segment][k]; ids[p].face >= 0) return &ids[p];
        return nullptr;
      };
      const auto describe = [&](int segment) {
        const workflow::PointId* id = ids.empty() ? nullptr : stitch_of(segment);
        return " (points " + std::to_string(system.segment_points[segment][1]) + "-" + std::to_string(system.segment_points[segment][2]) + ")" +
               (id ? " [face " + std::to_string(id->face) + ", row " + std::to_string(id->row) + ", " + id->type + "]" : std::string());
      };
      for (size_t i = 0; i < std::min<size_t>(a.crossings.size(), 20); ++i) {
        const auto& c = a.crossings[i];
        std::cout << "  segments " << c.segment_a << describe(c.segment_a) << " and " << c.segment_b << describe(c.segment_b) << " near (" << c.where.x()
                  << ", " << c.where.y() << ", " << c.where.z() << ")\n";
      }
      if (!ids.empty()) {
        std::set<int> faces, rows;
        for (const auto& c : a.crossings)
          for (int segment : {c.segment_a, c.segment_b})
            if (const auto* id = stitch_of(segment)) faces.insert(id->face), rows.insert(id->row);
        std::cout << "stitches in the crossings: " << faces.size() << " (in " << rows.size() << " rows)";
        int shown = 0;
        for (int f : faces) std::cout << (shown++ == 0 ? ": faces " : ", ") << f;
        std::cout << "\n";
      }
      for (size_t i = 0; i < std::min<size_t>(a.linking_changes.size(), 20); ++i) {
        const auto& l = a.linking_changes[i];
        std::cout << "linking number of closed curves " << l.a << " and " << l.b << ": " << l.before << " -> " << l.after << "\n";
      }
      std::cout << "linking numbers changed: " << a.linking_changes.size() << " (of " << a.linked_pairs << " pairs of closed curves that come near)\n";
      return a.unchanged() ? 0 : 1;
    }
    if (*devices) {
      const auto q = cuda::query_devices();
      std::cout << cuda::describe(q) << "\n";
      return 0;
    }
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  return 0;
}

}  // namespace skein::cli
