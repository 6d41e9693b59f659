// skein pattern: a knitting or weaving pattern written as text, tiled and optionally relaxed (Yuksel 2012 §5.3, Leaf 2018 §4)
#include "subcommand.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "relax/yarn_relax.hpp"
#include "render/chart_view.hpp"
#include "render/stitch_view.hpp"
#include "render/yarn_view.hpp"
#include "stitchmesh/chart_pattern.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/project.hpp"
#include "stitchmesh/tessellation.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/yarn_io.hpp"
#include "workflow/yarn_periodic.hpp"
#include "workflow/yarn_shape.hpp"

using nlohmann::json;

namespace skein::cli {
namespace {

struct PatternCommand final : Subcommand {
  CLI::App* pat = nullptr;
  std::string pat_in, pat_out, pat_tile = "4x4", pat_report, pat_png, pat_log, pat_stitches, pat_backend = "auto";
  mesh::StitchSize pat_size;
  double pat_radius = 0, pat_take_up = 1;
  bool pat_relax = false;
  relax::YarnRelaxOptions pat_options;
  std::string pat_preview, pat_preview_png;
  bool pat_tiled = false;
  std::string pat_tubes;
  std::string pat_ids, pat_chart_png;
  std::string pat_write_chart, pat_write_instructions;
  FabricChoice pat_fabric;
  std::vector<std::string> pat_take_up_stitch;
  std::string pat_period;
  double pat_gamma = 1;
  std::string pat_method = "lbfgs";
  std::string pat_stop_rule = "force";
  std::string pat_free_axes;
  std::string pat_period_method = "frame";
  std::string pat_views = "flat";
  int pat_panel = 900;
  std::string pat_onto, pat_rows;
  int pat_face = 0;
  bool pat_no_audit = false;

