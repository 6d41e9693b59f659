#include "stitchmesh/fabric.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "common/error.hpp"

namespace skein::mesh {

const std::vector<YarnWeight>& yarn_weights() {
  // Craft Yarn Council, Standard Yarn Weight System: stockinette stitches in 4 in (10 cm) and needle sizes per
  // category; wraps per inch as yarn-weight charts give them. The ranges, and the middle of each (jumbo: 6 and
  // fewer stitches on 12.75 mm and larger; its middles are those of 4 to 6 stitches and 12.75 to 17.25 mm).
  constexpr double kOpen = std::numeric_limits<double>::infinity();
  static const std::vector<YarnWeight> weights = {
      {"lace", {"0", "cobweb", "thread"}, 0, 35, 36.5, 1.875, 33, 40, 1.5, 2.25},
      {"fingering", {"1", "super-fine", "sock", "baby"}, 1, 20.5, 29.5, 2.75, 27, 32, 2.25, 3.25},
      {"sport", {"2", "fine"}, 2, 16.5, 24.5, 3.5, 23, 26, 3.25, 3.75},
      {"dk", {"3", "light", "light-worsted"}, 3, 13, 22.5, 4.125, 21, 24, 3.75, 4.5},
      {"worsted", {"4", "medium", "aran", "afghan"}, 4, 10, 18, 5.0, 16, 20, 4.5, 5.5},
      {"bulky", {"5", "chunky", "craft", "rug"}, 5, 7.5, 13.5, 6.75, 12, 15, 5.5, 8},
      {"super-bulky", {"6", "super-chunky", "roving"}, 6, 5.5, 9, 10.375, 7, 11, 8, 12.75},
      {"jumbo", {"7"}, 7, 3.5, 5, 15, 0, 6, 12.75, kOpen},
  };
  return weights;
}

const YarnWeight& find_yarn_weight(const std::string& name) {
  std::string key = name;
  std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return c == '_' || c == ' ' ? '-' : std::tolower(c); });
  std::string names;
  for (const auto& w : yarn_weights()) {
    if (w.name == key || std::find(w.aliases.begin(), w.aliases.end(), key) != w.aliases.end()) return w;
    names += (names.empty() ? "" : ", ") + w.name;
  }
  throw Error("", "--yarn '" + name + "'", "is not a yarn weight; one of " + names + " (or the Craft Yarn Council's number 0 to 7)");
}

void Gauge::validate() const {
  for (const auto& [what, v] : {std::pair{"stitches", stitches}, std::pair{"rows", rows}})
    if (!(std::isfinite(v) && v > 0 && v <= 1000))
      throw Error("", "gauge", std::string(what) + " in 10 cm must be a number in (0, 1000], got " + std::to_string(v));
}

StitchSize Gauge::stitch_size() const {
  validate();
  return {100 / stitches, 100 / rows};
}

Gauge parse_gauge(const std::string& text, const std::string& option) {
  const auto bad = [&](const std::string& rule) { return Error("", option + " '" + text + "'", rule); };
  const std::string format = "expected STITCHES or STITCHESxROWS in 10 cm of stockinette (e.g. 18x24)";
  // A number that fills its whole part of the text: "18", "18.5", "1e2"; not "18 rows" or "0x12".
  const auto number = [&](const std::string& part) {
    if (part.empty() || part.find_first_not_of("0123456789.+-eE") != std::string::npos) throw bad(format);
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (*end != 0) throw bad(format);
    return v;
  };
  const auto x = text.find('x');
  Gauge g;
  g.stitches = number(text.substr(0, x));
  g.rows = x == std::string::npos ? kLoopShapeFactor * g.stitches : number(text.substr(x + 1));
  try {
    g.validate();
  } catch (const Error& e) {
    throw bad(e.rule());
  }
  return g;
}

Gauge gauge_of(const StitchSize& size) { return {100 / size.width, 100 / size.height}; }

Gauge standard_gauge(const YarnWeight& weight) { return {weight.stitches_per_10cm, kLoopShapeFactor * weight.stitches_per_10cm}; }

Gauge needle_gauge(const YarnWeight& weight, double needle_mm, const std::string& option) {
  if (!(std::isfinite(needle_mm) && needle_mm > 0 && needle_mm <= 50))
  {
    std::ostringstream given;
    given << needle_mm;
    throw Error("", option + " " + given.str(), "a needle's diameter must be a number of millimetres in (0, 50]");
  }
  // One wrap of yarn around the needle per stitch: the loop length follows the wrap's centreline, π (D + d).
  const double d = weight.diameter();
  const double loop = standard_gauge(weight).loop_length() * (needle_mm + d) / (weight.needle_mm + d);
  const double stitches = kMundenKw * 100 / loop;  // Gauge::loop_length inverted
  return {stitches, kLoopShapeFactor * stitches};
}

bool needle_in_range(const YarnWeight& weight, double needle_mm) {
  return needle_mm >= weight.needle_min_mm && needle_mm <= weight.needle_max_mm;
}

std::string needle_range_note(const YarnWeight& weight) {
  std::ostringstream range;
  range << weight.needle_min_mm;
  if (std::isfinite(weight.needle_max_mm))
    range << " to " << weight.needle_max_mm << " mm";
  else
    range << " mm and larger";
  return "outside the Craft Yarn Council's range for " + weight.name + " yarn (" + range.str() + "); its gauge is extrapolated";
}

}  // namespace skein::mesh
