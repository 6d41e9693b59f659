#pragma once
// Knitting patterns as stitch dictionaries and yarn companies write them (issue 26, part 1): "Row 1 (RS): *k2,
// p2; rep from * to end." Read into the same Pattern as skein's own `format knit` (pattern.hpp), so that every
// command takes them. patterns/FORMAT.md, "Written instructions", lists what is understood.
#include <string>

#include "stitchmesh/pattern.hpp"

namespace skein::mesh {

/// Whether `text` is written instructions: its first line that is not blank or a `#` comment and not a
/// `format` line starts a row ("Row 1", "Rows 1 and 2", "Rnd 1", "Round 1") or is `format written`, or a row
/// line comes before any `format` line.
bool is_written_pattern(const std::string& text);

/// Reads written instructions into one repeat: rows bottom (Row 1) first, each as seen from the front.
/// - `Row N (RS):` / `Row N (WS):` (worked flat: odd rows RS unless marked) and `Rnd N:` (in the round, every
///   round from the right side); `Rows N and M:` / `Rows N-M:` for the same instructions on several rows;
///   `Rep Rows A-B.` (or `Rep Row A.`) as a row's instructions; rows numbered from 1 without gaps.
/// - Stitches, with counts (`k2`, `p3`): k p, k1tbl (a crossed knit, `x`), yo, k2tog ssk p2tog ssp,
///   sl1 wyib / sl1 wyif (knitwise or purlwise), cables C4F C4B C6F C6B, 2/2 LC, 2/2 RC, 1/1 LT, 1/1 RT;
///   `knit`, `purl`, `k to end`, `p to end` fill the repeat's width.
/// - Repeats: `*...; rep from * to end` (or `across`, or `to last N sts`) takes the starred part as the
///   repeat and leaves out the edge stitches around it; `[...] N times`, `(...) N times`, `[...] xN`.
/// - Right-side rows are read right to left and wrong-side rows left to right, with each stitch as it looks
///   from the front (a WS knit is a purl from the front), so the rows are laid out as the fabric looks.
/// Rows of different repeat widths are widened to their least common multiple. Throws skein::Error naming
/// `source`, the line and column and the rule broken; an unknown abbreviation names the closest known ones.
Pattern parse_written_pattern(const std::string& text, const std::string& source);

}  // namespace skein::mesh