  void declare(CLI::App& app) override {
    pat = app.add_subcommand("pattern", "a knitting or weaving pattern written as text, tiled and optionally relaxed (Yuksel 2012 §5.3, Leaf 2018 §4)");
    pat->add_option("FILE", pat_in, "pattern text (patterns/FORMAT.md): format knit, tiles or woven, written instructions, a chart or a WIF weaving draft")->required();
    pat->add_option("-o,--output", pat_out, "yarn to write (.bcc or .obj polylines); not needed when only --chart-png, --write-chart or --write-instructions is asked");
    pat->add_option("--tile", pat_tile, "repeats across x up (NxM) of the emitted yarn, of --relax --tiled, or of --preview (the periodic patch has its own)")
        ->capture_default_str();
    pat->add_option("--preview", pat_preview, "with --relax: the relaxed repeat tiled NxM (--tile) as yarn (.bcc or .obj), a preview of the fabric");
    pat->add_option("--preview-png", pat_preview_png, "with --relax: picture of the --tile NxM preview, front and back");
    pat->add_flag("--relax", pat_relax, "relax the pattern's periodic patch (Leaf 2018 §5; FIRE, pull-through guard) and write it");
    pat->add_flag("--tiled", pat_tiled, "with --relax: relax the NxM tiling with free borders instead of the periodic patch");
    pat->add_option("--report", pat_report, "JSON report: the pattern and its yarn; with --relax the same report as relax-yarn");
    pat->add_option("--png", pat_png, "picture of the yarn, front and back");
    pat->add_option("--tubes", pat_tubes, "also write the yarn (relaxed with --relax) as tubes for any renderer: OBJ in mm, or glTF 2.0 (.glb, .gltf) in metres; "
                                          "a pattern in colours gets a material per colour");
    pat->add_option("--chart-png", pat_chart_png, "the repeat drawn as a knitting chart in the Craft Yarn Council's symbols (patterns/FORMAT.md), as skein "
                                                  "read it; knits and tiles");
    pat->add_option("--write-chart", pat_write_chart, "the repeat as chart text (format chart: the Craft Yarn Council's symbols, patterns/FORMAT.md) that "
                                                      "skein reads back as the same stitches; knits and tiles; - for standard output");
    pat->add_option("--write-instructions", pat_write_instructions, "the repeat as written instructions (\"Row 1 (RS): k2, p2.\") that skein reads back "
                                                                    "as the same stitches; knits and tiles; - for standard output");
    pat->add_option("--ids", pat_ids, "also write each control point's stitch face, row and type as CSV (docs/FORMATS.md): knits and tiles, "
                                      "emitted or relaxed --tiled");
    pat->add_option("--log", pat_log, "with --relax: per-step CSV log as relax-yarn writes it");
    pat->add_option("--stitch-size", pat_size.width, "knits: stitch width [mm]; wovens: yarn spacing is 4 yarn radii")->capture_default_str();
    pat->add_option("--stitch-height", pat_size.height, "knits: stitch height [mm]")->capture_default_str();
    pat->add_option("--yarn-radius", pat_radius, "yarn radius [mm] (default: a tenth of the stitch width)")->check(positive());
    add_fabric(pat, pat_fabric, "sets the yarn radius and, without --gauge, the stitch size of its standard gauge", true);
    add_yarn_option(pat, "take_up", pat_take_up, "with --relax: ");
    pat->add_option("--take-up-stitch", pat_take_up_stitch, "with --relax: TYPE=F scales the yarn of one stitch type (s=0.8), TYPE:vertical=F or TYPE:horizontal=F only its loop carried up or its row's yarn (s:vertical=0.5), or weft=F, warp=F (Leaf 2018 §6.1)");
    pat->add_option("--period", pat_period, "with --relax: the repeat's period x its emitted size, along the course x the wale (e.g. 0.9x1)");
    pat->add_option("--gamma", pat_gamma, "with --relax: relax at gamma x the yarn radius and scale back by 1/gamma: 1/gamma of the yarn length (Leaf 2018 §6.2)")
        ->check(in_range(relax::kMinGamma, relax::kMaxGamma))->capture_default_str();
    pat->add_option("--stitches", pat_stitches, "stitch library folder (default: the bundled stitches/)");
    pat->add_option("--backend", pat_backend, "with --relax: auto, cpu or cuda")->check(CLI::IsMember({"auto", "cpu", "cuda"}))->capture_default_str();
    add_yarn_option(pat, "max_steps", pat_options.max_steps, "with --relax: ");
    add_yarn_option(pat, "max_seconds", pat_options.max_seconds, "with --relax: ");
    add_yarn_option(pat, "tolerance", pat_options.tolerance, "with --relax: ");
    add_yarn_option(pat, "method", pat_method, "with --relax: ");
    add_yarn_option(pat, "stop_rule", pat_stop_rule, "with --relax: ");
    add_yarn_option(pat, "force_tolerance", pat_options.force_tolerance);
    add_yarn_option(pat, "stall_window", pat_options.stall_window);
    add_yarn_option(pat, "energy_stall", pat_options.energy_stall);
    pat->add_option("--free-period", pat_free_axes,
                    "with --relax: the repeat's period relaxes too, to zero mean stress (variable-cell): the pattern's own gauge, in the report; "
                    "x (no value: the width, the rows held at the height of the gauge), y or xy (frictionless yarn's rows may slide apart: "
                    "docs/patterns.md)")
        ->expected(0, 1)->default_str("x")->check(CLI::IsMember({"xy", "x", "y"}));
    pat->add_option("--period-tolerance", pat_options.period.tolerance, "with --free-period: the largest stress left, × B/r³")->capture_default_str();
    pat->add_option("--period-method", pat_period_method,
                    "with --free-period: frame (the period relaxes with the points) or bracket (one free length: the repeat relaxed at "
                    "fixed widths until the stress-free one is bracketed; converges under tension, docs/patterns.md)")
        ->check(CLI::IsMember({"frame", "bracket"}))
        ->capture_default_str();
    add_yarn_option(pat, "k_bend", pat_options.params.k_bend, "with --relax: ");
    add_yarn_option(pat, "k_contact", pat_options.params.k_contact, "with --relax: ");
    add_yarn_option(pat, "k_stretch", pat_options.params.k_stretch, "with --relax: ");
    pat->add_flag("--shear", pat_options.period.shear, "with --free-period: the repeat may shear too (a diagonal pattern); without it only its two lengths relax");
    add_yarn_option(pat, "contact_spacing", pat_options.sampling.spacing, "with --relax: ");
    pat->add_option("--views", pat_views, "flat (front and back), front, or three (front, back, three-quarter), for --png and --preview-png")
        ->check(CLI::IsMember({"flat", "front", "three"}))->capture_default_str();
    pat->add_option("--png-size", pat_panel, "pixels per view of --png")->transform(whole_in_range(64, 4096))->capture_default_str();
    auto* onto_opt = pat->add_option("--onto", pat_onto, "tile the pattern onto this project's stitch mesh instead (-o writes the project)");
    pat->add_option("--face", pat_face, "with --onto: the stitch that takes the pattern's first stitch")->needs(onto_opt)->capture_default_str();
    pat->add_option("--rows", pat_rows, "with --onto: the rows A:B the pattern covers (default: all)")->needs(onto_opt);
    pat->add_flag("--no-audit", pat_no_audit, "with --relax: skip the per-step topology audit");
  }

