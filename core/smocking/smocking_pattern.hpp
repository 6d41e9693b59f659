#pragma once
// A smocking pattern (Zhou, Ren and Sorkine-Hornung 2024, §3): a grid of fabric points and stitching paths
// through them, each path one thread, its stitches alternately on the front and the back. The text format is in
// docs/smocking.md; Italian, Canadian and English smocking (the paper's Table 1) share it.
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace skein::smocking {

/// Italian: long paths, the fabric slides along the thread (Zhou 2024 §4.1). Canadian: short lines, each
/// gathered to one knot, stitches on the front only (§5.4). English: straight rows of even running stitches
/// pulled taut into regular pleats (Table 1).
enum class Style { Italian, Canadian, English };

/// One thread: grid points (column, row; row 0 at the top) in the order it is sewn.
struct Thread {
  std::vector<Eigen::Vector2i> points;
  bool first_front = true;  ///< the stitch from points[0] to points[1] lies on the front; the next on the back, ...
  int line = 0;             ///< the pattern line it came from (for messages)
  /// Whether stitch k (points[k] to points[k+1]) lies on the front.
  bool front(int k) const { return (k % 2 == 0) == first_front; }
};

/// A bead threaded on one stitch (Zhou 2024 §5.2, Fig. 12): the stitch cannot close below its diameter.
struct Bead {
  Eigen::Vector2i a, b;  ///< the stitch's two grid points, in either order
  double diameter = 0;   ///< [mm]
  int line = 0;
};

struct SmockingPattern {
  std::string name, note;
  Style style = Style::Italian;
  int columns = 0, rows = 0;  ///< grid points across and down
  double spacing = 10;        ///< mm between neighbouring grid points
  double gamma = 0.3;         ///< the threads' length after pulling over their length as sewn (Zhou eq. 1c)
  std::vector<Thread> threads;
  std::vector<Bead> beads;

  int num_points() const { return columns * rows; }
  int index(const Eigen::Vector2i& p) const { return p.y() * columns + p.x(); }
  /// The flat fabric's position of a grid point [mm], x to the right, y up (row 0 at the top, at y = 0).
  Eigen::Vector2d rest_position(const Eigen::Vector2i& p) const { return spacing * Eigen::Vector2d(p.x(), -p.y()); }
  int num_stitches() const;
};

const char* style_name(Style style);

/// Every thread on the grid with no stitch of zero length, and the style's rules (Table 1); throws skein::Error
/// naming `source` and each thread's line.
void check_threads(const SmockingPattern& pattern, const std::string& source);

/// Reads a smocking pattern; throws skein::Error naming the file, the line and the rule broken.
SmockingPattern read_smocking_pattern(const std::filesystem::path& file);
/// The same from text; `source` names it in errors.
SmockingPattern parse_smocking_pattern(const std::string& text, const std::string& source);

}  // namespace skein::smocking
