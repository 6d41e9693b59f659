#pragma once
// Yarn and gauge as a knitter gives them (issue 24, part 1): a yarn by its weight class on the label (the Craft
// Yarn Council's Standard Yarn Weight System) or by its diameter, a fabric by its stockinette gauge, stitches
// and rows in 10 cm, or by the needle it is knitted on. From them: the stitch size to tessellate at, the yarn radius to emit at, and the loop
// length that relaxed plain knit of that gauge has (Munden 1959: the relaxed dimensions follow the loop length).
#include <string>
#include <vector>

#include "stitchmesh/tessellation.hpp"

namespace skein::mesh {

/// One of the Craft Yarn Council's weight classes: its stockinette gauge range and needle range, their middles,
/// and the middle of the wraps per inch that knitters measure for it.
struct YarnWeight {
  std::string name;                  ///< "lace", "fingering", "sport", "dk", "worsted", "bulky", "super-bulky", "jumbo"
  std::vector<std::string> aliases;  ///< the CYC names and common ones ("super-fine", "sock", "medium", "chunky", ...)
  int category = 0;                  ///< CYC 0 (lace) to 7 (jumbo)
  double wraps_per_inch = 0;
  double stitches_per_10cm = 0;      ///< stockinette, the middle of the range
  double needle_mm = 0;              ///< the middle of the needle range
  double stitches_min = 0, stitches_max = 0;  ///< the CYC's stockinette range in 10 cm (jumbo: up to 6)
  double needle_min_mm = 0, needle_max_mm = 0;  ///< the CYC's needle range (jumbo: from 12.75 mm, no upper end: infinity)
  double diameter() const { return 25.4 / wraps_per_inch; }  ///< [mm]: one wrap per diameter
};

/// The eight weight classes, thinnest first.
const std::vector<YarnWeight>& yarn_weights();
/// The class named `name` (or one of its aliases, case-insensitive); throws skein::Error listing the names.
const YarnWeight& find_yarn_weight(const std::string& name);

/// Munden's loop shape factor Kc/Kw of relaxed plain knit (courses over wales per length): rows in 10 cm when
/// a gauge gives only stitches.
inline constexpr double kLoopShapeFactor = 1.3;
/// Munden's Kw, wales per length x loop length, of dry-relaxed plain knit (3.8 to 4.2 from dry to fully relaxed).
inline constexpr double kMundenKw = 4.0;
/// A yarn's contact diameter in knitted fabric as a share of its wraps-per-inch diameter: yarn flattens and
/// compresses where it crosses yarn, which round tubes cannot. Fitted on dk stockinette at its standard gauge
/// with Munden's loop length (21.4 of 22.5 stitches in 10 cm); fingering and worsted then give 0.93 and 0.98 of
/// theirs (docs/BENCHMARKS.md, "At the yarns' own gauges").
inline constexpr double kYarnCompression = 0.46;

/// A stockinette gauge: stitches and rows in 10 cm.
struct Gauge {
  double stitches = 0, rows = 0;
  void validate() const;         ///< throws skein::Error unless both are finite, positive and at most 1000
  StitchSize stitch_size() const;  ///< 100 / stitches x 100 / rows mm
  /// The loop length of relaxed plain knit at this gauge: Kw / wales per mm [mm].
  double loop_length() const { return kMundenKw * 100 / stitches; }
};
/// "18x24" (stitches x rows) or "18" (rows: 1.3 x 18, kLoopShapeFactor); throws skein::Error naming `option`.
Gauge parse_gauge(const std::string& text, const std::string& option = "--gauge");
Gauge gauge_of(const StitchSize& size);  ///< the gauge of stitches of this size
/// The standard gauge of a weight class: its stitches, and rows by the loop shape factor.
Gauge standard_gauge(const YarnWeight& weight);
/// The gauge of a yarn of this weight knitted on a needle `needle_mm` across (issue 24, part 1). Each stitch is
/// formed as one wrap of yarn around the needle, so its loop length follows the wrap's centreline circumference
/// π (D + d) (D the needle, d the yarn's diameter), scaled from the weight's standard loop length at the middle
/// of its needle range: l = l_standard (D + d) / (D_standard + d); stitches = Kw / l (Munden), rows by the loop
/// shape factor. At the ends of the CYC's needle ranges it gives the ends of its gauge ranges within 7 % (11 % at
/// super-bulky's 12.75 mm; docs/yarn.md). Throws skein::Error naming `option` unless the needle is in (0, 50] mm.
Gauge needle_gauge(const YarnWeight& weight, double needle_mm, const std::string& option = "--needle");
/// Whether a needle lies in the weight's CYC range (a knitter may go outside it; callers warn with the note).
bool needle_in_range(const YarnWeight& weight, double needle_mm);
/// "outside the Craft Yarn Council's range for worsted yarn (4.5 to 5.5 mm); its gauge is extrapolated"
std::string needle_range_note(const YarnWeight& weight);

}  // namespace skein::mesh
