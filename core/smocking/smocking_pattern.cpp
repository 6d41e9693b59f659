#include "smocking/smocking_pattern.hpp"

#include <charconv>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/error.hpp"
#include "common/input_file.hpp"
#include "common/text.hpp"

namespace skein::smocking {
namespace {

constexpr int kMaxGridPoints = 250'000;  // 500 x 500: Algorithm 1 steps every point thousands of times
constexpr int kMaxStitches = 1'000'000;

using Word = Token;

class Reader {
public:
  Reader(std::string source) : m_source(std::move(source)) {}
  [[noreturn]] void fail(int line, const Word& w, const std::string& rule) const { throw Error(m_source, text_place(line, w.column), rule); }
  [[noreturn]] void fail(int line, const std::string& rule) const { throw Error(m_source, text_place(line), rule); }

  int integer(int line, const Word& w, std::string_view text, const char* what) const {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    int v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty())
      fail(line, w, std::string("expected ") + what + " (a whole number), found \"" + w.text + "\"");
    return v;
  }
  double number(int line, const Word& w, const char* what) const {
    double v = 0;
    const auto [end, ec] = std::from_chars(w.text.data(), w.text.data() + w.text.size(), v);
    if (ec != std::errc() || end != w.text.data() + w.text.size()) fail(line, w, std::string("expected ") + what + " (a number), found \"" + w.text + "\"");
    return v;
  }
  /// "C,R" (a point or a step).
  Eigen::Vector2i pair(int line, const Word& w, const char* what) const {
    const auto comma = w.text.find(',');
    if (comma == std::string::npos || w.text.find(',', comma + 1) != std::string::npos)
      fail(line, w, std::string("expected ") + what + " as COLUMN,ROW, found \"" + w.text + "\"");
    const std::string_view t(w.text);
    return {integer(line, w, t.substr(0, comma), what), integer(line, w, t.substr(comma + 1), what)};
  }
  /// "xN", N >= 1.
  int times(int line, const Word& w) const {
    if (w.text.size() < 2 || w.text[0] != 'x') fail(line, w, "expected a count as xN (x3: three times), found \"" + w.text + "\"");
    const int n = integer(line, w, std::string_view(w.text).substr(1), "a count of 1 to 1000000");
    if (n < 1 || n > kMaxStitches) fail(line, w, "a count of 1 to " + std::to_string(kMaxStitches) + ", found " + std::to_string(n));
    return n;
  }

private:
  std::string m_source;
};

void check_on_grid(const Reader& reader, const SmockingPattern& p, const Thread& t, int line, const std::string& what) {
  for (size_t k = 0; k < t.points.size(); ++k) {
    const auto& q = t.points[k];
    if (q.x() < 0 || q.y() < 0 || q.x() >= p.columns || q.y() >= p.rows)
      reader.fail(line, what + "point " + std::to_string(k + 1) + " (" + std::to_string(q.x()) + "," + std::to_string(q.y()) +
                            ") is off the grid of " + std::to_string(p.columns) + " x " + std::to_string(p.rows) + " points (columns 0 to " +
                            std::to_string(p.columns - 1) + ", rows 0 to " + std::to_string(p.rows - 1) + ")");
    if (k > 0 && q == t.points[k - 1])
      reader.fail(line, what + "stitch " + std::to_string(k) + " goes from (" + std::to_string(q.x()) + "," + std::to_string(q.y()) +
                            ") to the same point: a stitch joins two different grid points");
  }
}

/// Table 1's rules for each style.
void check_style(const Reader& reader, const SmockingPattern& p) {
  for (const auto& t : p.threads) {
    if (p.style == Style::Canadian && !t.first_front)
      reader.fail(t.line, "Canadian smocking is stitched on the front only (Zhou 2024 §5.4): leave out \"back\"");
    if (p.style != Style::English) continue;
    const Eigen::Vector2i step = t.points[1] - t.points[0];
    for (size_t k = 1; k < t.points.size(); ++k) {
      const Eigen::Vector2i s = t.points[k] - t.points[k - 1];
      if (s.y() != 0 || s != step)
        reader.fail(t.line, "English smocking gathers along straight rows of even stitches (Zhou 2024 Table 1), but stitch " + std::to_string(k) +
                                " goes by (" + std::to_string(s.x()) + "," + std::to_string(s.y()) + ") where the first went by (" +
                                std::to_string(step.x()) + "," + std::to_string(step.y()) + ")");
    }
  }
}

}  // namespace

