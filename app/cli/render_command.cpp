// skein render: draw a project's stitch mesh to PNG
#include "subcommand.hpp"

#include <memory>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "render/stitch_view.hpp"
#include "render/yarn_view.hpp"
#include "stitchmesh/project.hpp"

namespace skein::cli {
namespace {

struct RenderCommand final : Subcommand {
  CLI::App* render_cmd = nullptr;
  std::string render_in, render_out, render_color = "row";
  bool render_yarn = false;
  double render_radius = 0;
  std::string render_views = "garment";

  void declare(CLI::App& app) override {
    render_cmd = app.add_subcommand("render", "draw a project's stitch mesh to PNG");
    render_cmd->add_option("INPUT", render_in, ".skein project (its stitch mesh, or with --yarn its yarn) or .bcc yarn")->required();
    render_cmd->add_option("-o,--output", render_out, "PNG to write")->required();
    render_cmd->add_flag("--yarn", render_yarn, "draw the project's yarn as tubes instead of its stitch mesh");
    render_cmd->add_option("--yarn-radius", render_radius, "yarn radius [mm] for --yarn (default: a tenth of the stitch width)");
    render_cmd->add_option("--color", render_color, "row, type or colour (the yarn's colours, patterns/FORMAT.md) for stitch meshes; type, yarn or colour for yarn")
        ->check(CLI::IsMember({"row", "type", "yarn", "colour"}));
    render_cmd->add_option("--views", render_views, "garment (three-quarter front, back-side), flat (front, back) or three (front, back, three-quarter)")
        ->check(CLI::IsMember({"garment", "flat", "three"}));
  }

  bool chosen() const override { return render_cmd->parsed(); }

  int run(const Context&) override {
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
};

}  // namespace

std::unique_ptr<Subcommand> make_render_command() { return std::make_unique<RenderCommand>(); }

}  // namespace skein::cli
