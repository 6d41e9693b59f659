// skein relax-yarn: relax yarn at yarn level without letting one yarn pass through another (Yuksel 2012 §6.3, Leaf 2018 §3)
#include "subcommand.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_checkpoint.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/project.hpp"
#include "workflow/yarn_io.hpp"
#include "workflow/yarn_local.hpp"
#include "workflow/yarn_options.hpp"
#include "workflow/yarn_settings.hpp"
#include "workflow/yarn_shape.hpp"
#include "workflow/yarn_standin.hpp"

using nlohmann::json;

namespace skein::cli {
namespace {

struct RelaxYarnCommand final : Subcommand {
  CLI::App* ry = nullptr;
  std::string ry_in, ry_out, ry_method = "fire", ry_resume, ry_report, ry_log, ry_png, ry_stitches;
  relax::YarnRelaxOptions ry_options;
  double ry_radius = 0, ry_take_up = 1;
  bool ry_no_guard = false, ry_no_shape = false, ry_no_audit = false, ry_no_bounds = false, ry_no_boundary = false, ry_no_patches = false;
  std::string ry_checkpoint;
  std::string ry_backend = "auto";
  std::string ry_ids;
  std::string ry_views = "garment";
  std::string ry_stop_rule = "leaf";
  std::string ry_stop_scale = "first";
  std::string ry_rest_lengths;
  std::vector<std::string> ry_take_up_stitch;
  FabricChoice ry_fabric;
  std::string ry_warm, ry_warm_project;
  workflow::LocalRelaxOptions ry_local;
  bool ry_stand_in = false;
  workflow::StandInOptions ry_stand_in_options;
  std::vector<std::string> ry_stand_in_patterns;

