#pragma once
#include <string>
#include <vector>

#include "relax/yarn_curves.hpp"
#include "render/raster.hpp"
#include "stitchmesh/pattern.hpp"

namespace skein::woven {

/// A weave pattern as Zhao 2012 §3 writes it: a binary image with one pixel per yarn crossing, rows the wefts
/// (bottom row first, along y) and columns the warps (along x); true where the warp lies on top. skein's
/// `format woven` text writes the opposite (1 = the weft over the warp): from_pattern turns it over.
struct Weave {
  int warps = 0, wefts = 0;
  std::vector<char> warp_up;  ///< wefts x warps, row by row

  bool at(int weft, int warp) const { return warp_up[static_cast<size_t>(weft) * warps + warp] != 0; }
  void set(int weft, int warp, bool up) { warp_up[static_cast<size_t>(weft) * warps + warp] = up; }
  bool operator==(const Weave&) const = default;
};

Weave make_weave(int warps, int wefts);
/// A woven pattern's repeat (skein's 1 = weft over warp, so warp_up = 1 - over).
Weave from_pattern(const mesh::Pattern& pattern);
/// The repeat tiled to warps x wefts crossings (the pattern's crossing (i mod h, j mod w)).
Weave tiled(const Weave& repeat, int warps, int wefts);
/// The weave's rows top row first, '#' where the warp is up, '.' where the weft is (for reports and errors).
std::string to_text(const Weave& weave);
/// Reads to_text's rows back; throws skein::Error naming `source` and the row for ragged rows or other characters.
Weave from_text(const std::string& text, const std::string& source);

/// Zhao §5.2: a design from a posterized picture. `labels` (width x height, top row first, as a picture is
/// read) gives each pixel's colour index; colour c is woven with elementary weave `weaves[map[c]]`, repeated
/// over the picture: W(x, y) = V_map(I(x, y))(x, y). The picture's bottom row becomes weft 0.
Weave weave_from_labels(const std::vector<int>& labels, int width, int height, const std::vector<Weave>& weaves, const std::vector<int>& map);
/// A posterized picture's labels for weave_from_labels: each pixel's colour index, colours numbered in the order
/// they first appear (top row first); `colours` gets their count.
std::vector<int> picture_labels(const render::Image& image, int& colours);

/// The weave of relaxed woven yarn, found from the yarn itself (Zhao §6.2, the crossing order): at each
/// crossing of warp j and weft i (where their projections onto the fabric plane meet), the warp is up when
/// its centreline lies above the weft's there. `warp_curves` and `weft_curves` list the curves in order.
/// Zhao uses the sign of the Gauss linking integral; for a single-layer weave that is the same test.
/// Throws skein::Error when a warp and a weft do not cross in projection.
Weave detect_weave(const relax::YarnCurves& yarn, const std::vector<int>& warp_curves, const std::vector<int>& weft_curves);

}  // namespace skein::woven
