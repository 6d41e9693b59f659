#pragma once
// Patterns compared as fabric: two repeats that make the same fabric, a pattern's rows as text, the bundled
// knit patterns.
#include <numeric>
#include <string>

#include "stitchmesh/pattern.hpp"

namespace skein::testing {

/// The two repeats make the same fabric: tiled to a common size, one equals the other shifted (rows and
/// columns, cyclically), cables included. For patterns of one-loop stitches.
inline bool same_fabric(const skein::mesh::Pattern& a, const skein::mesh::Pattern& b) {
  const int h = std::lcm(a.height(), b.height()), w = std::lcm(a.width(), b.width());
  const auto cell = [](const skein::mesh::Pattern& p, int r, int c) {
    const int rr = r % p.height(), cc = c % p.width();
    for (const auto& cable : p.cables)
      if (cable.row == rr && cc >= cable.first_loop && cc < cable.first_loop + cable.over + cable.under)
        return "cable" + std::to_string(cable.over) + "x" + std::to_string(cable.under) + (cable.order > 0 ? "+" : "-") + std::to_string(cc - cable.first_loop);
    return p.rows[rr][cc];
  };
  for (int dr = 0; dr < h; ++dr)
    for (int dc = 0; dc < w; ++dc) {
      bool same = true;
      for (int r = 0; r < h && same; ++r)
        for (int c = 0; c < w && same; ++c) same = cell(a, r, c) == cell(b, (r + dr) % h, (c + dc) % w);
      if (same) return true;
    }
  return false;
}
inline std::string rows_text(const skein::mesh::Pattern& p) {  // bottom row first
  std::string out;
  for (const auto& row : p.rows) {
    for (size_t i = 0; i < row.size(); ++i) out += (i ? " " : "") + row[i];
    out += " / ";
  }
  return out;
}
inline skein::mesh::Pattern bundled_knit(const std::string& name) { return skein::mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/" + name + ".knit"); }

}  // namespace skein::testing