void check_threads(const SmockingPattern& pattern, const std::string& source) {
  const Reader reader(source);
  if (pattern.columns < 2 || pattern.rows < 1 || static_cast<long>(pattern.columns) * pattern.rows > kMaxGridPoints)
    throw Error(source, "", "a grid of at least 2 x 1 and at most " + std::to_string(kMaxGridPoints) + " points, found " + std::to_string(pattern.columns) +
                                " x " + std::to_string(pattern.rows));
  if (pattern.threads.empty()) throw Error(source, "", "no thread");
  for (const auto& t : pattern.threads) {
    if (t.points.size() < 2) reader.fail(t.line, "a thread of at least two grid points (one stitch)");
    check_on_grid(reader, pattern, t, t.line, "");
  }
  check_style(reader, pattern);
  for (const auto& b : pattern.beads) {
    bool found = false;
    for (const auto& t : pattern.threads)
      for (size_t k = 0; k + 1 < t.points.size() && !found; ++k)
        found = (t.points[k] == b.a && t.points[k + 1] == b.b) || (t.points[k] == b.b && t.points[k + 1] == b.a);
    if (!found)
      reader.fail(b.line, "no stitch goes between (" + std::to_string(b.a.x()) + "," + std::to_string(b.a.y()) + ") and (" + std::to_string(b.b.x()) + "," +
                              std::to_string(b.b.y()) + ") to thread the bead on");
  }
}

int SmockingPattern::num_stitches() const {
  int n = 0;
  for (const auto& t : threads) n += static_cast<int>(t.points.size()) - 1;
  return n;
}

const char* style_name(Style style) {
  switch (style) {
    case Style::Italian: return "italian";
    case Style::Canadian: return "canadian";
    case Style::English: return "english";
  }
  return "?";
}

