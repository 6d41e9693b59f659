#include "render/chart_view.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "stitchmesh/stitch_types.hpp"

namespace skein::render {
namespace {

const Eigen::Vector3f kInk(0.08f, 0.08f, 0.1f), kGrid(0.6f, 0.6f, 0.62f), kPaper(1, 1, 1), kNoSymbol(0.78f, 0.78f, 0.8f),
    kCable(0.1f, 0.35f, 0.6f), kNumber(0.3f, 0.3f, 0.55f);

/// Drawing in cell units (x across, y up), each layer a little nearer the eye than the one below it.
struct Sketch {
  std::vector<Polygon> polygons;
  void quad(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d, const Eigen::Vector3f& color,
            double z) {
    Polygon p;
    for (const auto& v : {a, b, c, d}) p.points.emplace_back(v.x(), v.y(), z);
    p.color = color;
    polygons.push_back(std::move(p));
  }
  void box(double x0, double y0, double x1, double y1, const Eigen::Vector3f& color, double z) { quad({x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, color, z); }
  void stroke(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, const Eigen::Vector3f& color, double z = 0.03) {
    const Eigen::Vector2d d = (b - a).normalized(), n(-d.y() * width / 2, d.x() * width / 2);
    quad(a - n, b - n, b + n, a + n, color, z);
  }
  void dot(const Eigen::Vector2d& c, double r, const Eigen::Vector3f& color) {
    Polygon p;
    for (int k = 0; k < 16; ++k) p.points.emplace_back(c.x() + r * std::cos(k * M_PI / 8), c.y() + r * std::sin(k * M_PI / 8), 0.03);
    p.color = color;
    polygons.push_back(std::move(p));
  }
  void ring(const Eigen::Vector2d& c, double r, double width) {
    for (int k = 0; k < 20; ++k) {
      const double a0 = k * M_PI / 10, a1 = (k + 1) * M_PI / 10;
      stroke(c + r * Eigen::Vector2d(std::cos(a0), std::sin(a0)), c + r * Eigen::Vector2d(std::cos(a1), std::sin(a1)), width, kInk);
    }
  }
};

/// The symbol of one stitch in the cell whose lower left corner is (x, y): `glyph` is k p y / \ ^ v x.
void draw_glyph(Sketch& s, char glyph, double x, double y) {
  const double w = 0.09;
  const Eigen::Vector2d c(x + 0.5, y + 0.5);
  switch (glyph) {
    case 'k': break;
    case 'p': s.dot(c, 0.14, kInk); break;
    case 'y': s.ring(c, 0.28, w); break;
    case '/': s.stroke({x + 0.2, y + 0.15}, {x + 0.8, y + 0.85}, w, kInk); break;
    case '\\': s.stroke({x + 0.2, y + 0.85}, {x + 0.8, y + 0.15}, w, kInk); break;
    case '^':
      s.stroke({x + 0.2, y + 0.2}, {x + 0.5, y + 0.8}, w, kInk);
      s.stroke({x + 0.5, y + 0.8}, {x + 0.8, y + 0.2}, w, kInk);
      break;
    case 'v':
      s.stroke({x + 0.25, y + 0.8}, {x + 0.5, y + 0.2}, w, kInk);
      s.stroke({x + 0.5, y + 0.2}, {x + 0.75, y + 0.8}, w, kInk);
      break;
    case 'x':
      s.stroke({x + 0.3, y + 0.3}, {x + 0.7, y + 0.7}, w, kInk);
      s.stroke({x + 0.3, y + 0.7}, {x + 0.7, y + 0.3}, w, kInk);
      break;
    default: s.box(x + 0.06, y + 0.06, x + 0.94, y + 0.94, kNoSymbol, 0.02); break;
  }
}

/// Row number `n` as seven-segment digits `height` cells tall, its lower left corner at (x, y); returns the
/// width it took.
double draw_number(Sketch& s, int n, double x, double y, double height) {
  // Segments a (top), b (upper right), c (lower right), d (bottom), e (lower left), f (upper left), g (middle).
  static const char* const kDigits[] = {"abcdef", "bc", "abged", "abgcd", "fgbc", "afgcd", "afgedc", "abc", "abcdefg", "abcdfg"};
  const std::string digits = std::to_string(n);
  const double w = 0.55 * height, line = 0.16 * height, advance = w + 0.35 * height;
  for (size_t k = 0; k < digits.size(); ++k) {
    const double x0 = x + k * advance, x1 = x0 + w, y0 = y, y1 = y + height / 2, y2 = y + height;
    const double xs[2] = {x0, x1}, ys[3] = {y0, y1, y2};
    // Each segment's two ends, a to g: (column 0 or 1, height 0, 1 or 2 halves) and the same for the other end.
    static const int kEnds[7][4] = {{0, 2, 1, 2}, {1, 2, 1, 1}, {1, 1, 1, 0}, {0, 0, 1, 0}, {0, 1, 0, 0}, {0, 2, 0, 1}, {0, 1, 1, 1}};
    for (const char* seg = kDigits[digits[k] - '0']; *seg; ++seg) {
      const int* e = kEnds[*seg - 'a'];
      const Eigen::Vector2d a(xs[e[0]], ys[e[1]]), b(xs[e[2]], ys[e[3]]);
      const Eigen::Vector2d along = (b - a).normalized() * (line / 2);
      s.stroke(a - along, b + along, line, kNumber);
    }
  }
  return digits.size() * advance;
}

/// The glyphs of a face's cells, left to right (its stitch model's order), or "" when the type has no symbol.
std::string glyphs_of(const std::string& type, int cells) {
  if (type == "ys") return "y\\";   // a yarn-over, then ssk (stitches/ys.stitch)
  if (type == "2u") return "/y";    // k2tog, then a yarn-over
  if (type == "y3y") return "y^y";  // a yarn-over, sk2p, a yarn-over
  if (type == "s" || type == "sk") return "v";
  if (type == "x") return "x";
  if (type.size() >= 4 && type[0] == 'd' && std::isdigit(static_cast<unsigned char>(type[1]))) {
    // Decreases: the loop stacked nearest the new one says the lean (d12k: k2tog, /; d21k: ssk, \).
    const std::string digits = type.substr(1, type.size() - 2);
    const char lean = digits.front() == '1' ? '/' : digits.back() == '1' ? '\\' : '^';
    return std::string(1, lean) + (type.back() == 'p' ? "p" : "");
  }
  // k p y, their twisted tops (k+1, p-1 ...) and increases into several (kp, kyk, ...): one letter a cell.
  std::string base;
  for (char c : type)
    if (c == 'k' || c == 'p' || c == 'y') base += c;
    else if (c != '+' && c != '-' && !std::isdigit(static_cast<unsigned char>(c))) return "";
  return static_cast<int>(base.size()) == cells ? base : "";
}

}  // namespace

Image draw_chart(const mesh::Pattern& pattern, int cell) {
  if (pattern.format == mesh::PatternFormat::Woven) throw Error("", "chart", "a woven pattern has no knitting chart: draw its yarn with --png");
  if (cell < 8 || cell > 200) throw Error("", "chart", "cells of 8 to 200 pixels, found " + std::to_string(cell));
  Sketch s;
  int width = 0;
  const int rows = pattern.height();
  for (int r = 0; r < rows; ++r) {
    int x = 0;
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
      }
      x += cells;
    }
    width = std::max(width, x);
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
  // Row numbers at the right of each row, as charts print them (row 1 at the bottom).
  double numbers = 0;
  for (int r = 0; r < rows; ++r) numbers = std::max(numbers, draw_number(s, r + 1, width + 0.3, r + 0.25, 0.5));
  // The grid, and the paper under it with a margin.
  for (int r = 0; r <= rows; ++r) s.box(0, r - 0.015, width, r + 0.015, kGrid, 0.01);
  for (int c = 0; c <= width; ++c) s.box(c - 0.015, 0, c + 0.015, rows, kGrid, 0.01);
  s.box(-0.3, -0.3, width + 0.5 + numbers, rows + 0.3, kPaper, 0);
  View view;
  view.directions = {{0, 0, -1}};
  view.outlines = false;
  view.panel = std::clamp(static_cast<int>(cell * (std::max(width + numbers, static_cast<double>(rows)) + 1)), 64, 4096);
  return draw(s.polygons, view);
}

}  // namespace skein::render