  bool chosen() const override { return pat->parsed(); }

  int run(const Context& context) override {
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
      if (!pat_write_chart.empty() && pat_write_chart != "-") check_writable(pat_write_chart);
      if (!pat_write_chart.empty()) chart_text = mesh::write_chart_pattern(pattern);
      if (!pat_write_instructions.empty() && pat_write_instructions != "-") check_writable(pat_write_instructions);
      if (!pat_write_instructions.empty()) instructions = mesh::write_written_pattern(pattern);
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
        if (written.first == "-") {
          std::cout << written.second << std::flush;  // to read or pipe at once: "skein pattern P.txt --write-chart -"
          continue;
        }
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
    std::array<int, 2> repeat{pattern.width(), pattern.height()};  // the relaxed repeat's stitches (the patch's: PeriodicPatch::repeat)
    if (pat_relax && !pat_tiled) {
      auto patch = pattern.format == mesh::PatternFormat::Woven ? workflow::periodic_woven_patch(pattern, 4 * radius, sim_radius)
                                                                : workflow::periodic_patch(pattern, library, pat_size, sim_radius);
      if (preview) patch_kept = patch;
      repeat = patch.repeat;
      spdlog::info("periodic patch: {} x {} repeats, {} real, {} virtual and {} frozen control points", patch.tiles, patch.tiles,
                   std::count(patch.ring.begin(), patch.ring.end(), 0), patch.map.virtual_points.size(), patch.map.frozen.size());
      pat_extra = {{"pattern", pattern.name},
                   {"periodic", {{"tiles", patch.tiles}, {"repeat", patch.repeat}, {"real_points", std::count(patch.ring.begin(), patch.ring.end(), 0)},
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
      pat_options.interrupt = install_interrupt_handlers();  // Ctrl-C stops the run after its step (and a sweep's case)
      pat_options.stop_rule = relax::parse_stop_rule(pat_stop_rule);
      pat_options.method = relax::parse_yarn_method(pat_method);
      pat_options.period.free = pat->count("--free-period") > 0;
      pat_options.period.free_x = pat_free_axes != "y";
      pat_options.period.free_y = pat_free_axes == "y" || pat_free_axes == "xy";
      pat_options.period.method = pat_period_method == "bracket" ? relax::PeriodOptions::Method::Bracket : relax::PeriodOptions::Method::Frame;
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
          const double loop = relax::patch_loop_length(system, targets.periodic, repeat) / pat_gamma;
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
                                        !context.quiet && isatty(fileno(stderr)), pat_extra, pat_panel, color, 1 / pat_gamma,
                                        compressed ? radius : 0.0, repeat, pat_tubes});
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
};

}  // namespace

std::unique_ptr<Subcommand> make_pattern_command() { return std::make_unique<PatternCommand>(); }

}  // namespace skein::cli
