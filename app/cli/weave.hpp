#pragma once
// skein weave-exemplar and skein weave-volume: woven appearance from structure (Zhao 2012, issue 29).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "woven/exemplar.hpp"
#include "woven/synthesis.hpp"
#include "woven/woven_render.hpp"

namespace skein::cli {

struct WeaveExemplarArgs {
  std::vector<std::string> patterns;  ///< woven patterns (.weave or .wif)
  std::string output;                 ///< folder for the .vdb files
  std::string report;                 ///< a JSON report
  woven::ExemplarOptions options;
};
nlohmann::json weave_exemplar(const WeaveExemplarArgs& args);

struct WeaveVolumeArgs {
  std::string pattern;                ///< the design: a woven pattern (.weave or .wif), tiled to `size`
  std::string picture;                ///< or a posterized picture (PNG), each colour woven with one of `weaves`
  std::vector<std::string> weaves;    ///< the elementary weaves of the picture's colours, in the order the colours first appear
  std::string exemplars;              ///< folder of .vdb exemplars; empty: the bundled set, made on the fly
  std::string size;                   ///< WxH crossings; empty: the pattern's repeat tiled to about 48 x 48, or the picture's size
  std::string output;                 ///< a region of the synthesized volume as .vdb
  std::string region;                 ///< X,Y,W,H crossings of it; empty: everything up to 16 x 16 crossings, else the centre 16 x 16
  std::string png, report, assignment;
  std::string warp_colors = "#2a3a7a", weft_colors = "#d8cfb0";  ///< colours cycled over the warps and the wefts
  int edge_rank = 15;                 ///< 0: no edge fixing
  bool compare_truth = false;         ///< relax the design directly too and measure the synthesized volume against it
  woven::SynthesisOptions synthesis;
  woven::WovenRenderOptions render;
};
nlohmann::json weave_volume(const WeaveVolumeArgs& args);

/// The bundled exemplar set (patterns/ plain weave, 3/2 and 4/1 twill, 5-end satin and 2x2 basket), made with `options`.
std::vector<woven::Exemplar> bundled_exemplars(const woven::ExemplarOptions& options);

}  // namespace skein::cli
