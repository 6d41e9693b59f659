#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "relax/yarn_curves.hpp"
#include "stitchmesh/colours.hpp"
#include "stitchmesh/stitch_mesh.hpp"
#include "stitchmesh/tessellation.hpp"

namespace skein::mesh {

/// A knitting or weaving pattern written as text (Yuksel 2012 §5.3, Leaf 2018 §4): one repeat, laid out as
/// the fabric looks (the last line is the first row). patterns/FORMAT.md describes the three formats.
enum class PatternFormat {
  Knit,   ///< stitch types of the stitch library, separated by spaces (Yuksel §5.3)
  Tiles,  ///< Leaf's knit tile codes K P F B (Leaf Table 2)
  Woven,  ///< 0/1 matrix: 1 = the weft (row) over the warp (column) (Leaf §4)
};

/// A cable in a knit pattern (Yuksel 2012 §4.5): on the knit stitches of its row whose new loops are
/// first_loop .. first_loop + over + under (counted along the row's top), the first `over` loops cross right over the next `under` ones (cableAxB), in front
/// (order +1) or behind (-1), on their way into the row above.
struct PatternCable {
  int row = 0, first_loop = 0, over = 1, under = 1, order = 1;
  bool operator==(const PatternCable&) const = default;
};

struct Pattern {
  std::string name;   ///< from "# name:", else the file's stem
  std::string note;   ///< from "# source:": where the pattern comes from
  PatternFormat format = PatternFormat::Knit;
  /// Knit and tile patterns: per row, bottom row first, the stitch types (tile codes already mapped).
  std::vector<std::vector<std::string>> rows;
  /// Knits: the cables, rows counted as in `rows`.
  std::vector<PatternCable> cables;
  /// Woven patterns: per weft row, bottom row first, per warp column: 1 when the weft lies over the warp.
  std::vector<std::vector<char>> over;
  /// Knits in colour (issue 26): the palette, and per row per stitch face (as `rows`, a cable's faces each) its
  /// index into it. Both empty for a pattern in one colour.
  std::vector<PatternColour> palette;
  std::vector<std::vector<int>> colours;
  /// Wovens in colour (WIF drafts): each weft row's and each warp column's index into the palette; empty for none.
  std::vector<int> weft_colours, warp_colours;
  /// A shaped piece (knits, issue 26): its rows are the whole fabric, knitted once and not repeated, each as wide
  /// as its stitches (a row takes the loops the row below made; the first row is the cast-on's).
  bool whole = false;
  /// Knits read from written instructions or a chart worked flat (right- and wrong-side rows); false in the round
  /// and for `.knit` files, which say only how the fabric looks from the front. Charts number the rows so.
  bool flat = false;

  int width() const;   ///< loops per row (knits) or warp yarns (wovens) in one repeat
  int height() const;  ///< rows or weft yarns in one repeat
  int stitches() const; ///< knits: faces in one repeat (pattern_stitch_mesh)
};

/// A knit's repeat `times` over up: its rows, cables and colours again above themselves (the same fabric, a taller repeat).
Pattern stacked(const Pattern& pattern, int times);

/// Knits: the loops a row of stitch types takes from the row below, and the loops it makes for the row above.
int loops_taken(const std::vector<std::string>& row);
int loops_made(const std::vector<std::string>& row);

/// Reads a pattern file; throws skein::Error naming the file, the line and column and the rule broken
/// (unknown token with the known names, ragged woven rows, rows whose loop counts do not connect, also
/// across the repeat, an empty pattern).
Pattern read_pattern(const std::filesystem::path& file);
/// The same from text; `source` names it in errors.
Pattern parse_pattern(const std::string& text, const std::string& source);

/// Throws skein::Error unless every knit row takes the loops the row below it makes, and the first row the
/// loops the last row makes (the repeat stacks); `row_line[r]` is the line of rows[r] in `source`.
void check_stacking(const Pattern& pattern, const std::vector<int>& row_line, const std::string& source);

/// A flat stitch mesh in the z = 0 plane of a knit pattern repeated `across` times along the course and
/// `up` times along the wale, stitches `size` apart; row 1 at y = 0. Cables become cable marks on the course
/// edges above their stitches (none in the top row: nothing is above it). Valid by construction.
StitchMesh pattern_stitch_mesh(const Pattern& pattern, int across, int up, const StitchSize& size = {});

/// Colours woven yarn made by woven_yarn(pattern, across, up) (wefts first, then warps) by the pattern's weft and warp
/// colours; does nothing for a pattern in one colour.
void colour_woven_yarn(relax::YarnCurves& yarn, const Pattern& pattern, int across, int up);

/// Whether tiling the knit pattern re-meshes the stitches it covers (its rows have increases, decreases or
/// lace, or it has cables) instead of repainting plain stitches (tile_pattern).
bool remeshes(const Pattern& pattern);

/// A repeat's faces are numbered as pattern_stitch_mesh(pattern, 1, 1) makes them: rows bottom-up, each row's
/// stitches left to right. The face of pattern_stitch_mesh(pattern, across, up) that is face `place` of the
/// repeat `column` along the course and `level` up the wale.
int repeat_face(const Pattern& pattern, int across, int column, int level, int place);

/// Tiles a knit pattern over `faces` of a stitch mesh (Yuksel 2012 §5.3); the stitch `origin` takes the
/// pattern's first stitch of its first row.
/// - Patterns of plain stitches (one loop below, one above) and no cables: every other chosen plain stitch
///   takes the pattern's stitch at its row and column from there (stitch_grid), modulo the repeat, so the
///   repeat may be cut anywhere. Chosen faces of another shape keep their type.
/// - Patterns with increases, decreases, lace or cables re-mesh: every whole repeat of W x H chosen plain
///   stitches on the lattice from the origin is removed and the pattern's faces generated in its place; the
///   repeat's border keeps its vertices, the course lines inside it get the pattern's loop counts, spread
///   evenly. Stitches outside whole repeats keep their type. Face ids change (kept faces first, in order).
/// Throws skein::Error when the origin or a face does not exist, the pattern is woven, or no repeat fits.
/// The result is valid when the input is.
struct TileReport {
  int stitches = 0;  ///< chosen stitches the pattern changed or replaced
  int repeats = 0;   ///< whole repeats re-meshed (0 for plain patterns)
};
StitchMesh tile_pattern(const StitchMesh& mesh, const std::vector<int>& faces, const Pattern& pattern, int origin, TileReport* report = nullptr);

/// Woven yarn of a woven pattern repeated `across` × `up` times: straight weft yarns along x and warp yarns
/// along y, `spacing` apart, passing over and under each other by one yarn radius at every crossing.
relax::YarnCurves woven_yarn(const Pattern& pattern, int across, int up, double spacing, double radius);

}  // namespace skein::mesh
