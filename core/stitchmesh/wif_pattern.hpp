#pragma once
// Weaving drafts in WIF, the Weaving Information File (issue 26): the INI-style format that weaving programs
// (Fiberworks, WeaveIt, iWeaveIt, ArahWeave, Pixeloom, ...) write and handweaving archives publish, version 1.1
// (Nielsen et al., "WIF: Weaving Information File", 1997). skein reads the structure of a draft: the threading
// (warp thread -> shafts), and either the tie-up (treadle -> shafts) with the treadling (pick -> treadles) or a
// lift plan (pick -> shafts), and weaves them into the drawdown: on pick p, warp thread t is raised when one of
// its shafts is lifted (rising shed; a sinking shed's tie-up names the shafts that sink). Colours, yarn sizes
// and spacing are not read. patterns/FORMAT.md, "WIF drafts", says how the drawdown becomes a woven repeat.
#include <string>

#include "stitchmesh/pattern.hpp"

namespace skein::mesh {

/// Whether `text` is a WIF file: its first line that is not blank or a `;` comment is `[WIF]`.
bool is_wif_pattern(const std::string& text);

/// Reads a WIF draft into a woven pattern: the drawdown (pick 1 the bottom row, warp thread 1 the left column,
/// seen from the face) reduced to its smallest repeat across and up. Throws skein::Error naming `source`, the
/// line (or the section) and the rule broken: a missing [THREADING], neither a tie-up with a treadling nor a
/// lift plan, an entry that is not `N=...` with N from 1 to the threads (picks, treadles) and shafts from 1 to
/// [WEAVING] Shafts, more than 10,000 threads or picks or 4,000,000 cells, and a repeat over 256 threads or picks.
Pattern parse_wif_pattern(const std::string& text, const std::string& source);

}  // namespace skein::mesh
