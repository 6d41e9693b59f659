#pragma once
// A knit pattern drawn as a knitting chart (issue 26, part 2): one cell per stitch a row makes, the bottom row
// first, seen from the right side, in the Craft Yarn Council's symbols, so a designer sees what skein read
// from written instructions, a chart or skein's own format. patterns/FORMAT.md, "Charts", has the symbols.
#include "render/raster.hpp"
#include "stitchmesh/pattern.hpp"

namespace skein::render {

/// The repeat as a chart, `cell` pixels a cell: blank knit, a dot for purl, a ring for a yarn-over, / k2tog,
/// \ ssk, ^ a centred double decrease, V a slip, a small x a crossed knit, a cable as two strands crossing over its
/// cells (the front one whole), grey for a stitch with no symbol. Throws skein::Error for a woven pattern.
Image draw_chart(const mesh::Pattern& pattern, int cell = 40);

}  // namespace skein::render
