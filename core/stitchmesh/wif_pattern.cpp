#include "stitchmesh/wif_pattern.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "common/error.hpp"
#include "stitchmesh/text.hpp"

namespace skein::mesh {
namespace {

constexpr int kMostThreads = 10000;  // threads or picks of a draft: far past a loom's
constexpr int kLongestRepeat = 256;  // threads or picks of the repeat skein relaxes
constexpr long kMostCells = 4'000'000;  // threads x picks of the drawdown

std::string line_at(int line) { return "line " + std::to_string(line); }

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
  std::string raw, current;
  int line_no = 0;
  while (std::getline(in, raw)) {
    ++line_no;
    if (line_no == 1 && raw.rfind("\xEF\xBB\xBF", 0) == 0) raw = raw.substr(3);  // a UTF-8 byte-order mark
    const std::string line = trim(raw);
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

  // The smallest repeat up (rows) and across (columns).
  const int up = smallest_period(over);
  std::vector<std::vector<char>> columns(warps, std::vector<char>(up));
  for (int t = 0; t < warps; ++t)
    for (int pick = 0; pick < up; ++pick) columns[t][pick] = over[pick][t];
  const int across = smallest_period(columns);
  if (up > kLongestRepeat || across > kLongestRepeat)
    throw Error(source, "", "the draft's smallest repeat is " + std::to_string(across) + " threads x " + std::to_string(up) +
                                " picks; skein relaxes woven repeats up to " + std::to_string(kLongestRepeat) + " x " + std::to_string(kLongestRepeat));
  for (int pick = 0; pick < up; ++pick) p.over.emplace_back(over[pick].begin(), over[pick].begin() + across);
  return p;
}

}  // namespace skein::mesh
