#include "render/chart_view.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "render/sketch.hpp"
#include "stitchmesh/stitch_types.hpp"

namespace skein::render {
namespace {

const Eigen::Vector3f kInk(0.08f, 0.08f, 0.1f), kGrid(0.6f, 0.6f, 0.62f), kPaper(1, 1, 1), kNoSymbol(0.78f, 0.78f, 0.8f),
    kCable(0.1f, 0.35f, 0.6f), kNumber(0.3f, 0.3f, 0.55f), kNoStitch(0.55f, 0.55f, 0.58f);

/// The symbol of one stitch in the cell whose lower left corner is (x, y): `glyph` is k p y / \ ^ v x q.
void draw_glyph(Sketch& s, char glyph, double x, double y) {
  const double w = 0.09;
  const Eigen::Vector2d c(x + 0.5, y + 0.5);
  switch (glyph) {
    case 'k': break;
    case 'p': s.dot(c, 0.14, kInk); break;
    case 'y': s.ring(c, 0.28, w, kInk); break;
    case '/': s.stroke({x + 0.2, y + 0.15}, {x + 0.8, y + 0.85}, w, kInk); break;
    case '\\': s.stroke({x + 0.2, y + 0.85}, {x + 0.8, y + 0.15}, w, kInk); break;
    case '(':  // ssp: ssk's lean and a purl's dot
    case ')':  // p2tog
      draw_glyph(s, glyph == '(' ? '\\' : '/', x, y);
      s.dot({x + 0.5, y + 0.22}, 0.09, kInk);
      break;
    case '{':  // k3tog: three strands meeting at the top right
      s.stroke({x + 0.2, y + 0.15}, {x + 0.8, y + 0.85}, w, kInk);
      s.stroke({x + 0.55, y + 0.15}, {x + 0.8, y + 0.85}, w, kInk);
      break;
    case '}':  // sssk: at the top left
      s.stroke({x + 0.2, y + 0.85}, {x + 0.8, y + 0.15}, w, kInk);
      s.stroke({x + 0.2, y + 0.85}, {x + 0.45, y + 0.15}, w, kInk);
      break;
    case '^':
      s.stroke({x + 0.2, y + 0.2}, {x + 0.5, y + 0.8}, w, kInk);
      s.stroke({x + 0.5, y + 0.8}, {x + 0.8, y + 0.2}, w, kInk);
      break;
    case 'v':
      s.stroke({x + 0.25, y + 0.8}, {x + 0.5, y + 0.2}, w, kInk);
      s.stroke({x + 0.5, y + 0.2}, {x + 0.75, y + 0.8}, w, kInk);
      break;
    case 'x':
    case 'q':  // a crossed purl: the cross and, below it, the purl's dot
      s.stroke({x + 0.3, y + 0.3}, {x + 0.7, y + 0.7}, w, kInk);
      s.stroke({x + 0.3, y + 0.7}, {x + 0.7, y + 0.3}, w, kInk);
      if (glyph == 'q') s.dot({x + 0.5, y + 0.16}, 0.08, kInk);
      break;
    default: s.box(x + 0.06, y + 0.06, x + 0.94, y + 0.94, kNoSymbol, 0.02); break;
  }
}

/// The glyphs of a face's cells, left to right (its stitch model's order), or "" when the type has no symbol.
std::string glyphs_of(const std::string& type, int cells) {
  if (type == "ys") return "y\\";   // a yarn-over, then ssk (stitches/ys.stitch)
  if (type == "2u") return "/y";    // k2tog, then a yarn-over
  if (type == "ysp") return "y(";   // garter lace from the front: a yarn-over, then ssp (stitches/ysp.stitch)
  if (type == "2up") return ")y";   // p2tog, then a yarn-over
  if (type == "y3y") return "y^y";  // a yarn-over, sk2p, a yarn-over
  if (type == "s" || type == "sk") return "v";
  if (type == "x" || type == "q") return type;
  if (type.size() >= 4 && type[0] == 'd' && std::isdigit(static_cast<unsigned char>(type[1]))) {
    // Decreases: the loop stacked nearest the new one says the lean (d12k: k2tog, /; d21k: ssk, \).
    const std::string digits = type.substr(1, type.size() - 2);
    const bool three = digits.size() == 3;  // k3tog, sssk: drawn with the third strand joining the lean
    const char lean = digits.front() == '1' ? (three ? '{' : '/') : digits.back() == '1' ? (three ? '}' : '\\') : '^';
    return std::string(1, lean) + (type.back() == 'p' ? "p" : "");
  }
  // k p y, their twisted tops (k+1, p-1 ...) and increases into several (kp, kyk, kfb's xk and pq ...): one letter a cell.
  std::string base;
  for (char c : type)
    if (c == 'k' || c == 'p' || c == 'y' || c == 'x' || c == 'q') base += c;
    else if (c != '+' && c != '-' && !std::isdigit(static_cast<unsigned char>(c))) return "";
  return static_cast<int>(base.size()) == cells ? base : "";
}

}  // namespace

Image draw_chart(const mesh::Pattern& pattern, int cell) {
  if (pattern.format == mesh::PatternFormat::Woven) throw Error("", "chart", "a woven pattern has no knitting chart: draw its yarn with --png");
  if (cell < 8 || cell > 200) throw Error("", "chart", "cells of 8 to 200 pixels, found " + std::to_string(cell));
  Sketch s;
  const int rows = pattern.height();
  // A shaped piece's rows are as wide as their stitches: centred, as its stitch mesh lays them out, between
  // grey 'no stitch' cells.
  std::vector<int> row_cells(static_cast<size_t>(rows), 0);
  for (int r = 0; r < rows; ++r) row_cells[static_cast<size_t>(r)] = mesh::loops_made(pattern.rows[r]);
  const int width = rows > 0 ? *std::max_element(row_cells.begin(), row_cells.end()) : 0;
  for (int r = 0; r < rows; ++r) {
    const int left = (width - row_cells[static_cast<size_t>(r)] + 1) / 2;
    for (int c = 0; c < width; ++c)
      if (c < left || c >= left + row_cells[static_cast<size_t>(r)]) s.box(c, r, c + 1, r + 1, kNoStitch, 0.02);
    int x = left;
    for (const auto& type : pattern.rows[r]) {
      const auto* t = mesh::find_stitch_type(type);
      const int cells = t ? t->top : 1;
      const std::string glyphs = glyphs_of(type, cells);
      if (glyphs.empty()) {
        s.box(x + 0.06, r + 0.06, x + cells - 0.06, r + 0.94, kNoSymbol, 0.02);
      } else if (glyphs.size() == 2 && glyphs[1] == 'p' && cells == 1) {
        draw_glyph(s, glyphs[0], x, r);  // a purled decrease: its lean and a dot
        s.dot({x + 0.5, r + 0.22}, 0.09, kInk);
      } else {
        for (int k = 0; k < cells && k < static_cast<int>(glyphs.size()); ++k) draw_glyph(s, glyphs[k], x + k, r);
        if (t && t->bottom == 1 && cells > 1 && glyphs.find_first_not_of("kpxq") == std::string::npos) {
          // Stitches worked into one (kfb, (k1, p1, k1) in next st): a bracket under their cells joins them.
          s.stroke({x + 0.15, r + 0.1}, {x + cells - 0.15, r + 0.1}, 0.06, kInk);
          s.stroke({x + 0.15, r + 0.1}, {x + 0.15, r + 0.3}, 0.06, kInk);
          s.stroke({x + cells - 0.15, r + 0.1}, {x + cells - 0.15, r + 0.3}, 0.06, kInk);
        }
      }
      x += cells;
    }
  }
  // Cables over their cells: the strand in front whole, the one behind broken where it passes.
  for (const auto& cable : pattern.cables) {
    const double x0 = cable.first_loop, x1 = x0 + cable.over + cable.under, y0 = cable.row, y1 = y0 + 1;
    s.box(x0 + 0.04, y0 + 0.04, x1 - 0.04, y1 - 0.04, kPaper, 0.025);  // cover the cells' own symbols
    // order -1 (C4F, a left cross): the right stitches move left in front; +1 (C4B) the left ones move right.
    const Eigen::Vector2d front_from = cable.order < 0 ? Eigen::Vector2d(x1 - 0.25, y0 + 0.12) : Eigen::Vector2d(x0 + 0.25, y0 + 0.12);
    const Eigen::Vector2d front_to = cable.order < 0 ? Eigen::Vector2d(x0 + 0.25, y1 - 0.12) : Eigen::Vector2d(x1 - 0.25, y1 - 0.12);
    const Eigen::Vector2d back_from(x0 + x1 - front_from.x(), front_from.y()), back_to(x0 + x1 - front_to.x(), front_to.y());
    const Eigen::Vector2d mid = 0.5 * (back_from + back_to), along = (back_to - back_from).normalized();
    s.stroke(back_from, mid - 0.22 * along, 0.14, kCable, 0.04);
    s.stroke(mid + 0.22 * along, back_to, 0.14, kCable, 0.04);
    s.stroke(front_from, front_to, 0.22, kCable, 0.05);
  }
  // Row numbers as charts print them (row 1 at the bottom): at the right of rows read from the right, and, worked
  // flat, at the left of the wrong-side rows, read from the left.
  double numbers = 0, left_numbers = 0;
  for (int r = 0; r < rows; ++r) {
    const bool wrong_side = pattern.flat && r % 2 == 1;
    const double digits_width = 0.45 * static_cast<double>(std::to_string(r + 1).size());
    if (wrong_side) left_numbers = std::max(left_numbers, s.number(r + 1, -0.3 - digits_width, r + 0.25, 0.5, kNumber) + 0.3);
    else numbers = std::max(numbers, s.number(r + 1, width + 0.3, r + 0.25, 0.5, kNumber));
  }
  // The grid, and the paper under it with a margin.
  for (int r = 0; r <= rows; ++r) s.box(0, r - 0.015, width, r + 0.015, kGrid, 0.01);
  for (int c = 0; c <= width; ++c) s.box(c - 0.015, 0, c + 0.015, rows, kGrid, 0.01);
  s.box(-0.3 - left_numbers, -0.3, width + 0.5 + numbers, rows + 0.3, kPaper, 0);
  return draw_flat(s, std::clamp(static_cast<int>(cell * (std::max(width + numbers + left_numbers, static_cast<double>(rows)) + 1)), 64, 4096));
}

}  // namespace skein::render
