#include "stitchmesh/wif_pattern.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>
#include <vector>

#include "common/error.hpp"
#include "common/text.hpp"

namespace skein::mesh {
namespace {

constexpr int kMostThreads = 10000;  // threads or picks of a draft: far past a loom's
constexpr int kLongestRepeat = 256;  // threads or picks of the repeat skein relaxes
constexpr long kMostCells = 4'000'000;  // threads x picks of the drawdown

std::string line_at(int line) { return text_place(line); }

/// One `key=value` line of a section.
struct Entry {
  std::string key, value;
  int line = 0;
};

/// The file's sections by lower-case name, each with its entries in order and the line of its header.
struct Sections {
  std::map<std::string, std::vector<Entry>> entries;
  std::map<std::string, int> header_line;

  const std::vector<Entry>* find(const std::string& name) const {
    const auto it = entries.find(name);
    return it == entries.end() ? nullptr : &it->second;
  }
  /// The value of `key` (lower case) in `section`, if given.
  const Entry* value(const std::string& section, const std::string& key) const {
    if (const auto* list = find(section))
      for (const auto& e : *list)
        if (lower(e.key) == key) return &e;
    return nullptr;
  }
};

Sections split_sections(const std::string& text, const std::string& source) {
  Sections s;
  std::istringstream in(text);
  std::string current;
  LineReader reader(in, source);
  while (reader.next()) {
    const int line_no = reader.number();
    const std::string line = trim(reader.line());
    if (line.empty() || line[0] == ';') continue;
    if (line[0] == '[') {
      if (line.back() != ']') throw Error(source, line_at(line_no), "a section header is [NAME], found '" + line + "'");
      current = lower(trim(line.substr(1, line.size() - 2)));
      if (s.header_line.count(current)) throw Error(source, line_at(line_no), "section [" + current + "] again (first on line " + std::to_string(s.header_line[current]) + ")");
      s.header_line[current] = line_no;
      s.entries[current];
      continue;
    }
    if (current.empty()) throw Error(source, line_at(line_no), "expected [WIF] first, found '" + line + "'");
    const auto eq = line.find('=');
    if (eq == std::string::npos) throw Error(source, line_at(line_no), "expected KEY=VALUE in section [" + current + "], found '" + line + "'");
    s.entries[current].push_back({trim(line.substr(0, eq)), trim(line.substr(eq + 1)), line_no});
  }
  return s;
}

/// A whole number from `low` to `high`, or an error naming what it counts.
int number(const std::string& text, int low, int high, const std::string& what, const std::string& source, int line) {
  int v = 0;
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || ptr != end)
    throw Error(source, line_at(line), "expected " + what + " as a whole number, found '" + text + "'");
  if (v < low || v > high)
    throw Error(source, line_at(line), what + " " + text + " is outside " + std::to_string(low) + " to " + std::to_string(high));
  return v;
}

/// A comma-separated list of numbers from 1 to `high` (0 or nothing: none).
std::set<int> number_list(const std::string& text, int high, const std::string& what, const std::string& source, int line) {
  std::set<int> out;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    item = trim(item);
    if (item.empty() || item == "0") continue;
    out.insert(number(item, 1, high, what, source, line));
  }
  return out;
}

/// A count from the section's key (e.g. [WEAVING] Shafts), or std::nullopt when the file does not give it.
std::optional<int> count(const Sections& s, const std::string& section, const std::string& key, const std::string& source) {
  const Entry* e = s.value(section, key);
  if (!e) return std::nullopt;
  return number(e->value, 1, kMostThreads, "[" + section + "] " + e->key, source, e->line);
}

/// `section`'s entries as index -> numbers: index from 1 to `indices`, each number from 1 to `high`.
std::map<int, std::set<int>> table(const Sections& s, const std::string& section, int indices, int high, const std::string& index_name,
                                   const std::string& value_name, const std::string& source) {
  std::map<int, std::set<int>> out;
  for (const auto& e : *s.find(section)) {
    const int index = number(e.key, 1, indices, "[" + section + "] " + index_name, source, e.line);
    if (out.count(index)) throw Error(source, line_at(e.line), "[" + section + "] gives " + index_name + " " + e.key + " twice");
    out[index] = number_list(e.value, high, value_name, source, e.line);
  }
  return out;
}

/// The largest index an index table uses (for a file that does not give its thread or pick count).
int largest_index(const Sections& s, const std::string& section, const std::string& index_name, const std::string& source) {
  int most = 0;
  for (const auto& e : *s.find(section)) most = std::max(most, number(e.key, 1, kMostThreads, "[" + section + "] " + index_name, source, e.line));
  return most;
}

bool truthy(const std::string& v) {
  const std::string l = lower(v);
  return l == "true" || l == "yes" || l == "on" || l == "1";
}

