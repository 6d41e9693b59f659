#include "stitchmesh/chart_pattern.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <tuple>
#include <sstream>
#include <vector>

#include "common/error.hpp"
#include "common/text.hpp"
#include "stitchmesh/stitch_types.hpp"
#include "stitchmesh/written_pattern.hpp"

namespace skein::mesh {
namespace {

constexpr size_t kLongestLine = 4096;

/// What a symbol means: the stitch worked on a right-side row and on a wrong-side row (written abbreviations;
/// empty: none), and how many cells it is drawn over (a cable's stitches, else 1).
struct Symbol {
  std::string right, wrong;
  int cells = 1;
  bool no_stitch = false;
};

/// The cells a symbol is drawn over: one a stitch on the needle after the row. A cable: C4F, T3B (N), 2/2 LC,
/// 1/2 RPC (a + b); an increase into one stitch: kfb, pfb (2), "(k1, p1, k1) in next st" (one a stitch in the
/// group); 1 for the rest (a "C0B" too: the written reader then says which cables have models). Never 0, which
/// would draw it over nothing.
int cells_of(const std::string& abbreviation) {
  static const std::regex single(R"(^[ct]([1-9])[fb]$)", std::regex::icase), split(R"(^([1-9])\s*/\s*([1-9])\s*(?:lc|rc|lt|rt|lpc|rpc)$)", std::regex::icase),
      front_back(R"(^[kp]fb$)", std::regex::icase), into_one(R"(^[(\[]([^)\]]*)[)\]]\s*(?:all\s+)?in(?:to)?\s+(?:the\s+)?(?:next|same)\s+(?:st|stitch)$)", std::regex::icase);
  std::smatch m;
  if (std::regex_match(abbreviation, m, single)) return m[1].str()[0] - '0';
  if (std::regex_match(abbreviation, m, split)) return (m[1].str()[0] - '0') + (m[2].str()[0] - '0');
  if (std::regex_match(abbreviation, front_back)) return 2;
  if (std::regex_match(abbreviation, m, into_one)) {
    const std::string group = m[1].str();
    return std::min(9, 1 + static_cast<int>(std::count(group.begin(), group.end(), ',')));
  }
  return 1;
}

/// The Craft Yarn Council's chart symbols: in ASCII, and as charts print them in Unicode (UTF-8): a dot for
/// purl, a ring for a yarn-over, an inverted V for a centred double decrease, a filled square for no stitch.
std::map<std::string, Symbol> default_key() {
  return {{".", {"k", "p"}},           {"|", {"k", "p"}},           {"-", {"p", "k"}},        {"o", {"yo", "yo"}},
          {"O", {"yo", "yo"}},         {"/", {"k2tog", "p2tog"}},   {"\\", {"ssk", "ssp"}},    {"v", {"sl1 wyib", "sl1 wyif"}},
          {"V", {"sl1 wyib", "sl1 wyif"}}, {"t", {"k1 tbl", ""}},   {"^", {"sk2p", ""}},      {"x", {"", "", 1, true}},
          {"\u25A1", {"k", "p"}},  // □ white square: a blank cell
          {"\u2022", {"p", "k"}},  // • bullet
          {"\u25CF", {"p", "k"}},  // ● black circle
          {"\u2013", {"p", "k"}},  // – en dash
          {"\u2212", {"p", "k"}},  // − minus sign
          {"\u25CB", {"yo", "yo"}},  // ○ white circle
          {"\u25EF", {"yo", "yo"}},  // ◯ large circle
          {"\u2227", {"sk2p", ""}},  // ∧ logical and
          {"\u039B", {"sk2p", ""}},  // Λ Greek capital lambda
          {"\u2228", {"sl1 wyib", "sl1 wyif"}},  // ∨ logical or
          {"\u25A0", {"", "", 1, true}}};  // ■ black square
}

std::string key_symbols(const std::map<std::string, Symbol>& key) {
  std::string out;
  for (const auto& [c, s] : key) out += (out.empty() ? "" : " ") + c;
  return out;
}

/// The length in bytes of the UTF-8 character that starts at text[i] (1 for ASCII), or 0 when the bytes there
/// are not one.
size_t utf8_length(const std::string& text, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  const size_t n = lead < 0x80 ? 1 : lead >= 0xC2 && lead <= 0xDF ? 2 : lead >= 0xE0 && lead <= 0xEF ? 3 : lead >= 0xF0 && lead <= 0xF4 ? 4 : 0;
  if (n == 0 || i + n > text.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  return n;
}

/// One chart row as drawn: its cells (symbol, 1-based column) left to right, its line, its number if written.
struct ChartRow {
  std::vector<std::pair<std::string, int>> cells;  ///< each symbol one UTF-8 character
  int line = 0, number = 0;
};

/// A row of the written instructions a chart row makes, with the chart column of each stitch in it.
struct MadeRow {
  std::string text;
  std::vector<std::pair<int, int>> columns;  ///< (column in `text` where a stitch starts, its cell's chart column)
  int chart_line = 0;
};

/// A chart turned into written instructions: one made row per chart row, bottom first, and the chart's
/// "# name:" and "# source:" lines.
struct ChartReading {
  std::vector<MadeRow> made;
  std::vector<std::string> comments;
};
ChartReading read_chart(const std::string& text, const std::string& source);

/// The written instructions of a chart reading, as the written reader takes them.
std::string written_text(const ChartReading& reading) {
  std::string written;
  for (const auto& c : reading.comments) written += c + "\n";
  for (const auto& m : reading.made) written += m.text + "\n";
  return written;
}

}  // namespace

bool is_chart_pattern(const std::string& text) {
  std::istringstream in(text);
  static const std::regex format(R"(^\s*format\s+chart(\s+(flat|round))?\s*$)", std::regex::icase);
  for (std::string line; std::getline(in, line);) {
    if (line.size() > kLongestLine) return false;
    const std::string content = trim(line.substr(0, line.find('#')));
    if (content.empty()) continue;
    return std::regex_match(content, format);
  }
  return false;
}

namespace {
ChartReading read_chart(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  auto key = default_key();
  bool round = false, started = false;
  std::vector<ChartRow> drawn;  // top line first
  std::vector<std::string> comments;  // "# name:" and "# source:" lines, for the written reader
  int line_no = 0;
  const auto at = text_place;
  LineReader reader(in, source, kLongestLine);
  while (reader.next()) {
    line_no = reader.number();
    const std::string& raw = reader.line();
    const auto hash = comment_start(raw);
    if (hash != std::string::npos) {
      const std::string c = trim(raw.substr(hash + 1));
      if (c.rfind("name:", 0) == 0 || c.rfind("source:", 0) == 0) comments.push_back("# " + c);
    }
    const std::string line = raw.substr(0, hash);
    const std::string content = trim(line);
    if (content.empty()) continue;
    std::string lowered = content;
    std::transform(lowered.begin(), lowered.end(), lowered.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (!started) {
      if (lowered.rfind("format", 0) != 0) throw Error(source, at(line_no, 0), "expected 'format chart' (or 'format chart round') first");
      round = lowered.find("round") != std::string::npos;
      started = true;
      continue;
    }
    static const std::regex cast_on(R"(^cast\s+on\s+\d+\s*(?:sts|stitches)\.?$)", std::regex::icase);
    if (std::regex_match(content, cast_on)) {
      // "cast on 12 sts": a shaped piece, knitted once as drawn (written_pattern.hpp); passed on to the written reader.
      if (!drawn.empty()) throw Error(source, at(line_no, 0), "'cast on' after the chart's rows: give it first");
      comments.push_back(content);
      continue;
    }
    if (read_colour_declaration(content, false, 0, source, at(line_no, 0))) {
      // "colour B: red #b3261e": passed on to the written reader, which keeps the palette; a key gives the
      // colour's stitches ("key X k1 B / p1 B").
      if (!drawn.empty()) throw Error(source, at(line_no, 0), "a colour declaration after the chart's rows: declare the colours first");
      comments.push_back(content);
      continue;
    }
    if (lowered.rfind("key ", 0) == 0 || lowered.rfind("key\t", 0) == 0) {
      // "key C C4F", "key t k1 tbl / p1 tbl", "key x no stitch": a symbol and its stitch, right side / wrong side.
      if (!drawn.empty()) throw Error(source, at(line_no, 0), "a key line after the chart's rows: give the key first");
      const std::string rest = trim(content.substr(4));
      const size_t length = rest.empty() ? 0 : utf8_length(rest, 0);
      if (rest.size() < length + 2 || length == 0 || std::isspace(static_cast<unsigned char>(rest[0])) ||
          !std::isspace(static_cast<unsigned char>(rest[length])))
        throw Error(source, at(line_no, 0), "expected 'key SYMBOL STITCH' with a one-character symbol (e.g. 'key C C4F')");
      const std::string symbol = rest.substr(0, length);
      if (length == 1 && (std::isdigit(static_cast<unsigned char>(symbol[0])) || static_cast<unsigned char>(symbol[0]) < 33 || symbol[0] == 127))
        throw Error(source, at(line_no, 0), "a chart symbol is one printable character other than a digit (digits number the rows)");
      const std::string meaning = trim(rest.substr(length));
      Symbol s;
      if (meaning == "no stitch") {
        s.no_stitch = true;
      } else {
        const auto slash = meaning.find(" / ");
        s.right = trim(meaning.substr(0, slash));
        s.wrong = slash == std::string::npos ? "" : trim(meaning.substr(slash + 3));
        s.cells = cells_of(s.right);
      }
      key[symbol] = s;
      continue;
    }
    // A row of the grid: one character a cell, spaces between them or not, its row number at either end.
    ChartRow row;
    row.line = line_no;
    int column = 0;  // characters, not bytes
    for (size_t i = 0; i < line.size(); i += utf8_length(line, i)) {
      ++column;
      const size_t length = utf8_length(line, i);
      if (length == 0) throw Error(source, at(line_no, column), "is not UTF-8 text here: a chart cell is one character (ASCII or UTF-8)");
      const std::string c = line.substr(i, length);
      if (c == " " || c == "\t" || c == "\r") continue;
      if (std::isdigit(static_cast<unsigned char>(c[0]))) {
        size_t j = i;
        while (j < line.size() && std::isdigit(static_cast<unsigned char>(line[j]))) ++j;
        const bool first = row.cells.empty(), last = trim(line.substr(j)).empty();
        if ((!first && !last) || row.number > 0 || j - i > 6)
          throw Error(source, at(line_no, column), "a number inside a chart row: row numbers go at its start or its end");
        row.number = std::stoi(line.substr(i, j - i));
        column += static_cast<int>(j - i) - 1;
        i = j - 1;  // the loop steps past the last digit
        continue;
      }
      if (!key.count(c))
        throw Error(source, at(line_no, column),
                    "'" + c + "' is not in the chart's key (" + key_symbols(key) + "; add 'key " + c + " STITCH' above the chart)");
      row.cells.emplace_back(c, column);
    }
    if (row.cells.empty()) throw Error(source, at(line_no, 0), "a chart row with no cells");
    drawn.push_back(row);
  }
  if (!started) throw Error(source, "", "holds no chart: expected 'format chart' and rows of symbols");
  if (drawn.empty()) throw Error(source, "", "holds no chart rows");

  // Each row as a knitter reads it: right-side rows right to left, wrong-side rows left to right.
  std::vector<MadeRow> made;
  const int rows = static_cast<int>(drawn.size());
  for (int r = 1; r <= rows; ++r) {
    const ChartRow& row = drawn[rows - r];
    if (row.number > 0 && row.number != r)
      throw Error(source, at(row.line, 0), "is numbered " + std::to_string(row.number) + " but is row " + std::to_string(r) + " (the bottom row is row 1)");
    const bool right_side = round || r % 2 == 1;
    MadeRow out;
    out.chart_line = row.line;
    out.text = round ? "Rnd " + std::to_string(r) + ": " : "Row " + std::to_string(r) + (right_side ? " (RS): " : " (WS): ");
    std::vector<std::pair<std::string, int>> cells = row.cells;
    if (right_side) std::reverse(cells.begin(), cells.end());
    bool any = false;
    for (size_t i = 0; i < cells.size();) {
      const auto [c, column] = cells[i];
      const Symbol& s = key.at(c);
      size_t run = 1;
      if (s.cells > 1) {
        while (i + run < cells.size() && cells[i + run].first == c) ++run;
        if (run % s.cells != 0)
          throw Error(source, at(row.line, std::min(column, cells[i + run - 1].second)),
                      std::string("'") + c + "' is " + s.right + ", drawn over " + std::to_string(s.cells) + " cells, but here over " + std::to_string(run));
      }
      for (size_t k = 0; k < run; k += static_cast<size_t>(s.cells)) {
        if (s.no_stitch) continue;
        const std::string stitch = right_side ? s.right : s.wrong;
        if (stitch.empty())
          throw Error(source, at(row.line, cells[i + k].second),
                      std::string("'") + c + "' (" + s.right + ") on a wrong-side row: the key gives it no wrong-side stitch (key " + c + " RS / WS)");
        if (any) out.text += ", ";
        // The chart column of a cable is its leftmost cell's.
        const int chart_column = right_side ? cells[i + k + static_cast<size_t>(s.cells) - 1].second : cells[i + k].second;
        out.columns.emplace_back(static_cast<int>(out.text.size()) + 1, chart_column);
        out.text += stitch;
        any = true;
      }
      i += run;
    }
    if (!any) throw Error(source, at(row.line, 0), "a chart row of 'no stitch' cells only");
    out.text += ".";
    made.push_back(out);
  }
  return {std::move(made), std::move(comments)};
}
}  // namespace

Pattern parse_chart_pattern(const std::string& text, const std::string& source) {
  const ChartReading reading = read_chart(text, source);
  const auto& made = reading.made;
  const int rows = static_cast<int>(made.size());
  const auto at = text_place;
  // The written instructions, read as written; their errors placed back on the chart.
  const int first_row_line = static_cast<int>(reading.comments.size()) + 1;
  try {
    return parse_written_pattern(written_text(reading), source);
  } catch (const Error& e) {
    static const std::regex place(R"(^line (\d+)(?:, column (\d+))?$)"), mention(R"(\(line (\d+)\))");
    const auto chart_place = [&](int line, int column) {
      const int r = line - first_row_line;
      if (r < 0 || r >= rows) return std::pair{0, 0};
      int chart_column = 0;
      for (const auto& [from, to] : made[r].columns)
        if (from <= column) chart_column = to;
      return std::pair{made[r].chart_line, column > 0 ? chart_column : 0};
    };
    std::smatch m;
    std::string where = e.place();
    if (std::regex_match(where, m, place)) {
      const auto [line, column] = chart_place(std::stoi(m[1].str()), m[2].matched ? std::stoi(m[2].str()) : 0);
      if (line > 0) where = at(line, column);
    }
    std::string rule = e.rule(), mapped;
    auto from = rule.cbegin();
    for (std::sregex_iterator it(rule.begin(), rule.end(), mention), end; it != end; ++it) {
      const int line = chart_place(std::stoi((*it)[1].str()), 0).first;
      mapped.append(from, (*it)[0].first) += line > 0 ? "(line " + std::to_string(line) + ")" : (*it)[0].str();
      from = (*it)[0].second;
    }
    mapped.append(from, rule.cend());
    throw Error(source, where, mapped);
  }
}

namespace {

/// The chart cells of a stitch type as seen from the front, left to right, in the symbols write_chart uses
/// (the default key, and the keys kWrittenKeys adds); "" when a chart cannot say it yet.
std::string cells_of_type(const std::string& type) {
  static const std::map<std::string, std::string> cells = {{"k", "."},   {"p", "-"},    {"x", "t"},    {"s", "v"},     {"sk", "w"},
                                                           {"d12k", "/"}, {"d21k", "\\"}, {"d12p", ")"}, {"d21p", "("},
                                                           {"ys", "o\\"}, {"2u", "/o"},   {"y3y", "o^o"},
                                                           {"ky", ".o"},  {"yk", "o."},   {"py", "-o"},  {"yp", "o-"},   {"yky", "o.o"}, {"ypy", "o-o"},
                                                           {"d123k", "{"}, {"d321k", "}"}, {"d123p", "<"}, {"d321p", ">"}, {"q", "%"}};
  const auto it = cells.find(type);
  return it == cells.end() ? "" : it->second;
}

/// The keys write_chart gives the symbols the Craft Yarn Council's key lacks (or means on right-side rows
/// only), each with its wrong-side stitch so that a flat chart reads them on either side.
const std::vector<std::pair<char, std::string>> kWrittenKeys = {
    {'t', "k1 tbl / p1 tbl"}, {'%', "p1 tbl / k1 tbl"}, {'w', "sl1 wyif / sl1 wyib"}, {')', "p2tog / k2tog"}, {'(', "ssp / ssk"},
    {'{', "k3tog / p3tog"},   {'}', "sssk / sssp"},     {'<', "p3tog / k3tog"},       {'>', "sssp / sssk"}};

/// An increase face worked into one stitch (Yuksel 2012 Table 1; kp, xk, kpk, kyk, ...: its loops named from the
/// front, left to right) as the written reader takes it on a right-side and a wrong-side row: kfb and pfb where
/// they mean it, else "(k1, yo, k1) in next st" (a right-side row is worked right to left; a wrong-side row left
/// to right, its knits purls). Empty strings for other types.
std::pair<std::string, std::string> into_one_meaning(const std::string& type) {
  const StitchType* t = find_stitch_type(type);
  if (!t || t->bottom != 1 || t->top < 2 || type.find_first_not_of("kpyxq") != std::string::npos) return {};
  static const std::map<char, std::pair<const char*, const char*>> kWorked = {
      {'k', {"k1", "p1"}}, {'p', {"p1", "k1"}}, {'y', {"yo", "yo"}}, {'x', {"k1 tbl", "p1 tbl"}}, {'q', {"p1 tbl", "k1 tbl"}}};
  const auto group = [&](bool right_side) {
    if (type == (right_side ? "xk" : "pq")) return std::string("kfb");
    if (type == (right_side ? "qp" : "kx")) return std::string("pfb");
    std::string loops = type, out;
    if (right_side) std::reverse(loops.begin(), loops.end());
    for (char c : loops) out += (out.empty() ? "(" : ", ") + std::string(right_side ? kWorked.at(c).first : kWorked.at(c).second);
    return out + ") in next st";
  };
  return {group(true), group(false)};
}

/// The symbols write_chart draws increases worked into one stitch with, one a kind, each keyed.
const std::string kIntoOneSymbols = "+*=&$@?~;:";

/// The decrease's cell of one of Leaf's lace faces (a yarn-over beside the decrease that pays for it: ys, 2u,
/// and garter lace's ysp, 2up); 0 for other types.
char lace_decrease(const std::string& type) {
  if (type == "ys") return '\\';
  if (type == "2u") return '/';
  if (type == "ysp") return '(';
  if (type == "2up") return ')';
  return 0;
}

/// Each lace face's cells in a row as seen from the front, in an order the written reader pairs back into the
/// same faces: it pairs a yarn-over with the decrease beside it first come, first served in working order, so a
/// face worked right after a decrease is drawn decrease first (else that decrease would take its yarn-over).
/// Empty strings for the row's other faces.
std::vector<std::string> lace_cells(const std::vector<std::string>& row, bool right_side) {
  std::vector<std::string> out(row.size());
  bool after_decrease = false;
  for (size_t k = 0; k < row.size(); ++k) {
    const size_t f = right_side ? row.size() - 1 - k : k;  // working order
    const char decrease = lace_decrease(row[f]);
    if (!decrease) {
      after_decrease = row[f][0] == 'd';
      continue;
    }
    std::string worked = after_decrease ? std::string{decrease, 'o'} : std::string{'o', decrease};
    after_decrease = worked.back() == decrease;
    if (right_side) std::reverse(worked.begin(), worked.end());
    out[f] = worked;
  }
  return out;
}

/// A cable as the written reader names it: CnB / CnF half over half, else A/B RC or A/B LC; a travelling cable
/// (the stitches that crossed behind purled) T2, T3, T4 B/F where the Craft Yarn Council has the name (1 knit over
/// 1 purl, 2 over 1, 2 over 2), else A/B RPC or A/B LPC, A the stitches in front.
std::string cable_abbreviation(const PatternCable& c, bool purl_behind) {
  if (purl_behind) {
    const int front = c.order > 0 ? c.over : c.under, behind = c.order > 0 ? c.under : c.over;
    if ((front == 1 && behind == 1) || (front == 2 && (behind == 1 || behind == 2))) return "T" + std::to_string(front + behind) + (c.order > 0 ? "B" : "F");
    return std::to_string(front) + "/" + std::to_string(behind) + (c.order > 0 ? " RPC" : " LPC");
  }
  if (c.over == c.under) return "C" + std::to_string(2 * c.over) + (c.order > 0 ? "B" : "F");
  return c.order > 0 ? std::to_string(c.over) + "/" + std::to_string(c.under) + " RC" : std::to_string(c.under) + "/" + std::to_string(c.over) + " LC";
}

/// A symbol's stitch on the right and the wrong side, as the default key and kWrittenKeys give it.
std::pair<std::string, std::string> symbol_meaning(char symbol) {
  for (const auto& [c, meaning] : kWrittenKeys)
    if (c == symbol) return {meaning.substr(0, meaning.find(" / ")), meaning.substr(meaning.find(" / ") + 3)};
  const auto key = default_key();
  const Symbol& s = key.at(std::string(1, symbol));
  return {s.right, s.wrong};
}

std::string chart_text(const Pattern& pattern, bool round) {
  std::vector<std::string> grid(pattern.rows.size());
  std::set<char> used;
  // A stitch in a colour other than the first: a symbol of its own, keyed as the stitch in that colour
  // ("key a k B / p B"), from these letters (the default key's and the written keys' left out).
  static const std::string kColourSymbols = "abcdefghijklmnpqrsuyz";
  std::map<std::pair<char, int>, char> coloured;
  std::map<std::string, char> into_one;  // increase type -> its symbol
  for (size_t r = 0; r < pattern.rows.size(); ++r) {
    const std::vector<std::string> lace = lace_cells(pattern.rows[r], round || r % 2 == 0);
    for (size_t f = 0; f < pattern.rows[r].size(); ++f) {
      const std::string& type = pattern.rows[r][f];
      std::string cells = lace[f].empty() ? cells_of_type(type) : lace[f];
      if (cells.empty() && !into_one_meaning(type).first.empty()) {
        auto [it, added] = into_one.try_emplace(type, '\0');
        if (added) {
          if (into_one.size() > kIntoOneSymbols.size())
            throw Error("", "row " + std::to_string(r + 1), "more than " + std::to_string(kIntoOneSymbols.size()) + " kinds of increase into one stitch for one chart");
          it->second = kIntoOneSymbols[into_one.size() - 1];
        }
        if (!pattern.colours.empty() && pattern.colours[r][f] != 0)
          throw Error("", "row " + std::to_string(r + 1) + ", stitch " + std::to_string(f + 1),
                      "an increase into one stitch in a colour other than the first (" + pattern.palette[0].name + ") has no chart symbol yet");
        grid[r] += std::string(static_cast<size_t>(find_stitch_type(type)->top), it->second);
        continue;
      }
      if (cells.empty())
        throw Error("", "row " + std::to_string(r + 1) + ", stitch " + std::to_string(f + 1),
                    "stitch type '" + type + "' has no chart symbol yet (charts hold k, p, k1 tbl, p1 tbl, slips, two- and three-into-one decreases, increases into one stitch, yarn-overs beside a knit or purl, Leaf's yo pairs and cables)");
      used.insert(cells.begin(), cells.end());
      const int colour = pattern.colours.empty() ? 0 : pattern.colours[r][f];
      if (colour > 0)
        for (char& cell : cells) {
          auto [it, added] = coloured.try_emplace({cell, colour}, '\0');
          if (added) {
            if (coloured.size() > kColourSymbols.size())
              throw Error("", "row " + std::to_string(r + 1), "more than " + std::to_string(kColourSymbols.size()) + " stitches in colours for one chart");
            it->second = kColourSymbols[coloured.size() - 1];
          }
          cell = it->second;
        }
      grid[r] += cells;
    }
  }
  // Cables over their cells, a symbol each kind (C, D, E, ...).
  std::map<std::string, char> cable_symbol;
  for (const auto& c : pattern.cables) {
    if (!pattern.colours.empty()) {  // a cable's cells hold its symbol: no room for a colour
      int loop = 0;
      for (size_t f = 0; f < pattern.rows[static_cast<size_t>(c.row)].size(); ++f) {
        if (loop >= c.first_loop && loop < c.first_loop + c.over + c.under && pattern.colours[static_cast<size_t>(c.row)][f] != 0)
          throw Error("", "row " + std::to_string(c.row + 1) + ", loop " + std::to_string(c.first_loop + 1),
                      "a cable in a colour other than the first (" + pattern.palette[0].name + ") has no chart symbol yet");
        loop += find_stitch_type(pattern.rows[static_cast<size_t>(c.row)][f])->top;
      }
    }
    const int n = c.over + c.under;
    std::string& row = grid.at(static_cast<size_t>(c.row));
    const std::string drawn = c.first_loop < 0 || c.first_loop + n > static_cast<int>(row.size()) ? "" : row.substr(static_cast<size_t>(c.first_loop), static_cast<size_t>(n));
    // Crossed, the `under` loops lie on the left and the `over` loops on the right; a travelling cable purls the
    // ones that went behind (the written reader's append_row).
    const std::string knits(static_cast<size_t>(n), '.'),
        travelling = c.order > 0 ? std::string(static_cast<size_t>(c.under), '-') + std::string(static_cast<size_t>(c.over), '.')
                                 : std::string(static_cast<size_t>(c.under), '.') + std::string(static_cast<size_t>(c.over), '-');
    if (drawn != knits && drawn != travelling)
      throw Error("", "row " + std::to_string(c.row + 1) + ", loop " + std::to_string(c.first_loop + 1),
                  "a cable over stitches other than knits (or knits crossing purls behind them) has no chart symbol yet");
    const std::string name = cable_abbreviation(c, drawn != knits);
    if (!cable_symbol.count(name)) {
      if (cable_symbol.size() >= 20) throw Error("", "row " + std::to_string(c.row + 1), "more than 20 kinds of cable for one chart");
      cable_symbol[name] = static_cast<char>('C' + cable_symbol.size());
    }
    row.replace(static_cast<size_t>(c.first_loop), static_cast<size_t>(n), static_cast<size_t>(n), cable_symbol[name]);
  }
  // A shaped piece's rows, each as wide as its stitches, centred between 'no stitch' cells.
  if (pattern.whole) {
    size_t widest = 0;
    for (const auto& row : grid) widest = std::max(widest, row.size());
    for (auto& row : grid) {
      const size_t left = (widest - row.size() + 1) / 2;
      row = std::string(left, 'x') + row + std::string(widest - row.size() - left, 'x');
    }
  }
  std::ostringstream out;
  out << "# name: " << pattern.name << "\n";
  if (!pattern.note.empty()) out << "# source: " << pattern.note << "\n";
  out << "# the fabric from the right side, row 1 at the bottom (patterns/FORMAT.md, \"Charts\"); written by skein\n";
  out << (round ? "format chart round" : "format chart") << "\n";
  if (pattern.whole) out << "cast on " << loops_taken(pattern.rows.front()) << " sts\n";
  for (const auto& c : pattern.palette)
    out << "colour " << c.name << (c.alias.empty() ? "" : " (" + c.alias + ")") << ": " << (c.description.empty() ? "" : c.description + " ") << colour_code(c.srgb) << "\n";
  for (const auto& [symbol, meaning] : kWrittenKeys)
    if (used.count(symbol)) out << "key " << symbol << " " << meaning << "\n";
  for (const auto& [cell, symbol] : coloured) {
    const auto [right, wrong] = symbol_meaning(cell.first);
    const std::string& name = pattern.palette[static_cast<size_t>(cell.second)].name;
    out << "key " << symbol << " " << right << " " << name;
    if (!wrong.empty()) out << " / " << wrong << " " << name;
    out << "\n";
  }
  for (const auto& [name, symbol] : cable_symbol) out << "key " << symbol << " " << name << "\n";
  for (const auto& [type, symbol] : into_one) {
    const auto [right, wrong] = into_one_meaning(type);
    out << "key " << symbol << " " << right << " / " << wrong << "\n";
  }
  // Row numbers as printed charts place them: at the right of rows read from the right (every round, and a flat
  // chart's right-side rows), at the left of a flat chart's wrong-side rows, read from the left.
  const size_t digits = std::to_string(grid.size()).size();
  const std::string margin(round ? 0 : digits + 3, ' ');
  for (size_t r = grid.size(); r-- > 0;) {
    const std::string number = std::string(digits - std::to_string(r + 1).size(), ' ') + std::to_string(r + 1);
    std::string cells;
    for (size_t i = 0; i < grid[r].size(); ++i) cells += (i ? " " : "") + std::string(1, grid[r][i]);
    if (!round && r % 2 == 1) out << number << "   " << cells << "\n";
    else out << margin << cells << "   " << number << "\n";
  }
  return out.str();
}

bool same_stitches(const Pattern& a, const Pattern& b) {
  auto ca = a.cables, cb = b.cables;
  const auto order = [](const PatternCable& x, const PatternCable& y) { return std::tie(x.row, x.first_loop) < std::tie(y.row, y.first_loop); };
  std::sort(ca.begin(), ca.end(), order);
  std::sort(cb.begin(), cb.end(), order);
  return a.rows == b.rows && ca == cb && a.palette == b.palette && a.colours == b.colours && a.whole == b.whole;
}

}  // namespace

std::string write_chart_pattern(const Pattern& pattern) {
  if (pattern.format == PatternFormat::Woven) throw Error("", "chart", "a woven pattern has no knitting chart");
  // Flat (wrong-side rows read with their wrong-side stitches) where that reads back as the same stitches; else
  // read from the right side on every row: lace pairs and cables have models on right-side rows only.
  std::string why;
  for (const bool round : {false, true}) {
    const std::string text = chart_text(pattern, round);
    try {
      if (same_stitches(parse_chart_pattern(text, "chart"), pattern)) return text;
      why = "it reads back as other stitches";
    } catch (const Error& e) {
      why = e.what();
    }
  }
  throw Error("", "chart", "the chart skein draws for " + pattern.name + " does not read back as the pattern (" + why + ")");
}

std::string write_written_pattern(const Pattern& pattern) {
  const std::string chart = write_chart_pattern(pattern);
  ChartReading reading = read_chart(chart, "chart");
  // As books write them: runs of plain knits and purls counted (k, k, k → k3).
  static const std::regex prefix(R"(^((?:Row|Rnd) \d+(?: \([RW]S\))?: ))");
  for (size_t r = 0; r < reading.made.size(); ++r) {
    MadeRow& m = reading.made[r];
    std::smatch head;
    std::regex_search(m.text, head, prefix);
    std::vector<std::string> items;
    std::string rest = m.text.substr(static_cast<size_t>(head.length(0)));
    rest.pop_back();  // the final "."
    for (size_t from = 0;;) {
      const size_t comma = rest.find(", ", from);
      items.push_back(rest.substr(from, comma - from));
      if (comma == std::string::npos) break;
      from = comma + 2;
    }
    std::string text = head.str(0);
    // Plain knits and purls, also in a colour ("k B"), are counted: "k3 B".
    static const std::regex plain(R"(^(k|p)( \S+)?$)");
    for (size_t i = 0; i < items.size();) {
      size_t run = 1;
      std::smatch pm;
      const bool counted = std::regex_match(items[i], pm, plain);
      while (counted && i + run < items.size() && items[i + run] == items[i]) ++run;
      text += (i ? ", " : "") + (counted ? pm[1].str() + std::to_string(run) + pm[2].str() : items[i]);
      i += run;
    }
    m.text = text + ".";
    // A shaped piece's rows that change the count say so, as books do: "K1, kfb, k2. (5 sts)".
    const int made = loops_made(pattern.rows[r]);
    if (pattern.whole && made != loops_taken(pattern.rows[r])) m.text += " (" + std::to_string(made) + " sts)";
  }
  for (auto& c : reading.comments)  // the chart's "cast on 12 sts" as books write it
    if (c.rfind("cast on ", 0) == 0) c = "Cast on " + c.substr(8) + ".";
  reading.comments.push_back("# written instructions, by skein (patterns/FORMAT.md)");
  const std::string out = written_text(reading);
  if (!same_stitches(parse_written_pattern(out, "written instructions"), pattern))
    throw Error("", "written instructions", "the instructions skein writes for " + pattern.name + " do not read back as the pattern");
  return out;
}

}  // namespace skein::mesh
