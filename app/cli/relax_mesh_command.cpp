// skein relax-mesh: relax a stitch mesh on the limit surface of its input mesh (Yuksel 2012 §6.1)
#include "subcommand.hpp"

#include <memory>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "render/stitch_view.hpp"
#include "stitchmesh/project.hpp"
#include "surface/mesh_relax.hpp"

using nlohmann::json;

namespace skein::cli {
namespace {

struct RelaxMeshCommand final : Subcommand {
  CLI::App* relax_cmd = nullptr;
  std::string relax_in, relax_out, relax_png, relax_png_before, relax_ply, relax_report;
  surface::MeshRelaxOptions relax_options;

  void declare(CLI::App& app) override {
    relax_cmd = app.add_subcommand("relax-mesh", "relax a stitch mesh on the limit surface of its input mesh (Yuksel 2012 §6.1)");
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
  }

  bool chosen() const override { return relax_cmd->parsed(); }

  int run(const Context&) override {
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
};

}  // namespace

std::unique_ptr<Subcommand> make_relax_mesh_command() { return std::make_unique<RelaxMeshCommand>(); }

}  // namespace skein::cli
