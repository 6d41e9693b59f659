#pragma once
#include <vector>

#include "stitchmesh/input_mesh.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/stitch_mesh.hpp"

namespace skein::mesh {

/// The size of one stitch on the garment [mm]: along the course (width) and along the wale (height).
struct StitchSize {
  double width = 6.0;
  double height = 5.0;
  void validate() const;  ///< throws skein::Error unless both are finite and positive
};

/// Tessellation values (Yuksel 2012 §5.2): for a course edge, how many stitches lie along it; for a wale
/// edge, how many stitch rows its input row splits into (all wale edges of a row share one value).
struct TessellationValues {
  std::vector<int> edge;     ///< per input edge, >= 1
  std::vector<char> marked;  ///< per input edge: 1 = increases/decreases of its faces go next to this wale edge
};

/// Values from edge lengths and the stitch size; each row gets enough stitch rows that no stitch row
/// more than doubles or halves its stitch count (so increases are 1→2 and decreases 2→1).
TessellationValues initial_values(const InputMesh& mesh, const Labeling& labels, const StitchSize& size);

/// Sets a course edge's value. Throws skein::Error for a wale edge or n < 1.
void set_course_value(const InputMesh& mesh, const Labeling& labels, TessellationValues& values, int edge, int n);
/// Sets the value of every wale edge of a row. Throws skein::Error for n < 1 or an unknown row.
void set_row_value(const InputMesh& mesh, const Labeling& labels, TessellationValues& values, int row, int n);
/// Marks (or unmarks) a wale edge as the one increases and decreases of its faces are placed along.
void mark_wale_edge(const InputMesh& mesh, const Labeling& labels, TessellationValues& values, int edge, bool marked);

/// About how many stitches the mesh makes at this stitch size: its surface area over the stitch's (issue 25).
double estimated_stitches(const InputMesh& mesh, const StitchSize& size);
/// The default of `--max-stitches`: more than any garment needs, fewer than fill this machine's memory.
inline constexpr double kDefaultMaxStitches = 5e6;
/// Throws skein::Error naming the mesh, the estimate and the stitch size when it passes `max_stitches`.
void check_stitch_count(const InputMesh& mesh, const StitchSize& size, double max_stitches);

/// Tessellates every labeled face into stitch faces: edges split uniformly, inner vertices placed with mean
/// value coordinates over the face, increase/decrease faces next to the wale edges (or the marked one).
/// Throws skein::Error naming the face when the labeling is invalid or a stitch row would change its
/// stitch count by more than 3x (no stitch type has more than 3 top or bottom edges).
StitchMesh tessellate(const InputMesh& mesh, const Labeling& labels, const TessellationValues& values);

}  // namespace skein::mesh