SmockingPattern parse_smocking_pattern(const std::string& text, const std::string& source) {
  const Reader reader(source);
  SmockingPattern p;
  std::istringstream in(text);
  LineReader lines(in, source);
  int line = 0, format_line = 0, grid_line = 0;
  long stitches = 0;
  const auto add_stitches = [&](long n, int at) {
    stitches += n;
    if (stitches > kMaxStitches) reader.fail(at, "more than " + std::to_string(kMaxStitches) + " stitches in all");
  };
  while (lines.next()) {
    line = lines.number();
    const std::string& raw = lines.line();
    if (raw.rfind("# name:", 0) == 0) p.name = trim(raw.substr(7));
    if (raw.rfind("# source:", 0) == 0) p.note = trim(raw.substr(9));
    const auto words = split(raw.substr(0, raw.find('#')));
    if (words.empty()) continue;
    const std::string& key = words[0].text;
    if (format_line == 0) {
      if (key != "format") reader.fail(line, words[0], "expected the format first (\"format smocking\"), found \"" + key + "\"");
      if (words.size() != 2 || words[1].text != "smocking")
        reader.fail(line, words.size() > 1 ? words[1] : words[0], "this reader takes \"format smocking\" (knits and weaves: skein pattern)");
      format_line = line;
      continue;
    }
    const auto arguments = [&](size_t n, const char* usage) {
      if (words.size() != n + 1) reader.fail(line, words[0], std::string("expected \"") + usage + "\"");
    };
    if (key == "style") {
      arguments(1, "style italian|canadian|english");
      const std::string& s = words[1].text;
      if (s == "italian") p.style = Style::Italian;
      else if (s == "canadian") p.style = Style::Canadian;
      else if (s == "english") p.style = Style::English;
      else reader.fail(line, words[1], "expected italian, canadian or english, found \"" + s + "\"");
    } else if (key == "grid") {
      arguments(2, "grid COLUMNS ROWS");
      if (grid_line) reader.fail(line, words[0], "a second grid (the first is on line " + std::to_string(grid_line) + ")");
      if (!p.threads.empty()) reader.fail(line, words[0], "the grid comes before the threads");
      p.columns = reader.integer(line, words[1], words[1].text, "the number of columns");
      p.rows = reader.integer(line, words[2], words[2].text, "the number of rows");
      if (p.columns < 2 || p.rows < 1 || static_cast<long>(p.columns) * p.rows > kMaxGridPoints)
        reader.fail(line, words[1], "a grid of at least 2 x 1 and at most " + std::to_string(kMaxGridPoints) + " points, found " +
                                        std::to_string(p.columns) + " x " + std::to_string(p.rows));
      grid_line = line;
    } else if (key == "spacing") {
      arguments(1, "spacing MM");
      p.spacing = reader.number(line, words[1], "the grid spacing in mm");
      if (!(p.spacing >= 0.1 && p.spacing <= 1000)) reader.fail(line, words[1], "a grid spacing of 0.1 to 1000 mm, found " + words[1].text);
    } else if (key == "gamma") {
      arguments(1, "gamma G");
      p.gamma = reader.number(line, words[1], "the shrinkage gamma");
      if (!(p.gamma > 0 && p.gamma <= 1)) reader.fail(line, words[1], "gamma (the threads' length after pulling over before) in (0, 1], found " + words[1].text);
    } else if (key == "path" || key == "walk") {
      if (!grid_line) reader.fail(line, words[0], "a thread before the grid: write \"grid COLUMNS ROWS\" first");
      Thread t;
      t.line = line;
      size_t w = 1;
      if (w < words.size() && (words[w].text == "front" || words[w].text == "back")) t.first_front = words[w++].text == "front";
      for (size_t k = w; k < words.size(); ++k) {
        if (words[k].text == "front" || words[k].text == "back")
          reader.fail(line, words[k], "\"" + words[k].text + "\" comes right after \"" + key + "\": it says the side of the thread's first stitch");
        if (words[k].text.size() > 1 && words[k].text[0] == 'x' && k + 1 < words.size())
          reader.fail(line, words[k], "the count \"" + words[k].text + "\" comes last, after the steps");
      }
      if (key == "path") {
        for (; w < words.size(); ++w) t.points.push_back(reader.pair(line, words[w], "a grid point"));
        if (t.points.size() < 2) reader.fail(line, words[0], "a path of at least two grid points (one stitch): path [front|back] C,R C,R ...");
      } else {
        // walk [front|back] START STEP... xN: N stitches from START, taking the steps in turn.
        if (words.size() < w + 3) reader.fail(line, words[0], "expected \"walk [front|back] C,R STEP... xN\" (N stitches from C,R, the steps in turn)");
        Eigen::Vector2i at = reader.pair(line, words[w++], "the start point");
        std::vector<Eigen::Vector2i> steps;
        for (; w + 1 < words.size(); ++w) {
          steps.push_back(reader.pair(line, words[w], "a step"));
          if (std::abs(steps.back().x()) >= p.columns || std::abs(steps.back().y()) >= p.rows) reader.fail(line, words[w], "a step longer than the grid");
        }
        const int n = reader.times(line, words.back());
        t.points.push_back(at);
        for (int k = 0; k < n; ++k) t.points.push_back(at += steps[k % steps.size()]);
      }
      check_on_grid(reader, p, t, line, "");
      add_stitches(static_cast<long>(t.points.size()) - 1, line);
      p.threads.push_back(std::move(t));
    } else if (key == "bead") {
      // bead C,R C,R MM: a bead on the stitch between the two points (Zhou §5.2).
      arguments(3, "bead C,R C,R DIAMETER_MM");
      Bead b;
      b.a = reader.pair(line, words[1], "a grid point");
      b.b = reader.pair(line, words[2], "a grid point");
      b.diameter = reader.number(line, words[3], "the bead's diameter in mm");
      if (!(b.diameter > 0 && b.diameter <= 1000)) reader.fail(line, words[3], "a bead's diameter of more than 0 and at most 1000 mm, found " + words[3].text);
      b.line = line;
      p.beads.push_back(b);
    } else if (key == "repeat") {
      // repeat DC,DR xN: every thread so far, N times in all, each copy shifted by DC,DR from the one before.
      arguments(2, "repeat DC,DR xN");
      if (p.threads.empty()) reader.fail(line, words[0], "nothing to repeat yet: write a path or walk first");
      const Eigen::Vector2i shift = reader.pair(line, words[1], "the shift");
      if (std::abs(shift.x()) >= p.columns || std::abs(shift.y()) >= p.rows) reader.fail(line, words[1], "a shift longer than the grid");
      if (shift.isZero()) reader.fail(line, words[1], "a shift of 0,0 puts every copy on top of the one before");
      const int n = reader.times(line, words[2]);
      const std::vector<Thread> unit = p.threads;
      const std::vector<Bead> unit_beads = p.beads;
      const int unit_stitches = p.num_stitches();
      for (int c = 1; c < n; ++c) {
        add_stitches(unit_stitches, line);
        for (const auto& u : unit) {
          Thread t = u;
          for (auto& q : t.points) q += c * shift;
          check_on_grid(reader, p, t, line, "copy " + std::to_string(c + 1) + " of the thread of line " + std::to_string(u.line) + ": ");
          p.threads.push_back(std::move(t));
        }
        for (auto b : unit_beads) b.a += c * shift, b.b += c * shift, p.beads.push_back(b);
      }
    } else {
      reader.fail(line, words[0], "unknown keyword \"" + key + "\" (expected style, grid, spacing, gamma, path, walk, bead or repeat)");
    }
  }
  if (format_line == 0) throw Error(source, "", "empty: expected \"format smocking\", a grid and at least one thread (docs/smocking.md)");
  if (!grid_line) throw Error(source, "", "no grid: expected \"grid COLUMNS ROWS\"");
  if (p.threads.empty()) throw Error(source, "", "no thread: expected at least one path or walk");
  check_threads(p, source);
  return p;
}

SmockingPattern read_smocking_pattern(const std::filesystem::path& file) {
  check_input_file(file, 4u << 20);  // a smocking pattern is a few lines of text
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string(), "", "cannot be opened for reading");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_smocking_pattern(text.str(), file.string());
}

}  // namespace skein::smocking
