// skein yarn: emit yarn curves from a stitch mesh (.bcc or OBJ polylines)
#include "subcommand.hpp"

#include <algorithm>
#include <memory>

#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "render/yarn_view.hpp"
#include "stitchmesh/project.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/yarn_io.hpp"

namespace skein::cli {
namespace {

struct YarnCommand final : Subcommand {
  CLI::App* yarn_cmd = nullptr;
  std::string yarn_in, yarn_out, yarn_tubes, yarn_png, yarn_color, stitches_dir;
  double yarn_radius = 0;
  std::string yarn_ids;
  std::string yarn_units = "mm";
  FabricChoice yarn_fabric;

  void declare(CLI::App& app) override {
    yarn_cmd = app.add_subcommand("yarn", "emit yarn curves from a stitch mesh (.bcc or OBJ polylines)");
    yarn_cmd->add_option("PROJECT", yarn_in, ".skein project with a stitch mesh")->required();
    yarn_cmd->add_option("-o,--output", yarn_out, "yarn to write: .bcc (Catmull-Rom curves) or .obj (polylines)")->required();
    yarn_cmd->add_option("--tubes", yarn_tubes, "also write a tube mesh with normals for any renderer: OBJ, or glTF 2.0 when it ends in .glb or .gltf (in metres, "
                                                "glTF's unit)");
    yarn_cmd->add_option("--ids", yarn_ids, "also write each control point's stitch face, row and type as CSV (docs/FORMATS.md), for outside checks");
    yarn_cmd->add_option("--units", yarn_units, "units of the OBJ outputs (polylines and --tubes): mm, cm or m (Blender reads OBJ as metres); .bcc stays in mm")
        ->check(CLI::IsMember({"mm", "cm", "m"}))->capture_default_str();
    yarn_cmd->add_option("--yarn-radius", yarn_radius, "yarn radius [mm] (default: a tenth of the stitch width)");
    add_fabric(yarn_cmd, yarn_fabric, "sets the yarn radius", false);
    yarn_cmd->add_option("--png", yarn_png, "picture of the yarn as shaded tubes");
    yarn_cmd->add_option("--color", yarn_color, "tube colour: type (stitch type), yarn (one per yarn) or colour (the yarn's own; the default when it has them, else type)")
        ->check(CLI::IsMember({"type", "yarn", "colour"}));
    yarn_cmd->add_option("--stitches", stitches_dir, "stitch library folder (default: the bundled stitches/)");
  }

  bool chosen() const override { return yarn_cmd->parsed(); }

  int run(const Context&) override {
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
};

}  // namespace

std::unique_ptr<Subcommand> make_yarn_command() { return std::make_unique<YarnCommand>(); }

}  // namespace skein::cli