/// The [COLOR TABLE]'s colours by index (sRGB 0..1), each `R,G,B` on the [COLOR PALETTE]'s Range (0,255 unless
/// it says otherwise); empty when the draft has no table.
std::map<int, std::array<double, 3>> wif_colours(const Sections& s, const std::string& source) {
  std::map<int, std::array<double, 3>> out;
  const auto* list = s.find("color table");
  if (!list) return out;
  int low = 0, high = 255;
  if (const Entry* range = s.value("color palette", "range")) {
    const auto comma = range->value.find(',');
    if (comma == std::string::npos) throw Error(source, line_at(range->line), "[COLOR PALETTE] Range is LOW,HIGH (0,255), found '" + range->value + "'");
    low = number(trim(range->value.substr(0, comma)), 0, 65535, "[COLOR PALETTE] Range's low end", source, range->line);
    high = number(trim(range->value.substr(comma + 1)), low + 1, 65535, "[COLOR PALETTE] Range's high end", source, range->line);
  }
  for (const auto& e : *list) {
    const int index = number(e.key, 1, kMostThreads, "[COLOR TABLE] colour", source, e.line);
    std::vector<std::string> parts;
    std::istringstream in(e.value);
    for (std::string part; std::getline(in, part, ',');) parts.push_back(trim(part));
    if (parts.size() != 3) throw Error(source, line_at(e.line), "[COLOR TABLE] colour " + e.key + " is R,G,B, found '" + e.value + "'");
    std::array<double, 3> rgb{};
    for (size_t k = 0; k < 3; ++k)
      rgb[k] = (number(parts[k], low, high, "[COLOR TABLE] colour " + e.key + "'s channel", source, e.line) - low) / double(high - low);
    if (out.count(index)) throw Error(source, line_at(e.line), "[COLOR TABLE] gives colour " + e.key + " twice");
    out[index] = rgb;
  }
  return out;
}

/// The smallest p such that every element equals the one p further on (the repeat of a draft, its last repeat
/// possibly cut short): n less the longest proper prefix that is also a suffix (Knuth-Morris-Pratt), in O(n)
/// comparisons of elements.
template <class Seq> int smallest_period(const Seq& seq) {
  const int n = static_cast<int>(seq.size());
  std::vector<int> border(n, 0);
  for (int i = 1; i < n; ++i) {
    int k = border[i - 1];
    while (k > 0 && !(seq[i] == seq[k])) k = border[k - 1];
    border[i] = seq[i] == seq[k] ? k + 1 : 0;
  }
  return n == 0 ? 0 : n - border[n - 1];
}

}  // namespace

bool is_wif_pattern(const std::string& text) {
  std::istringstream in(text);
  std::string raw;
  bool first = true;
  while (std::getline(in, raw)) {
    if (first && raw.rfind("\xEF\xBB\xBF", 0) == 0) raw = raw.substr(3);
    first = false;
    const std::string line = trim(raw);
    if (line.empty() || line[0] == ';') continue;
    return lower(line) == "[wif]";
  }
  return false;
}

