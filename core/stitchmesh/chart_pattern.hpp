#pragma once
// Knitting charts as text (issue 26, part 2): a grid of symbols drawn as the fabric looks from the right side,
// the bottom line row 1, with the Craft Yarn Council's symbols as the default key and keys of the file's own.
// Read by turning each chart row into the written instructions a knitter reads off it (right-side rows right
// to left, wrong-side rows left to right with each symbol worked as its wrong-side stitch) and reading those
// with the written-instruction reader (written_pattern.hpp), so both notations mean the same stitches.
// patterns/FORMAT.md, "Charts", lists the symbols.
#include <string>

#include "stitchmesh/pattern.hpp"

namespace skein::mesh {

/// Whether `text` is a chart: its first line that is not blank or a `#` comment is `format chart` (worked
/// flat) or `format chart round` (in the round).
bool is_chart_pattern(const std::string& text);

/// Reads a chart into one repeat, rows bottom first, as seen from the front. Throws skein::Error naming
/// `source`, the chart's line and column and the rule broken: a symbol the key does not hold (naming the
/// key's symbols), a cable drawn over the wrong number of cells, a row number that is not the row's, and what
/// the written-instruction reader refuses in the row the chart makes (placed at the chart's cell).
Pattern parse_chart_pattern(const std::string& text, const std::string& source);

/// A knit pattern as chart text that parse_chart_pattern reads back as the same stitches: `format chart`
/// (flat) where its wrong-side rows can be read so, else `format chart round`; keys for cables and for the
/// symbols the default key lacks. Throws skein::Error naming the row and stitch of a stitch type no chart
/// symbol stands for yet (increases, twisted tops, ...), and for woven patterns.
std::string write_chart_pattern(const Pattern& pattern);

/// The same pattern as written instructions ("Row 1 (RS): k2, p2, C4B, p2."), runs of knits and purls
/// counted, that parse_written_pattern reads back as the same stitches; what write_chart_pattern refuses too.
std::string write_written_pattern(const Pattern& pattern);

}  // namespace skein::mesh
