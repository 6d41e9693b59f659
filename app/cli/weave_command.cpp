// skein weave-exemplar, skein weave-volume: relax small woven patches and voxelize them as exemplars for weave-volume (Zhao 2012 §4, §6; docs/woven.md); synthesize the volumetric appearance of a woven design from exemplars and render it (Zhao 2012 §5; docs/woven.md)
#include "subcommand.hpp"

#include <cstdio>
#include <memory>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "weave.hpp"

namespace skein::cli {
namespace {

struct WeaveCommand final : Subcommand {
  CLI::App* wex = nullptr;
  CLI::App* wvol = nullptr;
  WeaveExemplarArgs wx;
  WeaveVolumeArgs wv;
  bool wv_fixed = false;

  void declare(CLI::App& app) override {
    wex = app.add_subcommand("weave-exemplar", "relax small woven patches and voxelize them as exemplars for weave-volume (Zhao 2012 §4, §6; docs/woven.md)");
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

    wvol = app.add_subcommand("weave-volume", "synthesize the volumetric appearance of a woven design from exemplars and render it (Zhao 2012 §5; docs/woven.md)");
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
    wvol->add_flag("--no-randomize", wv_fixed, "keep the dynamic program's blocks (no random shifts by the exemplars' symmetries)")
        ->each([&](const std::string&) { wv.synthesis.randomize = false; });
    wvol->add_option("--seed", wv.synthesis.seed, "random seed of the randomization")->capture_default_str();
    wvol->add_option("--width", wv.render.width, "picture width [pixels]")->capture_default_str()->transform(whole_in_range(8, 8192));
    wvol->add_option("--height", wv.render.height, "picture height [pixels]")->capture_default_str()->transform(whole_in_range(8, 8192));
    wvol->add_option("--samples", wv.render.samples, "paths per pixel")->capture_default_str()->transform(whole_in_range(1, 65536));
    wvol->add_option("--field", wv.render.field, "the picture's width on the fabric [mm] (default: the whole fabric)")->check(in_range(0.01, 1e6));
    wvol->add_option("--tilt", wv.render.tilt, "the view's angle from straight down [degrees]")->capture_default_str()->check(in_range(0.0, 80.0));
  }

  bool chosen() const override { return wex->parsed() || wvol->parsed(); }

  int run(const Context&) override {
    if (wex->parsed()) {
      weave_exemplar(wx);
      return 0;
    }
    if (!wv.pattern.empty() && !wv.picture.empty()) throw Error("", "weave-volume", "give a woven PATTERN or --picture, not both");
    weave_volume(wv);
    return 0;
  }
};

}  // namespace

std::unique_ptr<Subcommand> make_weave_command() { return std::make_unique<WeaveCommand>(); }

}  // namespace skein::cli
