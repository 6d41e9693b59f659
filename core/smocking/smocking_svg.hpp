#pragma once
// Smocking patterns drawn as SVG (issue 30, part 1): stitching lines on a grid, front stitches solid and back
// stitches dashed, as Zhou 2024 draws them (Fig. 4, 5), read into a SmockingPattern; and any pattern written
// back as .smock text.
#include <filesystem>
#include <string>

#include "smocking/smocking_pattern.hpp"

namespace skein::smocking {

struct SvgImport {
  Style style = Style::Italian;
  double grid = 0;      ///< grid spacing in the drawing's units; 0: the smallest step between stitch ends
  int margin = 1;       ///< grid squares of fabric around the stitches
  double spacing = 10;  ///< mm between grid points in the pattern
};

/// Reads the drawing's `line`, `polyline` and `path` elements (straight segments; group transforms applied):
/// each stitch end snapped to the grid; a `line` is one stitch, on the back when it has a `stroke-dasharray`,
/// and `line`s that meet end to start chain into one thread (Canadian: every line its own knot); a polyline or
/// path is one thread whose stitches alternate, its first on the back when it is dashed.
/// Throws skein::Error naming the file, the element and the rule (curves, points off the grid, a thread whose
/// stitches do not alternate sides, ...).
SmockingPattern read_smocking_svg(const std::filesystem::path& file, const SvgImport& import = {});
/// The same from the drawing's text; `file` names it in errors and the pattern.
SmockingPattern parse_smocking_svg(const std::string& text, const std::filesystem::path& file, const SvgImport& import = {});

/// The pattern as .smock text (docs/smocking.md) that reads back to the same grid and threads.
std::string smocking_text(const SmockingPattern& pattern);

}  // namespace skein::smocking
