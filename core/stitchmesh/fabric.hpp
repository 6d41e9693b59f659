#pragma once
// Yarn and gauge as a knitter gives them (issue 24, part 1): a yarn by its weight class on the label (the Craft
// Yarn Council's Standard Yarn Weight System) or by its diameter, a fabric by its stockinette gauge, stitches
// and rows in 10 cm. From them: the stitch size to tessellate at, the yarn radius to emit at, and the loop
// length that relaxed plain knit of that gauge has (Munden 1959: the relaxed dimensions follow the loop length).
#include <string>
#include <vector>

#include "stitchmesh/tessellation.hpp"

namespace skein::mesh {

/// One of the Craft Yarn Council's weight classes: the middle of its stockinette gauge range and of its needle
/// range, and the middle of the wraps per inch that knitters measure for it.
struct YarnWeight {
  std::string name;                  ///< "lace", "fingering", "sport", "dk", "worsted", "bulky", "super-bulky", "jumbo"
  std::vector<std::string> aliases;  ///< the CYC names and common ones ("super-fine", "sock", "medium", "chunky", ...)
  int category = 0;                  ///< CYC 0 (lace) to 7 (jumbo)
  double wraps_per_inch = 0;
  double stitches_per_10cm = 0;      ///< stockinette
  double needle_mm = 0;
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

}  // namespace skein::mesh
