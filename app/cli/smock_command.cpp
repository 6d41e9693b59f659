// skein smock: gather a smocking pattern by its threads: Italian, Canadian or English smocking (Zhou 2024 §4.1; docs/smocking.md)
#include "subcommand.hpp"

#include <cstdio>
#include <memory>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "smock.hpp"

namespace skein::cli {
namespace {

struct SmockCommand final : Subcommand {
  CLI::App* smock = nullptr;
  SmockArgs sm;
  bool smock_raw = false;

  void declare(CLI::App& app) override {
    smock = app.add_subcommand("smock", "gather a smocking pattern by its threads: Italian, Canadian or English smocking (Zhou 2024 §4.1; docs/smocking.md)");
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
    smock->add_option("--subdivisions", sm.cloth_options.subdivisions, "with --cloth or --cloth-png: fine squares per side of a pattern square (even)")->capture_default_str();
    smock->add_option("--frames", sm.cloth_options.frames, "with --cloth or --cloth-png: frames at most (the paper's 100; a run ends sooner when a frame no longer moves)")
        ->capture_default_str()->transform(whole_in_range(1, 100000));
    smock->add_option("--gamma", sm.gamma, "pull the threads to this fraction of their sewn length (default: the pattern's gamma line)")->check(in_range(1e-6, 1.0));
    smock->add_option("--thickness", sm.options.thickness, "fabric thickness [mm] (default: 1 % of the grid's longer side, the paper's setting)")
        ->check(in_range(1e-6, 1e4));
    smock->add_option("--pull", sm.pull, "pulling direction X,Y, or \"along\": each stitch pulled along itself (the paper's CURVE pattern)")->capture_default_str();
    smock->add_option("--snapshots", sm.options.snapshots, "also keep and draw the fabric when the threads first reach these fractions, e.g. 0.8,0.6,0.4")
        ->delimiter(',')->check(in_range(1e-6, 1.0));
    smock->add_flag("--no-settle", smock_raw, "leave the pleat points where Algorithm 1 stops (the paper's output; the fabric may be stretched there)")
        ->each([&](const std::string&) { sm.options.settle = false; });
    smock->add_option("--max-iterations", sm.options.max_iterations, "stop after this many iterations")->capture_default_str()->transform(whole_in_range(0, 1000000000));
  }

  bool chosen() const override { return smock->parsed(); }

  int run(const Context&) override { return run_smock(sm); }
};

}  // namespace

std::unique_ptr<Subcommand> make_smock_command() { return std::make_unique<SmockCommand>(); }

}  // namespace skein::cli