Pattern parse_wif_pattern(const std::string& text, const std::string& source) {
  const Sections s = split_sections(text, source);
  Pattern p;
  p.format = PatternFormat::Woven;
  p.name = std::filesystem::path(source).stem().string();
  if (const Entry* title = s.value("text", "title"); title && !title->value.empty()) p.name = title->value;
  if (const Entry* program = s.value("wif", "source program"); program && !program->value.empty()) p.note = "a WIF draft from " + program->value;

  if (!s.find("threading")) throw Error(source, "", "has no [THREADING] section: a WIF draft needs one to say which shafts carry which warp threads");
  const bool lift_plan = s.find("liftplan") != nullptr;
  if (!lift_plan && !(s.find("tieup") && s.find("treadling")))
    throw Error(source, "", "has neither a [LIFTPLAN] nor a [TIEUP] with a [TREADLING] section: nothing says which shafts rise on each pick");

  const int shafts = count(s, "weaving", "shafts", source).value_or(kMostThreads);
  const int warps = count(s, "warp", "threads", source).value_or(largest_index(s, "threading", "thread", source));
  const std::string pick_table = lift_plan ? "liftplan" : "treadling";
  const int picks = count(s, "weft", "threads", source).value_or(largest_index(s, pick_table, "pick", source));
  if (warps == 0) throw Error(source, "line " + std::to_string(s.header_line.at("threading")), "[THREADING] threads no warp thread");
  if (picks == 0) throw Error(source, "line " + std::to_string(s.header_line.at(pick_table)), "[" + pick_table + "] gives no pick");

  if (static_cast<long>(warps) * picks > kMostCells)
    throw Error(source, "", "the draft is " + std::to_string(warps) + " threads x " + std::to_string(picks) + " picks; skein weaves drafts of up to " +
                                std::to_string(kMostCells) + " cells");
  const auto threading = table(s, "threading", warps, shafts, "thread", "shaft", source);
  std::vector<std::set<int>> tied(picks);  // per pick, the shafts its tie-up moves: up in a rising shed, down in a sinking one
  if (lift_plan) {
    for (const auto& [pick, shafts_moved] : table(s, "liftplan", picks, shafts, "pick", "shaft", source)) tied[pick - 1] = shafts_moved;
  } else {
    const int treadles = count(s, "weaving", "treadles", source).value_or(kMostThreads);
    const auto tieup = table(s, "tieup", treadles, shafts, "treadle", "shaft", source);
    for (const auto& [pick, used] : table(s, "treadling", picks, treadles, "pick", "treadle", source))
      for (const int treadle : used)
        if (const auto it = tieup.find(treadle); it != tieup.end()) tied[pick - 1].insert(it->second.begin(), it->second.end());
  }
  const Entry* shed = s.value("weaving", "rising shed");
  const bool rising = !shed || truthy(shed->value);

  // The drawdown, pick 1 at the bottom: 1 where the weft lies over the warp, 0 where the warp thread is raised
  // (one of its shafts lifted; in a sinking shed, none of its shafts sunk). An unthreaded thread stays down.
  std::vector<std::vector<char>> over(picks, std::vector<char>(warps, 1));
  for (const auto& [thread, its_shafts] : threading) {
    if (its_shafts.empty()) continue;
    for (int pick = 0; pick < picks; ++pick) {
      const bool moved = std::any_of(its_shafts.begin(), its_shafts.end(), [&](int shaft) { return tied[pick].count(shaft) > 0; });
      if (moved == rising) over[pick][thread - 1] = 0;
    }
  }

  // Colours (issue 26): each thread's [WARP COLORS] / [WEFT COLORS] entry, else its section's Color=, an index
  // of the [COLOR TABLE]; 0 where the draft gives none.
  const auto colours = wif_colours(s, source);
  std::vector<int> warp_colour(warps, 0), weft_colour(picks, 0);
  for (const auto& [section, name, threads, out] : {std::tuple{"warp", "WARP", warps, &warp_colour}, std::tuple{"weft", "WEFT", picks, &weft_colour}}) {
    const int high = colours.empty() ? kMostThreads : colours.rbegin()->first;
    if (const Entry* e = s.value(section, "color")) std::fill(out->begin(), out->end(), number(e->value, 1, high, "[" + std::string(name) + "] Color", source, e->line));
    if (s.find(std::string(section) + " colors"))
      for (const auto& [thread, colour] : table(s, std::string(section) + " colors", threads, high, "thread", "colour", source))
        if (!colour.empty()) (*out)[thread - 1] = *colour.begin();
    for (const int c : *out)
      if (c > 0 && !colours.count(c))
        throw Error(source, "", "[" + std::string(name) + "] threads use colour " + std::to_string(c) + ", which the [COLOR TABLE] does not give");
  }

  // The smallest repeat up (rows) and across (columns), colours included (a colour order can repeat less often
  // than the weave).
  std::vector<std::pair<std::vector<char>, int>> rows(picks);
  for (int pick = 0; pick < picks; ++pick) rows[pick] = {over[pick], weft_colour[pick]};
  const int up = smallest_period(rows);
  std::vector<std::pair<std::vector<char>, int>> columns(warps, {std::vector<char>(up), 0});
  for (int t = 0; t < warps; ++t) {
    for (int pick = 0; pick < up; ++pick) columns[t].first[pick] = over[pick][t];
    columns[t].second = warp_colour[t];
  }
  const int across = smallest_period(columns);
  if (up > kLongestRepeat || across > kLongestRepeat)
    throw Error(source, "", "the draft's smallest repeat is " + std::to_string(across) + " threads x " + std::to_string(up) +
                                " picks; skein relaxes woven repeats up to " + std::to_string(kLongestRepeat) + " x " + std::to_string(kLongestRepeat));
  for (int pick = 0; pick < up; ++pick) p.over.emplace_back(over[pick].begin(), over[pick].begin() + across);
  if (std::any_of(warp_colour.begin(), warp_colour.end(), [](int c) { return c > 0; }) ||
      std::any_of(weft_colour.begin(), weft_colour.end(), [](int c) { return c > 0; })) {
    // The palette: the table's colours the repeat uses, in table order, named by their index; a thread of no
    // colour takes the first of them.
    std::set<int> used;
    for (int t = 0; t < across; ++t) used.insert(warp_colour[t]);
    for (int pick = 0; pick < up; ++pick) used.insert(weft_colour[pick]);
    used.erase(0);
    std::map<int, int> index;
    for (const int c : used) {
      index[c] = static_cast<int>(p.palette.size());
      p.palette.push_back({"C" + std::to_string(c), "WIF colour " + std::to_string(c), colours.at(c)});
    }
    const auto of = [&](int c) { return c > 0 ? index.at(c) : 0; };
    for (int t = 0; t < across; ++t) p.warp_colours.push_back(of(warp_colour[t]));
    for (int pick = 0; pick < up; ++pick) p.weft_colours.push_back(of(weft_colour[pick]));
  }
  return p;
}

}  // namespace skein::mesh
