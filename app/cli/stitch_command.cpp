// skein stitch: label a mesh and tessellate it into a stitch mesh (.skein)
#include "subcommand.hpp"

#include <cstdio>
#include <memory>
#include <optional>

#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "render/stitch_view.hpp"
#include "stitchmesh/knit_field.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/project.hpp"
#include "stitchmesh/tessellation.hpp"

namespace skein::cli {
namespace {

struct StitchCommand final : Subcommand {
  CLI::App* stitch = nullptr;
  std::string stitch_in, stitch_out, stitch_labels, stitch_png, stitch_png_types, stitch_stats;
  bool auto_label = false;
  int start_edge = -1;
  mesh::StitchSize size;
  bool height_given = false;
  bool trace_field = false, stitch_repair = false;
  std::vector<double> start_point;
  int end_edge = -1;
  std::vector<double> end_point;
  FabricChoice stitch_fabric;
  double max_stitches = mesh::kDefaultMaxStitches;

  void declare(CLI::App& app) override {
    stitch = app.add_subcommand("stitch", "label a mesh and tessellate it into a stitch mesh (.skein)");
    stitch->add_option("MESH", stitch_in, "mesh (OBJ, PLY, glTF, FBX, ... or a .skein project)")->required();
    auto* auto_opt = stitch->add_flag("--auto-label", auto_label, "label every row automatically from the lowest border edge");
    auto* labels_opt = stitch->add_option("--labels", stitch_labels, "use the labels stored in this .skein file");
    stitch->add_flag("--repair", stitch_repair, "mend the mesh first where CGAL can (duplicate points and faces, degenerate faces, orientation, bow ties) and say what changed");
    auto* field_opt = stitch->add_flag("--field", trace_field,
                                       "trace rows on any surface (triangles, poles, closed) as isolines of the knitting distance from the start (docs/stitch-a-garment.md)");
    auto_opt->excludes(labels_opt);
    field_opt->excludes(auto_opt)->excludes(labels_opt);
    auto* start_edge_opt = stitch->add_option("--start-edge", start_edge, "with --auto-label or --field: the border edge to start from (default: the lowest)");
    stitch->add_option("--start-point", start_point, "with --field: knit in the round outwards from the surface point nearest X,Y,Z")
        ->expected(3)->delimiter(',')->needs(field_opt)->excludes(start_edge_opt);
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
    stitch->add_option("--max-stitches", max_stitches, "refuse a mesh that would make more stitches than this (its area over the stitch's)")
        ->check(positive())->capture_default_str();
    add_fabric(stitch, stitch_fabric, "without --gauge, sets the stitch size of its standard gauge", true);
  }

  bool chosen() const override { return stitch->parsed(); }

  int run(const Context&) override {
    height_given = stitch->count("--stitch-height") > 0;
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
};

}  // namespace

std::unique_ptr<Subcommand> make_stitch_command() { return std::make_unique<StitchCommand>(); }

}  // namespace skein::cli
