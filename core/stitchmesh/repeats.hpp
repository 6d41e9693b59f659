#pragma once
#include <string>
#include <vector>

#include "stitchmesh/pattern.hpp"
#include "stitchmesh/stitch_mesh.hpp"

namespace skein::mesh {

/// The repeating patterns a stitch mesh is knitted in, read back from its stitch types: the inverse of tiling a
/// pattern (Yuksel 2012 §5.3), for the periodic stand-ins of issue 10 (Leaf 2018 §5 relaxes one repeat).
/// Only plain stitches (one loop below, one above) on a regular grid take part; stitches on a cable mark,
/// increases, decreases and the stitches around them are in no repeat (find_tiled_repeats finds the repeats of
/// named patterns that have them).
struct RepeatRegions {
  /// Each repeat a knit pattern of plain stitch types, rows bottom-up as in Pattern: its smallest rectangular
  /// repeat (every pattern of the integer grid has one), started at the phase whose rows, read bottom-up and
  /// left to right, come first in string order, so that the same pattern found anywhere is the same repeat.
  std::vector<Pattern> repeats;
  std::vector<int> repeat;       ///< per face: its repeat, -1 for none
  std::vector<int> column, row;  ///< per face of a repeat: its stitch there, repeats[repeat[f]].rows[row[f]][column[f]]
  int faces_of(int r) const;     ///< faces in repeat r
};

/// Finds the repeats. A stitch starts a region when, from it, the stitch types repeat with the pattern's
/// period over a period and at least two stitches each way (no smaller period does; periods up to
/// `max_period` stitches along the row and along the wale, smallest area first). The region then grows stitch
/// by stitch along rows and wales to every stitch whose 3 x 3 neighbourhood of stitches is a regular grid with
/// the pattern's types around that stitch's place in the repeat, unless the stitch starts another pattern's
/// region itself; so a region reaches up to one stitch from another pattern or a border. Then, one ring at a
/// time for `reach` rings, plain stitches next to a region join it where their own type is the pattern's at
/// their place (the stitches along borders, seams and the edge of another pattern). Throws skein::Error when max_period
/// is outside 1..16 or reach is negative.
RepeatRegions find_repeats(const StitchMesh& mesh, int max_period = 8, int reach = 0);

/// The repeats of patterns tiled by re-meshing (tile_pattern: patterns with increases, decreases, lace or
/// cables), which find_repeats cannot read back from stitch types alone: each is found as a set of faces that
/// is one repeat of the pattern's stitch mesh face for face (pattern_stitch_mesh): the same stitch types and
/// shapes, joined across the same edges, with the same cable marks on their edges.
struct TiledRepeats {
  std::vector<Pattern> patterns;  ///< the patterns looked for that re-mesh, in the order given
  std::vector<int> pattern;       ///< per face: its pattern, -1 for none
  std::vector<int> place;         ///< per face of a repeat: its face in the repeat (repeat_face's numbering)
  std::vector<int> repeats;       ///< per pattern: whole repeats found
};

/// Finds the repeats of `patterns` (knit or tile patterns; those that do not re-mesh are skipped, find_repeats
/// reads them back). A repeat is matched from one of its faces outwards; no face belongs to two repeats, the
/// earlier pattern first. Throws skein::Error for a woven pattern.
TiledRepeats find_tiled_repeats(const StitchMesh& mesh, const std::vector<Pattern>& patterns);

/// A repeat as one line: its rows top row first, as a pattern file shows them, separated by " / ".
std::string repeat_text(const Pattern& repeat);

}  // namespace skein::mesh
