#pragma once
// Yarn colours as pattern designers give them (issue 26, part 3): a palette of named colours ("MC: cream",
// "colour B: navy #1f2a44") and a colour per stitch. The colours travel from the pattern to the stitch faces
// and on to the yarn's control points, the pictures and the OBJ and glTF materials.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "relax/yarn_curves.hpp"

namespace skein::mesh {

/// One colour of a pattern's palette.
struct PatternColour {
  std::string name;             ///< as the pattern names it, in its case: "A", "MC", "CC1"
  std::string description;      ///< what the designer wrote after it, without the hex code: "cream", "Navy"
  std::array<double, 3> srgb{};  ///< 0..1
  std::string alias;            ///< a second name given in brackets ("Colour A (MC): ..."), or empty
  bool operator==(const PatternColour&) const = default;
};

/// A colour declaration line, as knitting patterns write them: `NAME: DESCRIPTION` or `NAME = DESCRIPTION`,
/// with `colour`, `color` or `yarn` before NAME (`colour A: cream #f3ead8`), a second name in brackets after it
/// (`Colour A (MC): natural`); with `prefix_optional` (written instructions) the usual names alone too: `MC`,
/// `CC`, `CC1` to `CC9` and one letter.
/// The colour is the description's `#rrggbb` (or a word of six hex digits) when it has one, else the first colour
/// word it holds (white, cream, natural, grey, black, red, navy, ...), else the `index`-th colour of a default
/// palette. Returns nothing when `line` is no declaration; throws skein::Error (naming `source` and `where`) for a
/// declaration that breaks a rule: a name that is a stitch (k, p, y, ...) or longer than 8 characters, a `#` code
/// that is not six hex digits.
std::optional<PatternColour> read_colour_declaration(const std::string& line, bool prefix_optional, int index, const std::string& source,
                                                     const std::string& where);

/// Where a line's `#` comment starts (npos for none): at its first `#` not followed straight by a letter or digit
/// (a colour code, which read_colour_declaration checks), so that `colour A: cream #f0e6cf  # the main colour` keeps
/// its code and `#e9dcg3` is an error, not a comment.
size_t comment_start(const std::string& line);

/// Throws skein::Error (naming `source` and `where`) when `c`'s name or alias is already one of `palette`'s.
void check_new_colour(const std::vector<PatternColour>& palette, const PatternColour& c, const std::string& source, const std::string& where);

/// `#rrggbb` of an sRGB colour (0..1).
std::string colour_code(const std::array<double, 3>& srgb);

/// The palette index of `name` (case-insensitive; a colour's name or its alias), or -1.
int find_colour(const std::vector<PatternColour>& palette, const std::string& name);

/// Adds the colours of `added` that `palette` does not name yet (by name, case-insensitive; a name already there
/// keeps its colour) and returns each added colour's index in `palette`: a pattern's palette joining a garment's.
std::vector<int> merge_palette(std::vector<PatternColour>& palette, const std::vector<PatternColour>& added);

/// Colours the yarn: each control point takes the colour of the stitch face it was emitted in
/// (`face_colour[point_face]`), a point of no face (a border piece) that of the nearest point along its yarn
/// that has one. Sets `yarn.point_colour` and `yarn.colours`; with an empty palette it clears them.
void colour_yarn(relax::YarnCurves& yarn, const std::vector<int>& face_colour, const std::vector<PatternColour>& palette);

/// The yarn length of each colour [mm] (the control polygon's, each segment to its first point's colour).
std::vector<double> yarn_length_by_colour(const relax::YarnCurves& yarn);

}  // namespace skein::mesh
