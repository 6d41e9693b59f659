#pragma once
// Smocking pictures (issue 30): the pattern on its grid and where the 2-D embedding put it, in Zhou 2024's
// colours (Fig. 5): stitching points orange, front stitches and their midpoints green, back ones purple, pleat
// points grey, beads as blue rings; and the threads' shortening over the iterations (Fig. 17).
#include "render/raster.hpp"
#include "smocking/smocking_cloth.hpp"
#include "smocking/smocking_embed.hpp"

namespace skein::render {

/// Panels side by side at one scale: the pattern as drawn, each snapshot of the embedding (largest fraction
/// first), and the embedding where the run ended; `pixels` a panel.
Image draw_smocking(const smocking::SmockingPattern& pattern, const smocking::Embedding& embedding, int pixels = 700);

/// D(X)/D(X̄) against the iterations, with the goal γ as a dashed line; `pixels` wide.
Image draw_shrinkage_chart(const smocking::Embedding& embedding, double gamma, int pixels = 700);

/// The smocked fabric in 3-D (smock_cloth) from the front and at a slant from the side (the pleats' depth), in a
/// light cloth colour; `pixels` a panel.
Image draw_smocked_fabric(const smocking::Cloth& cloth, int pixels = 900);

}  // namespace skein::render
