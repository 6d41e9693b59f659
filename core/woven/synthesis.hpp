#pragma once
#include <cstdint>
#include <vector>

#include "woven/weave.hpp"

namespace skein::woven {

/// Zhao 2012 §5.3: where one output crossing copies its volume from: exemplar `exemplar`'s block at crossing
/// column x (warp) and row y (weft).
struct Block {
  int exemplar = -1, x = 0, y = 0;
  bool operator==(const Block&) const = default;
};

/// The assignment function c: one block per crossing of the target weave, row by row (weft i, warp j).
struct Assignment {
  int warps = 0, wefts = 0;
  std::vector<Block> blocks;
  const Block& at(int weft, int warp) const { return blocks[static_cast<size_t>(weft) * warps + warp]; }
  Block& at(int weft, int warp) { return blocks[static_cast<size_t>(weft) * warps + warp]; }
};

struct SynthesisOptions {
  /// Also count continuity with the column to the left (already assigned) in each column's dynamic program.
  /// Zhao's Eq. 1 counts the two neighbours along the column only; the 2-D continuity it approximates counts four.
  bool horizontal = true;
  /// §5.4 Randomization: shift every group x group blocks by one random translational symmetry of their
  /// exemplars (a shift under which each block keeps its weave neighbourhood), so no period shows.
  bool randomize = true;
  int group = 3;
  std::uint64_t seed = 1;
};

/// The three principles of §5.3, counted over an assignment.
struct SynthesisScore {
  long crossings = 0;
  long correct = 0;       ///< principle 1: the block has the target's yarn on top
  long matches = 0;       ///< principle 2: the target's neighbours the block's neighbours match (at most 4 per crossing)
  long best_matches = 0;  ///< the most matches any correct assignment could reach (each crossing's best correct block)
  long consistent = 0;    ///< crossings whose every neighbour matches
  long continuity = 0;    ///< principle 3: pairs of neighbouring crossings that copy neighbouring blocks of one exemplar
};

/// Principle 2 for one block: how many of the target crossing's (up to four) neighbours the block's
/// neighbours in its exemplar match (a neighbour past the exemplar's edge matches nothing).
int neighbour_matches(const Weave& target, int weft, int warp, const Weave& exemplar, int x, int y);

/// §5.3 continuity between two neighbouring crossings (d_weft, d_warp one step apart): whether they copy
/// blocks of one exemplar lying the same step apart.
bool continuous(const Block& a, const Block& b, int d_weft, int d_warp);

/// §5.4: correct blocks only; per crossing the blocks of the most matching neighbours (consistency, solved
/// exactly, crossing by crossing); among those, per warp column the dynamic program of Eq. 1 for the most
/// continuity; then the randomization. Throws skein::Error when no exemplar has a block with the needed yarn
/// on top.
Assignment synthesize(const Weave& target, const std::vector<Weave>& exemplars, const SynthesisOptions& options = {});

SynthesisScore score(const Weave& target, const std::vector<Weave>& exemplars, const Assignment& assignment);

}  // namespace skein::woven