  void declare(CLI::App& app) override {
    ry = app.add_subcommand("relax-yarn", "relax yarn at yarn level without letting one yarn pass through another (Yuksel 2012 §6.3, Leaf 2018 §3)");
    ry->add_option("INPUT", ry_in, ".skein project (its stitch faces drive shape preservation) or .bcc yarn")->required();
    ry->add_option("-o,--output", ry_out, "relaxed yarn to write (.bcc or .obj polylines)")->required();
    add_yarn_option(ry, "method", ry_method);
    ry->add_option("--backend", ry_backend, "auto (the GPU when one answers, else the CPU), cpu or cuda (an error without a GPU)")
        ->check(CLI::IsMember({"auto", "cpu", "cuda"}))->capture_default_str();
    ry->add_option("--checkpoint", ry_checkpoint, "checkpoint file, written atomically every --checkpoint-every steps or minutes");
    add_yarn_option(ry, "checkpoint_every", ry_options.checkpoint_every, "", " (500 with --checkpoint when neither this nor --checkpoint-minutes is given)");
    add_yarn_option(ry, "checkpoint_minutes", ry_options.checkpoint_minutes);
    ry->add_option("--resume", ry_resume, "continue from this checkpoint (same input and method)");
    ry->add_option("--report", ry_report, "JSON report: converged, steps, wall_seconds, residual, guard_events, pull_through_events");
    ry->add_option("--log", ry_log, "per-step log as CSV: step, energy, residual, time step, largest move, contacts, guard hits, held points, crossings");
    ry->add_option("--png", ry_png, "picture of the relaxed yarn");
    ry->add_option("--ids", ry_ids, "also write each control point's stitch face, row and type as CSV (docs/FORMATS.md), for outside checks; a project's yarn");
    ry->add_option("--views", ry_views, "garment (three-quarter front, back-side), flat (front, back) or three (front, back, three-quarter) for --png")
        ->check(CLI::IsMember({"garment", "flat", "three"}))->capture_default_str();
    add_yarn_option(ry, "max_steps", ry_options.max_steps);
    add_yarn_option(ry, "max_seconds", ry_options.max_seconds);
    add_yarn_option(ry, "tolerance", ry_options.tolerance);
    add_yarn_option(ry, "stall", ry_options.stall);
    add_yarn_option(ry, "stop_rule", ry_stop_rule);
    add_yarn_option(ry, "force_tolerance", ry_options.force_tolerance);
    add_yarn_option(ry, "stall_window", ry_options.stall_window);
    add_yarn_option(ry, "energy_stall", ry_options.energy_stall);
    add_yarn_option(ry, "stop_scale", ry_stop_scale);
    add_yarn_option(ry, "jam_steps", ry_options.jam_steps);
    add_yarn_option(ry, "jam_drop", ry_options.jam_drop);
    add_yarn_option(ry, "max_move", ry_options.guard.max_move);
    add_yarn_option(ry, "contact_margin", ry_options.contact_margin);
    ry->add_option("--guard-depth", ry_options.guard.max_depth, "bounding-sphere levels of the guard (pieces of 1/2^depth of a segment)")->capture_default_str();
    add_yarn_option(ry, "take_up", ry_take_up);
    ry->add_option("--rest-lengths", ry_rest_lengths,
                   "a .bcc of the same yarn in another shape whose lengths (× --take-up) are the rest lengths, instead of the input's own "
                   "(e.g. a swatch relaxed flat, then bent: the bent one relaxes with the flat yarn's lengths)");
    ry->add_option("--take-up-stitch", ry_take_up_stitch, "TYPE=F scales the yarn of one stitch type (e.g. s=0.8), TYPE:vertical=F or TYPE:horizontal=F only its loop carried up or its row's yarn (s:vertical=0.5; Leaf 2018 §6.1)");
    ry->add_option("--yarn-radius", ry_radius, "yarn radius [mm] for a project (default: a tenth of the stitch width)")->check(positive());
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
    ry->add_flag("--active-set", ry_options.active_set.enabled,
                                    "converged points stop being integrated until their force grows or a neighbour moves (CPU only; the stop rule still sees every point)");
    const double wake_force = relax::ActiveSetOptions{}.wake_force;  // a sleeping point wakes above it: sleep below it
    ry->add_option("--sleep-force", ry_options.active_set.sleep_force,
                   "the active set's (--active-set, or a project's saved yarn.active_set): a point sleeps below this × ε1 |∇E_0| / √N (under the "
                   "wake force, " + std::to_string(static_cast<int>(wake_force)) + ")")
        ->check(number_check(false, [wake_force](double x) { return x > 0 && x < wake_force; }, "(0, " + std::to_string(static_cast<int>(wake_force)) + ")"))
        ->capture_default_str();
    ry->add_option("--wake-move", ry_options.active_set.wake_move, "the active set's: a sleeping point wakes when its neighbours moved this × r")
        ->check(positive())->capture_default_str();
    add_yarn_option(ry, "contact_spacing", ry_options.sampling.spacing);
    ry->add_option("--warm-start", ry_warm, "the relaxed yarn (.bcc) of --warm-project: start from it and relax only the stitches changed since, "
                                            "and --rings rings around them");
    ry->add_option("--warm-project", ry_warm_project, "with --warm-start: the project its yarn was emitted from, before the edits");
    add_yarn_option(ry, "rings", ry_local.rings, "with --warm-start: ");
    add_yarn_option(ry, "halo", ry_local.halo, "with --warm-start: ");
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
    ry->add_option("--stand-in-pattern", ry_stand_in_patterns,
                   "with --stand-in: a pattern tiled onto the garment that re-meshes (cables, lace, increases, decreases; patterns/FORMAT.md): "
                   "its whole repeats get a stand-in too (repeat the option for several)");
  }

  bool chosen() const override { return ry->parsed(); }

  int run(const Context& context) override {
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
    for (const char* flag : {"--sleep-force", "--wake-move"})
      if (ry->count(flag) > 0 && !ry_options.active_set.enabled)
        throw Error("", flag, "goes with the active set: give --active-set, or relax a project that saves yarn.active_set");
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
      const auto splice = [&] {
        try {
          return workflow::splice_previous(yarn, previous_emitted, previous);
        } catch (const Error&) {  // the one rule the splice checks, said with the files' names
          throw Error(ry_warm, "", "holds other curves than the yarn of " + ry_warm_project + " (curve or point counts differ): it was not relaxed from it");
        }
      }();
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
      const double energy = relax::relaxer_energy(system, targets, ry_options, points);
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
                                     {ry_in, ry_out, ry_backend, ry_report, ry_log, ry_png, ry_views, !context.quiet && isatty(fileno(stderr)),
                                      ry_extra, 900, own_colours(yarn), 1, ry_radius_out, {}, {}});
    if (run.stopped_by != relax::StopReason::Interrupted) write_ids(yarn);  // the relaxed yarn's points are the emitted ones, in order
    return exit_status(run.stopped_by);
  }
};

}  // namespace

std::unique_ptr<Subcommand> make_relax_yarn_command() { return std::make_unique<RelaxYarnCommand>(); }

}  // namespace skein::cli
