#include "stitchmesh/written_pattern.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <map>
#include <numeric>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "common/error.hpp"
#include "common/text.hpp"
#include "stitchmesh/stitch_types.hpp"

namespace skein::mesh {
namespace {

constexpr size_t kLongestLine = 4096;

/// A count as written (the digits a pattern gives): its value, or a million for more than six digits, which
/// every bound below refuses (std::stoi would throw out of range on a long one).
int count_of(const std::string& digits) { return digits.size() > 6 ? 1000000 : std::stoi(digits); }

/// The counts books write in words, and digits: "once", "twice", "thrice", "one" to "ten"; 0 for none of them.
int count_in_words(const std::string& text) {
  static const std::array<const char*, 10> words = {"one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten"};
  const std::string word = lower(text);
  if (!word.empty() && std::all_of(word.begin(), word.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) return count_of(word);
  if (word == "once") return 1;
  if (word == "twice") return 2;
  if (word == "thrice") return 3;
  for (size_t k = 0; k < words.size(); ++k)
    if (word == words[k]) return static_cast<int>(k) + 1;
  return 0;
}

/// One thing a row's instructions say, in the order written.
struct Item {
  enum Kind { Stitch, Cable, Fill, Star, Repeat, Group } kind = Stitch;
  std::string type;        ///< Stitch: the skein stitch type as seen from the front (after the side is applied); Fill: "k" or "p"
  std::string written;     ///< the abbreviation as written, for errors
  int column = 0;          ///< 1-based, in the line
  int over = 0, under = 0, order = 1;  ///< Cable, as seen from the front (PatternCable)
  bool purl_behind = false; ///< Cable: the stitches that cross behind are purled (T3F, 2/1 LPC: knits travelling over purls)
  int times = 1;           ///< Group
  int colour = -1;         ///< Stitch, Cable, Fill: index into the pattern's palette (issue 26), -1 for none said
  int leave = 0;           ///< Fill: "k to last N sts" leaves N
  bool made = false;       ///< Stitch: a loop made from the bar between two stitches (m1l, m1p): `type` its crossed loop
  std::vector<Item> items; ///< Group
};

Item make(Item::Kind kind, const std::string& written, int column, const std::string& type = "") {
  Item item;
  item.kind = kind;
  item.written = written;
  item.column = column;
  item.type = type;
  return item;
}

// The abbreviations skein knows (Craft Yarn Council), and those it reads but has no stitch model for yet.
const char* const kKnown[] = {"k", "p", "k1tbl", "p1tbl", "yo", "k2tog", "ssk", "skp", "p2tog", "ssp", "k3tog", "sssk", "p3tog", "sssp", "sl1", "sl1 wyib", "sl1 wyif",
                              "psso", "p2sso", "m1", "m1l", "m1p", "m1lp", "c4f", "c4b", "c6f", "c6b", "2/2 lc", "2/2 rc", "1/1 lt", "1/1 rt", "knit", "purl", "k to end", "p to end"};
const char* const kNotModelled[] = {"m1r", "m1rp", "mb", "w&t", "kyok", "ktbl2tog", "dpk"};

int edit_distance(const std::string& a, const std::string& b) {
  std::vector<int> row(b.size() + 1);
  std::iota(row.begin(), row.end(), 0);
  for (size_t i = 1; i <= a.size(); ++i) {
    int diagonal = row[0];
    row[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int next = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = row[j];
      row[j] = next;
    }
  }
  return row[b.size()];
}

std::string suggestions(const std::string& word) {
  std::vector<std::pair<int, std::string>> ranked;
  for (const char* k : kKnown) ranked.emplace_back(edit_distance(word, k), k);
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::string out;
  for (size_t i = 0; i < 3 && i < ranked.size(); ++i) out += (out.empty() ? "'" : ", '") + ranked[i].second + "'";
  return out;
}

/// A slip as books write it: "sl1", "sl 1 pwise wyib", "s1", "slip 2 tog kwise", "sl 1 as if to knit"; the count
/// (1 when none is written) and the side the yarn is held. The letter after it is its knitwise or purlwise only as
/// a word of its own ("sl1 k1": a slip, then a knit).
const char* const kSlip =
    R"((?:slip|sl|s)\s*(\d*)(?:\s*tog(?:ether)?)?(?:\s*(?:knitwise|purlwise|kwise|pwise|as\s+if\s+to\s+(?:knit|purl)|k|p)(?![a-z0-9]))?(?:\s*(wyib|wyif))?)";

/// A centred double decrease (sk2p, s2kp, cdd) before pair_lace gives it a model.
const std::string kCentred = "centred double decrease";

/// Leaf's lace stitches (Leaf 2018 Table 2), one face each: a yarn-over beside the decrease that pays for it, a
/// knit from the front: beside a d21k (ssk; ssp on a wrong-side row) it is `ys`, beside a d12k (k2tog; p2tog on a
/// wrong-side row) `2u`, and "yo, sk2p, yo" (right-side rows) is `y3y`; beside a purl from the front (d21p, d12p:
/// garter lace's "yo, k2tog" from the wrong side) `ysp` and `2up`.
/// A yarn-over with no decrease beside it is an increase (Yuksel 2012 Table 1's increase faces): it joins the
/// plain stitch worked before it, or else the one after, into one face that takes that stitch's loop and makes
/// two, named as seen from the front (a right-side row is worked right to left, a wrong-side row left to right
/// with its knits purls): on a right-side row "k1, yo" is `yk`, "yo, k1" `ky`, the same with purls `yp`, `py`; on a
/// wrong-side row "k1, yo" is `py`; "yo, k1, yo" with no plain stitch after it is `yky` (`ypy`). Which neighbour
/// a yarn-over joins changes how the stitch mesh groups the loops, not the loops. Its decreases may lie anywhere in the row
/// (feather and fan); the stitch mesh checks that each row makes as many loops as the next one takes.
void pair_lace(std::vector<Item>& items, const std::string& source, int line, bool right_side) {
  std::vector<Item> out;
  const auto is = [&](size_t i, const char* written) { return i < items.size() && items[i].written == written; };
  const auto plain = [](const Item& item) { return item.kind == Item::Stitch && (item.type == "k" || item.type == "p"); };
  const auto type_is = [&](size_t i, const char* type) { return i < items.size() && items[i].kind == Item::Stitch && items[i].type == type; };
  // `type` with a yarn-over worked after it (`after`) or before it, as seen from the front: a right-side row is
  // worked right to left, so what is worked later lies on the left; a wrong-side row the other way.
  const auto beside = [&](const std::string& type, bool after, const std::string& loop = "y") { return after == right_side ? loop + type : type + loop; };
  // A yarn-over and its decrease, in either order: the lace face (a purl from the front: garter lace's ysp, 2up).
  static const std::pair<const char*, const char*> kLaceFaces[] = {{"d21k", "ys"}, {"d12k", "2u"}, {"d21p", "ysp"}, {"d12p", "2up"}};
  const auto lace_face = [&](size_t i) -> const char* {
    for (const auto& [decrease, face] : kLaceFaces)
      if ((is(i, "yo") && type_is(i + 1, decrease)) || (type_is(i, decrease) && is(i + 1, "yo"))) return face;
    return nullptr;
  };
  // A made loop joins the plain stitch worked before it, or else the one after, as a yarn-over does: "k1, m1l"
  // on a right-side row is kfb's face xk. The face must exist (a made knit beside a knit, a made purl beside a
  // purl: "k2, m1p, p2" joins the purl after) and takes one colour.
  const auto made_face = [&](const Item& made, const Item& plain_item, bool after) {
    Item face = plain_item;
    face.type = beside(plain_item.type, after, made.type);
    face.written = after ? plain_item.written + ", " + made.written : made.written + ", " + plain_item.written;
    return face;
  };
  const auto fail_made = [&](const Item& made, const std::string& rule) {
    throw Error(source, "line " + std::to_string(line) + ", column " + std::to_string(made.column), "'" + made.written + "' " + rule);
  };
  for (size_t i = 0; i < items.size(); ++i) {
    Item item = items[i];
    if (item.made) {
      std::vector<std::string> tried;  // the faces it would make, for the error
      const auto fits = [&](const Item& face) {
        tried.push_back("'" + face.type + "'");
        return find_stitch_type(face.type) != nullptr;
      };
      const auto same_colour = [&](const Item& neighbour) {
        if (item.colour != neighbour.colour)
          fail_made(item, "is in another colour than the stitch it joins ('" + neighbour.written +
                              "'): the increase face they make takes one colour; give them the same");
      };
      if (!out.empty() && plain(out.back()) && !out.back().made) {
        const Item face = made_face(item, out.back(), true);
        if (fits(face)) {
          same_colour(out.back());
          out.back() = face;
          continue;
        }
      }
      if (i + 1 < items.size() && plain(items[i + 1]) && !items[i + 1].made) {
        const Item face = made_face(item, items[i + 1], false);
        if (fits(face)) {
          same_colour(items[i + 1]);
          out.push_back(face);
          ++i;
          continue;
        }
      }
      if (!tried.empty())
        fail_made(item, "would make the increase face " + tried.front() + (tried.size() > 1 ? " or " + tried.back() : "") + " with its neighbours, which skein has no stitch model for: a made "
                        "loop joins a plain stitch of its own kind, a knit beside a knit ('k1, m1l'), a purl beside a purl ('m1p, p1')");
      fail_made(item, "makes a loop that skein models beside a plain knit or purl stitch ('k1, m1l', 'm1p, p1'); here it has neither "
                      "(beside 'k to end', write one stitch out: 'm1, k1, k to end')");
    }
    if (is(i, "yo") && i + 2 < items.size() && items[i + 1].type == kCentred && is(i + 2, "yo")) {
      item.type = "y3y";
      item.colour = items[i + 1].colour;  // the decrease's colour ("yo, sk2p CC, yo"), as the face's below
      item.written = "yo, " + items[i + 1].written + ", yo";
      i += 2;
    } else if (const char* face = lace_face(i)) {
      item.type = face;
      item.colour = items[is(i, "yo") ? i + 1 : i].colour;  // the decrease's: "yo, ssk CC" is a face in CC
      item.written = items[i].written + ", " + items[i + 1].written;
      ++i;
    } else if (is(i, "yo") && !out.empty() && plain(out.back())) {
      out.back().type = beside(out.back().type, true);
      out.back().written += ", yo";
      continue;
    } else if (is(i, "yo") && i + 1 < items.size() && plain(items[i + 1])) {
      item.type = beside(items[i + 1].type, false);
      item.written = "yo, " + items[i + 1].written;
      ++i;
    } else if (is(i, "yo") && !out.empty() && (out.back().type == beside("k", false) || out.back().type == beside("p", false))) {
      out.back().type = beside(out.back().type, true);  // "yo, k1, yo" with nothing plain after it: one loop into three
      out.back().written += ", yo";
      continue;
    } else if (is(i, "yo")) {
      throw Error(source, "line " + std::to_string(line) + ", column " + std::to_string(item.column),
                  "a yarn-over has a stitch model beside its decrease ('yo, ssk', 'k2tog, yo', 'yo, sk2p, yo', ...) or beside a plain knit or "
                  "purl stitch it increases into ('k1, yo', 'yo, p1'); here it has neither");
    } else if (item.type == kCentred) {
      throw Error(source, "line " + std::to_string(line) + ", column " + std::to_string(item.column),
                  "'" + item.written + "' has a stitch model only between two yarn-overs ('yo, " + item.written + ", yo', Leaf's y3y)");
    }
    out.push_back(item);
  }
  items = std::move(out);
}

/// Reads one row's instructions (`text` lower-cased, starting at column `offset` + 1 of its line).
class InstructionReader {
public:
  /// `palette` and `colour`: the pattern's colours and the one worked with, which "with B" changes for this and
  /// the following rows.
  InstructionReader(const std::string& text, int offset, bool right_side, const std::string& source, int line,
                    const std::vector<PatternColour>& palette, int& colour)
      : m_text(text), m_offset(offset), m_rs(right_side), m_source(source), m_line(line), m_palette(palette), m_colour(colour) {
    // The stitch count books give after a row, "K1, kfb, k2. (5 sts)" or "... k2tog — 7 sts.": the stitches on the
    // needle when the row is done, taken off here and checked once the row's width is known.
    // Also "(5 sts; 1 st increased)", "... k3. 5 sts." and the change alone: "(2 sts inc'd)", "(1 st dec)".
    static const std::regex stated(
        R"((?:[(\[]\s*(\d+)\s*(?:sts?|stitches)(?:\s+(?:remain|on\s+needle))?\s*(?:[;,][^)\]]*)?[)\]]|(?:-|–|—)+\s*(\d+)\s*(?:sts?|stitches))"
        R"(|[(\[]\s*(\d+)\s*(?:sts?|stitches)\s+(inc|dec)(?:'d|reased|d)?\s*[)\]]|\.\s+(\d+)\s*(?:sts?|stitches))\s*\.?\s*$)",
        std::regex::icase);
    std::smatch m;
    if (std::regex_search(m_text, m, stated)) {
      if (m[3].matched) m_change = (lower(m[4].str()) == "inc" ? 1 : -1) * count_of(m[3].str());
      else m_stated = count_of(m[1].matched ? m[1].str() : m[2].matched ? m[2].str() : m[5].str());
      m_stated_column = column(static_cast<size_t>(m.position(0) + (m[5].matched ? 1 : 0)));
      m_text.erase(static_cast<size_t>(m.position(0) + (m[5].matched ? 1 : 0)));  // "k3. 5 sts.": the row keeps its period
    }
  }

  std::vector<Item> read() { return sequence(false); }
  /// The stitch count written after the row, or 0; and its column.
  int stated_count() const { return m_stated; }
  /// The change of count written after the row ("(2 sts inc'd)": +2), if that is what it says.
  std::optional<int> stated_change() const { return m_change; }
  int stated_column() const { return m_stated_column; }

private:
  /// The 1-based column, in characters, of byte `at` of the instructions: "K1—M1R" has a dash of three bytes.
  int column(size_t at) const {
    const auto characters = std::count_if(m_text.begin(), m_text.begin() + static_cast<long>(std::min(at, m_text.size())),
                                          [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; });
    return m_offset + static_cast<int>(characters) + 1;
  }
  [[noreturn]] void fail(size_t at, const std::string& rule) const { fail_column(column(at), rule); }
  [[noreturn]] void fail_column(int column, const std::string& rule) const {
    throw Error(m_source, "line " + std::to_string(m_line) + ", column " + std::to_string(column), rule);
  }
  bool match(const char* pattern, std::smatch& m) {
    // Compiled once per pattern and thread (each is a string literal of this file), not at every token tried.
    thread_local std::map<const char*, std::regex> compiled;
    auto it = compiled.find(pattern);
    if (it == compiled.end()) it = compiled.emplace(pattern, std::regex(pattern, std::regex::icase)).first;
    const std::regex& re = it->second;
    const auto begin = m_text.cbegin() + static_cast<long>(m_pos);
    if (!std::regex_search(begin, m_text.cend(), m, re, std::regex_constants::match_continuous)) return false;
    const size_t end = m_pos + static_cast<size_t>(m.length(0));
    if (end < m_text.size() && std::isalnum(static_cast<unsigned char>(m_text[end])) && std::isalnum(static_cast<unsigned char>(m_text[end - 1])))
      return false;  // a word must end where the abbreviation does
    return true;
  }
  /// Commas, semicolons, full stops and spaces between stitches; hyphens and dashes too, as Walker's Treasuries
  /// join the steps of one decrease ("sl 1-k1-psso", "sl 1—k2 tog—psso").
  void skip_separators() {
    static constexpr std::string_view kSeparators = ",;.-";
    for (;;) {
      if (m_pos < m_text.size() && (std::isspace(static_cast<unsigned char>(m_text[m_pos])) || kSeparators.find(m_text[m_pos]) != std::string_view::npos)) {
        ++m_pos;
      } else if (m_text.compare(m_pos, 3, "\xe2\x80\x93") == 0 || m_text.compare(m_pos, 3, "\xe2\x80\x94") == 0) {
        m_pos += 3;  // an en or em dash (UTF-8)
      } else {
        return;
      }
    }
  }
  Item stitch(size_t at, const std::string& written, const std::string& rs, const std::string& ws) {
    Item item;
    item.column = column(at);
    item.written = written;
    const std::string& type = m_rs ? rs : ws;
    if (type.empty())
      fail(at, "'" + written + "' on a " + (m_rs ? "right" : "wrong") + "-side row has no stitch model yet" +
                   (m_rs ? "" : " (work it from the right side, or write the row from the right side)"));
    item.type = type;
    return item;
  }
  /// Two loops taken by one, as seen from the front on a right-side and on a wrong-side row.
  struct Decrease {
    const char* written;
    const char* right_side;
    const char* wrong_side;
  };
  const Decrease* decrease(std::smatch& m) {
    // Three into one stack as two do: k3tog's leftmost loop lies on top (d123), sssk's rightmost (d321). skp (slip,
    // knit, pass the slipped stitch over) leans left as ssk does, its right loop on top: one model for both.
    static const Decrease kDecreases[] = {{R"(k2\s*tog)", "d12k", "d12p"}, {R"(p2\s*tog)", "d12p", "d12k"}, {"ssk", "d21k", "d21p"},
                                          {"ssp", "d21p", "d21k"}, {"skpo?", "d21k", "d21p"}, {R"(k3\s*tog)", "d123k", "d123p"},
                                          {R"(p3\s*tog)", "d123p", "d123k"}, {"sssk", "d321k", "d321p"}, {"sssp", "d321p", "d321k"}};
    for (const auto& d : kDecreases)
      if (match(d.written, m)) return &d;
    return nullptr;
  }
  void add(std::vector<Item>& items, Item item, int count) {
    if (count < 1 || count > 1000) fail_column(item.column, "'" + item.written + "': 1 to 1000 stitches");
    for (int i = 0; i < count; ++i) items.push_back(item);
  }

  /// "psso" and "p2sso" (or "pass slipped st over"), as books write skp, sk2p and s2kp out: the slipped stitch
  /// (or two, slipped together) passed over the one worked after it. "sl1, k1, psso" is skp (the model of ssk,
  /// d21k; "sl1, p1, psso" the purl's), "sl1, k2tog, psso" sk2p and "sl2, k1, p2sso" s2kp, the centred double
  /// decrease. The items they name, the last read in this group or repeat, become that one stitch, in the colour
  /// of the stitch worked (the loop left on the needle).
  void pass_over(std::vector<Item>& items, size_t at, const std::string& written, bool two, bool in_group) {
    static const std::regex knit_one(R"(k1?)", std::regex::icase), purl_one(R"(p1?)", std::regex::icase), k2tog(R"(k2\s*tog)", std::regex::icase);
    const size_t slips = two ? 2 : 1, n = items.size();
    const std::string how = "'" + written + "' passes the slipped stitch" + (two ? "es" : "") +
                            " over the one worked after them: 'sl1, k1, psso' (skp), 'sl1, k2tog, psso' (sk2p) or 'sl2, k1, p2sso' (s2kp)";
    const auto named = [](const Item& item) { return item.kind == Item::Star ? std::string("a '*'") : item.kind == Item::Group ? std::string("a group") : "'" + item.written + "'"; };
    const std::string in_group_only = "; in a group it passes over only what the group works before it";
    if (n == 0) fail(at, how + (in_group ? in_group_only : "; here nothing comes before it"));
    const Item& worked = items[n - 1];
    const bool single = !two && worked.kind == Item::Stitch && (std::regex_match(worked.written, knit_one) || std::regex_match(worked.written, purl_one));
    const bool centred = worked.kind == Item::Stitch && (two ? std::regex_match(worked.written, knit_one) : std::regex_match(worked.written, k2tog));
    if (!single && !centred) fail(at, how + "; here " + named(worked) + " comes before it");
    const Item* slip = n >= 2 ? &items[n - 2] : nullptr;
    const int slipped = slip ? slipped_count(*slip) : 0;
    if (slipped == 2 && !two) fail(at, how + "; here '" + slip->written + "' slips two: pass them over with 'p2sso'");
    if (slipped == 1 && two) fail(at, how + "; here '" + slip->written + "' slips one: 'p2sso' passes two slipped together ('sl2, k1, p2sso')");
    if (slipped != static_cast<int>(slips) || n < slips + 1 || (two && items[n - 3].column != slip->column))
      fail(at, how + (slip ? "; here " + named(*slip) + " comes before " + named(worked)
                           : in_group ? in_group_only : "; here nothing comes before " + named(worked)));
    Item out = items[n - 1 - slips];
    out.written = out.written + ", " + worked.written + ", " + written;
    out.colour = worked.colour;
    if (centred) {
      if (!m_rs) fail(at, "'" + out.written + "' on a wrong-side row has no stitch model yet (work it from the right side, or write the row from the right side)");
      out.type = kCentred;  // a model only between two yarn-overs (pair_lace)
    } else {
      out.type = (worked.written[0] == 'k') == m_rs ? "d21k" : "d21p";
    }
    items.resize(n - 1 - slips);
    items.push_back(out);
  }
  /// How many stitches a slip item slips ("sl1", "s1", "slip 2 tog kwise"): 0 for an item that is no slip.
  static int slipped_count(const Item& item) {
    static const std::regex slip(kSlip, std::regex::icase);
    std::smatch m;
    if (item.kind != Item::Stitch || !std::regex_match(item.written, m, slip)) return 0;
    return m[1].length() ? count_of(m[1].str()) : 1;
  }

  /// "(k1, p1) in next st", "[k1, yo, k1] into the same stitch": two or three stitches worked into one loop below,
  /// an increase face (Yuksel 2012 Table 1) named as seen from the front: a right-side row is worked right to left,
  /// so "(p1, k1) in next st" is `kp` there and "(k1, p1) in next st" is `pk`; a wrong-side row left to right, its
  /// knits purls.
  Item worked_into_one(const Item& group, size_t at) {
    std::string type, written;
    for (const auto& item : group.items) {
      // k1, p1, yo, k1 tbl and p1 tbl: one loop each.
      static const std::regex one_loop(R"((?:k|p)1?|yo1?|(?:k|p)1?(?:\s*tbl|-b))", std::regex::icase);
      const bool single = item.kind == Item::Stitch && item.type.size() == 1 && std::string("kpyxq").find(item.type) != std::string::npos &&
                          std::regex_match(item.written, one_loop);
      if (!single) fail_column(item.column, "'" + item.written + "': a group worked into one stitch holds single knits, purls and yarn-overs");
      type += item.type;
      written += (written.empty() ? "" : ", ") + item.written;
    }
    if (m_rs) std::reverse(type.begin(), type.end());
    if (group.items.size() < 2 || group.items.size() > 3 || !find_stitch_type(type))
      fail(at, "'(" + written + ") in next st' has no stitch model: two or three stitches into one are read as skein's increase faces "
               "(kp, pk, kpk, pkp, kyk, pyp, xk, ...; seen from the front), and this one would be '" + type + "'");
    return make(Item::Stitch, "(" + written + ") in next st", column(at), type);
  }

  /// "with B", "using MC", "change to CC", "join A": the colour worked from here on; false when no declared
  /// colour is named here.
  bool colour_change() {
    std::smatch m;
    if (!match(R"((?:with|using|change\s+to|switch\s+to|join)\s+([a-z0-9]+))", m)) return false;
    static const std::set<std::string> not_colours = {"rs", "ws", "right", "wrong", "yarn", "the", "a"};  // "With RS facing, ..."
    if (not_colours.count(m[1].str()) && find_colour(m_palette, m[1].str()) < 0) return false;
    const int c = find_colour(m_palette, m[1].str());
    if (c < 0) fail(m_pos + static_cast<size_t>(m.position(1)), "'" + m.str(0) + "' names a colour the pattern does not declare " + declared());
    m_pos += static_cast<size_t>(m.length(0));
    m_colour = c;
    return true;
  }
  /// The declared colours in brackets, or how to declare one.
  std::string declared() const {
    std::string names;
    for (const auto& d : m_palette) names += (names.empty() ? "" : ", ") + d.name + (d.alias.empty() ? "" : " (" + d.alias + ")");
    return names.empty() ? "(declare it before the rows: 'MC: cream', 'CC: navy')" : "(" + names + ")";
  }
  /// The colour of the stitches just read (items from `first` on): the one a following "A", "in MC" or "with B"
  /// names ("k1 A, k1 B" in stranded knitting), else the colour worked with.
  void colour_stitches(std::vector<Item>& items, size_t first) {
    if (m_palette.empty() || items.size() == first) return;
    int colour = m_colour;
    bool said = false;
    std::smatch m;
    if (match(R"(\s*(?:in\s+|with\s+)?([a-z0-9]+))", m))
      if (const int c = find_colour(m_palette, m[1].str()); c >= 0) {
        m_pos += static_cast<size_t>(m.length(0));
        colour = c;
        said = true;
      }
    for (size_t i = first; i < items.size(); ++i)
      if (items[i].kind == Item::Stitch || items[i].kind == Item::Cable || items[i].kind == Item::Fill)
        if (said || items[i].colour < 0) items[i].colour = colour;
  }

  std::vector<Item> sequence(bool in_group) {
    std::vector<Item> items;
    for (;;) {
      skip_separators();
      if (m_pos >= m_text.size()) {
        if (in_group) fail(m_pos, "a '[' or '(' group is not closed");
        return items;
      }
      if (colour_change()) continue;
      const size_t at = m_pos, first = items.size();
      std::smatch m;
      if (m_text[m_pos] == '*') {
        ++m_pos;
        items.push_back(make(Item::Star, "*", column(at)));
      } else if (match(R"(rep(?:eat)?\.?\s+from\s+\*(?:\s+(?:to\s+end|across|around|to\s+last\s+(?:(\d+)\s+)?(?:sts?|stitch(?:es)?)))?)", m)) {
        m_pos += static_cast<size_t>(m.length(0));
        items.push_back(make(Item::Repeat, "rep from *", column(at)));
      } else if (m_text[m_pos] == '[' || m_text[m_pos] == '(') {
        ++m_pos;
        Item g = make(Item::Group, "[", column(at));
        if (++m_depth > kMaxGroupDepth) fail(at, "groups are nested more than " + std::to_string(kMaxGroupDepth) + " deep");
        g.items = sequence(true);
        --m_depth;
        skip_separators();
        std::smatch times;
        if (match(R"((?:all\s+)?in(?:to)?\s+(?:the\s+)?(?:next|same)\s+(?:st|stitch)\b)", times)) {
          m_pos += static_cast<size_t>(times.length(0));
          items.push_back(worked_into_one(g, at));
          items.back().colour = g.items.front().colour;
          colour_stitches(items, first);
          continue;
        }
        if (match(R"(\s*(?:x\s*(\d+)|(\d+)\s*(?:times|x)))", times)) {
          m_pos += static_cast<size_t>(times.length(0));
          g.times = count_of(times[1].matched ? times[1].str() : times[2].str());
        } else if (match(R"(\s*(once|twice|thrice|(?:one|two|three|four|five|six|seven|eight|nine|ten)\s+times))", times)) {
          // As books write the count: "[k1, p1] twice", "(k2, p2) three times".
          m_pos += static_cast<size_t>(times.length(0));
          const std::string said = times[1].str();
          g.times = count_in_words(said.substr(0, said.find_first_of(" \t")));
        } else {
          fail(m_pos, "expected how many times the group is worked after it ('3 times' or 'x3')");
        }
        if (g.times < 1 || g.times > 1000) fail(at, "a group is worked 1 to 1000 times");
        items.push_back(std::move(g));
      } else if (m_text[m_pos] == ']' || m_text[m_pos] == ')') {
        if (!in_group) fail(m_pos, "a ']' or ')' closes no group");
        ++m_pos;
        return items;
      } else if (match(R"((knit|purl|k|p)\s+to\s+(?:end|(last)\s+(?:(\d+)\s+)?(?:sts?|stitch(?:es)?)))", m) || match(R"((knit|purl))", m)) {
        m_pos += static_cast<size_t>(m.length(0));
        const bool knit = m[1].str()[0] == 'k';
        items.push_back(make(Item::Fill, m.str(0), column(at), knit == m_rs ? "k" : "p"));
        if (m.size() > 2 && m[2].matched) items.back().leave = m[3].matched ? count_of(m[3].str()) : 1;  // "k to last st": one
      } else if (match(kSlip, m)) {
        m_pos += static_cast<size_t>(m.length(0));
        const int n = m[1].length() ? count_of(m[1].str()) : 1;
        const bool front = m[2].matched && m[2].str() == "wyif";  // with the yarn toward the knitter
        // The float lies on the side the yarn is held: behind the fabric seen from the front is `s`, in front `sk`.
        const bool float_behind = front != m_rs;
        add(items, stitch(at, m.str(0), float_behind ? "s" : "sk", float_behind ? "s" : "sk"), n);
      } else if (match(R"((c|t)(\d+)(f|b))", m) || match(R"((\d)/(\d)\s*(l|r)(p?)(?:c|t))", m)) {
        // Cables, and travelling stitches: knits crossing over purls, the knits in front (the Craft Yarn Council's
        // T3F: sl 2 to cn, hold in front, p1, k2 from cn). CnB and CnF cross half over half; Tn crosses n - 1 knits
        // over one purl (T4: two over two); A/B RC, LC, RPC, LPC (RT, LT, ...) cross A stitches over B.
        m_pos += static_cast<size_t>(m.length(0));
        int front = 0, behind = 0;  // the stitches that travel in front, and those they cross
        bool right = false, purl_behind = false;
        if (m.str(0)[0] == 'c' || m.str(0)[0] == 't') {
          const int n = count_of(m[2].str());
          purl_behind = m[1].str() == "t";
          if (!purl_behind && (n % 2 != 0 || n < 2 || n > 6)) fail(at, "'" + m.str(0) + "': cables of 2, 4 or 6 stitches (half over half) have models");
          if (purl_behind && (n < 2 || n > 4))
            fail(at, "'" + m.str(0) + "': travelling cables of 2, 3 or 4 stitches (T2: 1 over 1, T3: 2 over 1, T4: 2 over 2) have models");
          front = purl_behind && n != 4 ? n - 1 : n / 2;
          behind = n - front;
          right = m[3].str() == "b";  // CnB, TnB: the stitches in front travel right; CnF, TnF: left
        } else {
          front = count_of(m[1].str());
          behind = count_of(m[2].str());
          right = m[3].str() == "r";
          purl_behind = m[4].length() > 0;
        }
        if (front < 1 || front > 3 || behind < 1 || behind > 3) fail(at, "'" + m.str(0) + "': cables cross 1 to 3 stitches over 1 to 3");
        // On a wrong-side row the cable is worked in purl, so that its stitches are knits from the front, as cable
        // patterns cross them on such rows. Held at the back of the work (the front of the fabric) the stitches
        // slipped first, the front's leftmost ones, travel right in front: a CnB looks from the front as a
        // right-side CnB does, and the same for every other cable. Travelling stitches would put a purl in front.
        if (!m_rs && purl_behind)
          fail(at, "travelling stitches on wrong-side rows have no model yet: cross them on right-side rows (a cable of knits, worked in purl, crosses on either side)");
        // Seen from the front, the cable's left loops cross right: in front (order 1) when the stitches in front
        // travel right, else behind them (order -1).
        Item c = make(Item::Cable, m.str(0), column(at));
        c.over = right ? front : behind;
        c.under = right ? behind : front;
        c.order = right ? 1 : -1;
        c.purl_behind = purl_behind;
        items.push_back(c);
      } else if (match(R"((?:m1|make\s+(?:1|one))(lp|l|p)?(\s+(?:purlwise|pwise|knitwise|kwise))?(?![a-z0-9]))", m)) {
        // Make one: the bar between two stitches lifted and worked through its back loop, a crossed loop (x as a
        // knit from the front, q as a purl); m1l's twist is k1tbl's. It joins a plain neighbour (pair_lace).
        // "M1 purlwise" is m1p; "make 1" and "make one" are m1.
        m_pos += static_cast<size_t>(m.length(0));
        const bool purl = m[1].str().find('p') != std::string::npos || m[2].str().find('p') != std::string::npos;
        Item made = stitch(at, m.str(0), purl ? "q" : "x", purl ? "x" : "q");
        made.made = true;
        items.push_back(made);
      } else if (match(R"((k|p)fb)", m)) {
        // Into the front and then the back leg of one loop: the second loop crossed (Yuksel 2012 Table 1's increase
        // with an x or q loop), seen from the front: a right-side row worked right to left, a wrong-side row left to
        // right with its knits purls.
        m_pos += static_cast<size_t>(m.length(0));
        const bool knit = m[1].str() == "k";
        items.push_back(stitch(at, m.str(0), knit ? "xk" : "qp", knit ? "pq" : "kx"));
      } else if (const Decrease* d = decrease(m)) {
        m_pos += static_cast<size_t>(m.length(0));
        items.push_back(stitch(at, m.str(0), d->right_side, d->wrong_side));
      } else if (match(R"(p(2?)sso|p\.s\.s\.o\.?|pass\s+(?:the\s+)?(2\s+)?(?:slipped|sl)\s+(?:sts?|stitch(?:es)?)\s+over)", m)) {
        m_pos += static_cast<size_t>(m.length(0));
        pass_over(items, at, m.str(0), m[1].length() > 0 || m[2].length() > 0, in_group);
        colour_stitches(items, items.size() - 1);  // "psso CC": the decrease's colour
        continue;
      } else if (match(R"(sk2po?|s2kpo?|s2kp2|cdd)", m)) {
        m_pos += static_cast<size_t>(m.length(0));
        items.push_back(stitch(at, m.str(0), kCentred, ""));  // a model only between two yarn-overs (pair_lace)
      } else if (match(R"(yo(\d*))", m)) {
        m_pos += static_cast<size_t>(m.length(0));
        add(items, stitch(at, "yo", "y", "y"), m[1].length() ? count_of(m[1].str()) : 1);
      } else if (match(R"((k|p)(\d*)(?:\s*tbl|-b))", m)) {  // Walker writes "k1-b"
        m_pos += static_cast<size_t>(m.length(0));
        const bool knit = m[1].str() == "k";
        // Through the back loop, knit or purl, the loop crosses the same way: a crossed knit (x) or purl (q) from the front.
        add(items, stitch(at, m.str(0), knit ? "x" : "q", knit ? "q" : "x"), m[2].length() ? count_of(m[2].str()) : 1);
      } else if (match(R"((k|p)(\d*))", m)) {
        m_pos += static_cast<size_t>(m.length(0));
        const bool knit = m[1].str() == "k";
        const int n = m[2].length() ? count_of(m[2].str()) : 1;
        add(items, stitch(at, m.str(0), knit ? "k" : "p", knit ? "p" : "k"), n);
      } else {
        size_t end = m_pos;
        while (end < m_text.size() && !std::isspace(static_cast<unsigned char>(m_text[end])) && m_text[end] != ',' && m_text[end] != ';' &&
               m_text[end] != '.' && m_text[end] != ']' && m_text[end] != ')')
          ++end;
        const std::string word = m_text.substr(m_pos, end - m_pos);
        if (std::find(std::begin(kNotModelled), std::end(kNotModelled), word) != std::end(kNotModelled))
          fail(at, "'" + word + "' is a knitting abbreviation skein has no stitch model for yet" +
                       std::string(word.rfind("m1", 0) == 0 ? "; its loop twists the other way from skein's crossed loops (k1tbl's and m1l's): "
                                                              "the nearest are 'm1l' and 'kfb'" : ""));
        // "k2 DC" in a pattern in colours: a word after a stitch reads as its colour.
        const bool after_stitch = !m_palette.empty() && !items.empty() && at > 0 && std::isspace(static_cast<unsigned char>(m_text[at - 1])) &&
                                  word.size() <= 3;
        if (after_stitch)
          fail(at, "'" + word + "' after a stitch would be its colour, but the pattern does not declare it " + declared() +
                       "; as an abbreviation it is unknown: did you mean " + suggestions(word) + "?");
        fail(at, "unknown abbreviation '" + word + "'; did you mean " + suggestions(word) + "? (patterns/FORMAT.md lists what is read)");
      }
      colour_stitches(items, first);
    }
  }

  std::string m_text;
  int m_stated = 0, m_stated_column = 0;
  std::optional<int> m_change;
  int m_offset;
  bool m_rs;
  std::string m_source;
  int m_line;
  const std::vector<PatternColour>& m_palette;
  int& m_colour;
  size_t m_pos = 0;
  int m_depth = 0;                         ///< groups open at m_pos
  static constexpr int kMaxGroupDepth = 16;  ///< "[(k1, p1) twice, k2] 3 times" is two; no pattern needs sixteen
};

/// Groups expanded, in the order written.
void flatten(const std::vector<Item>& items, std::vector<Item>& out) {
  for (const auto& item : items) {
    if (item.kind != Item::Group) {
      out.push_back(item);
      continue;
    }
    for (int t = 0; t < item.times; ++t) flatten(item.items, out);
  }
}

int taken(const Item& item) {
  return item.kind == Item::Cable ? item.over + item.under : item.kind == Item::Fill ? 1 : find_stitch_type(item.type)->bottom;
}
int loops_taken(const std::vector<Item>& items) {
  int n = 0;
  for (const auto& item : items) n += taken(item);
  return n;
}
int made(const Item& item) {
  return item.kind == Item::Cable ? item.over + item.under : item.kind == Item::Fill ? 1 : find_stitch_type(item.type)->top;
}
int loops_made(const std::vector<Item>& items) {
  int n = 0;
  for (const auto& item : items) n += made(item);
  return n;
}

/// One row as written: the stitches before its `*` repeat, the repeat, and those after (the edge stitches).
/// A row without `*` is all repeat; `knit` / `purl` is a repeat of one stitch.
struct WrittenRow {
  std::vector<Item> before, repeat, after;  ///< flat: no groups, stars or repeats; stitches as seen from the front
  bool right_side = true;
  bool starred = false;  ///< written with a `*` repeat; without one (and not a fill) the row is as wide as written
  int partial_fill = 0;  ///< the column of a `k to end` or `k to last N sts` beside other stitches (shaped pieces only), or 0
  int line = 0;
  int stated = 0, stated_column = 0;  ///< the stitch count written after the row ("(5 sts)") and its column, or 0
  std::optional<int> change;          ///< or the change it says ("(2 sts inc'd)": +2)
  int edges() const { return loops_taken(before) + loops_taken(after); }
  /// The loops of front-view edge on the left: right-side rows are worked right to left as seen from the front.
  int left_edge() const { return loops_taken(right_side ? after : before); }
  /// The whole row `copies` repeats wide, in the order it is worked.
  std::vector<Item> worked(int copies) const {
    std::vector<Item> row = before;
    for (int c = 0; c < copies; ++c) row.insert(row.end(), repeat.begin(), repeat.end());
    row.insert(row.end(), after.begin(), after.end());
    return row;
  }
  /// The whole row `copies` repeats wide, left to right as seen from the front.
  std::vector<Item> front(int copies) const {
    std::vector<Item> row = worked(copies);
    if (right_side) std::reverse(row.begin(), row.end());
    return row;
  }
};

WrittenRow split_row(std::vector<Item> written, bool right_side, int line, const std::string& source) {
  const std::string where = "line " + std::to_string(line);
  std::vector<Item> flat;
  flatten(written, flat);
  WrittenRow row;
  row.right_side = right_side;
  row.line = line;
  const auto star = std::find_if(flat.begin(), flat.end(), [](const Item& i) { return i.kind == Item::Star; });
  const auto rep = std::find_if(flat.begin(), flat.end(), [](const Item& i) { return i.kind == Item::Repeat; });
  if ((star == flat.end()) != (rep == flat.end()))
    throw Error(source, where, star == flat.end() ? "'rep from *' without a '*' before it" : "a '*' without 'rep from *' after it");
  if (star != flat.end()) {
    if (rep < star) throw Error(source, where + ", column " + std::to_string(rep->column), "'rep from *' comes before its '*'");
    row.starred = true;
    row.before.assign(flat.begin(), star);
    row.repeat.assign(star + 1, rep);
    row.after.assign(rep + 1, flat.end());
  } else {
    row.repeat = flat;
  }
  for (auto* part : {&row.before, &row.repeat, &row.after})
    pair_lace(*part, source, line, right_side);
  for (const auto* part : {&row.before, &row.repeat, &row.after})
    for (const auto& item : *part) {
      if (item.kind == Item::Star || item.kind == Item::Repeat) throw Error(source, where, "holds more than one '*' repeat; write one repeat per row");
      if (item.kind == Item::Fill && (flat.size() != 1 || item.leave > 0) && row.partial_fill == 0) row.partial_fill = item.column;
    }
  if (loops_taken(row.repeat) < 1) throw Error(source, where, "its repeat takes no loop from the row below");
  return row;
}

struct RowHeader {
  int first = 0, last = 0;
  std::vector<int> also;  ///< "Rows 1, 3 and 5 (RS):": the later rows of a list with gaps (first = last = 1 here)
  bool round = false;
  int side = 0;       ///< +1 RS, -1 WS, 0 not said
  size_t colon = 0;   ///< where the instructions start
};

bool row_header(const std::string& line, RowHeader& h) {
  static const std::regex re(
      R"(^\s*(rows?|rnds?|rounds?)\s+(\d+)(?:\s*(?:-|–|to)\s*(\d+)|((?:\s*(?:,|and|&|,\s*and)\s*\d+)+))?\s*(?:\(\s*(rs|ws|right\s+side|wrong\s+side)\s*\))?\s*[:.])",
      std::regex::icase);
  std::smatch m;
  if (!std::regex_search(line, m, re)) return false;
  h.round = lower(m[1].str())[1] == 'n' || lower(m[1].str()).rfind("round", 0) == 0;
  h.first = count_of(m[2].str());
  h.last = m[3].matched ? count_of(m[3].str()) : h.first;
  h.also.clear();
  if (m[4].matched) {  // "Rows 1 and 2" is a run of rows; "Rows 1, 3 and 5" rows apart, worked when their turn comes
    static const std::regex number(R"(\d+)");
    std::vector<int> listed{h.first};
    const std::string list = m[4].str();
    for (auto it = std::sregex_iterator(list.begin(), list.end(), number); it != std::sregex_iterator(); ++it) listed.push_back(count_of(it->str()));
    bool run = true;
    for (size_t k = 1; k < listed.size(); ++k) run = run && listed[k] == listed[k - 1] + 1;
    if (run) h.last = listed.back();
    else h.also.assign(listed.begin() + 1, listed.end());
  }
  h.side = m[5].matched ? (lower(m[5].str())[0] == 'r' ? 1 : -1) : 0;
  h.colon = static_cast<size_t>(m.length(0));
  return true;
}

}  // namespace

bool is_written_pattern(const std::string& text) {
  std::istringstream in(text);
  RowHeader h;
  for (std::string line; std::getline(in, line);) {
    if (line.size() > kLongestLine) line.resize(200);  // a heading is short; the reader says what is wrong with the rest
    const auto hash = line.find('#');
    const std::string content = line.substr(0, hash);
    if (content.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string l = lower(content);
    static const std::regex format(R"(^\s*format\s+(\w+)\s*$)");
    std::smatch m;
    if (std::regex_search(l, m, format)) return m[1].str() == "written";
    if (row_header(content, h)) return true;
  }
  return false;
}

namespace {
/// "Rep Rows 1 and 2", "Rep Rows 3-6 twice more", "Rep last 2 rows 3 times more", "Rep the last row", "Rep Row 1 for patt": the rows a
/// line repeats, as a row's instructions or on a line of its own.
const std::regex again_line(
    R"(^\s*rep(?:eat)?\.?\s+(?:(?:rows?|rnds?|rounds?)\s+(\d+)(?:\s*(?:and|-|–|to|through|thru|&)\s*(\d+))?|(?:the\s+)?last\s+(?:(\w+)\s+)?(?:rows?|rnds?|rounds?))(?:\s+(\w+)(\s+more)?(?:\s+times?)?(\s+more)?)?(?:\s+for\s+(?:the\s+)?patt(?:ern)?)?\s*\.?\s*$)",
    std::regex::icase);

struct RowsAgain {
  int first = 0, last = 0;  ///< rows first..last (1-based) ...
  int times = 1;            ///< ... worked this many times more
};

/// The rows an `again_line` match repeats, `written` rows being above it. `heading_rows` is the number of rows its
/// heading has left ("Rows 5-12: Rep Rows 1-4 twice."), or 0 on a line of its own: there a count must say "more"
/// ("twice more", "3 more times"), since "Rep Rows 1 and 2 three times" reads either way; under a heading the
/// rows the heading names must be what the count makes. Throws skein::Error naming `source` and the line.
RowsAgain rows_again(const std::smatch& m, int written, int line, int heading_rows, const std::string& source) {
  const std::string where = "line " + std::to_string(line);
  RowsAgain out;
  if (!m[1].matched) {  // "the last N rows", "the last row"
    const int n = m[3].matched ? count_in_words(m[3].str()) : 1;
    if (n < 1) throw Error(source, where, "cannot read '" + m[3].str() + "' as a number of rows");
    if (n > written) throw Error(source, where, "repeats the last " + std::to_string(n) + " rows, but " + std::to_string(written) + " are written above it");
    out.first = written - n + 1;
    out.last = written;
  } else {
    out.first = count_of(m[1].str());
    out.last = m[2].matched ? count_of(m[2].str()) : out.first;
  }
  if (out.first < 1 || out.last < out.first || out.last > written)
    throw Error(source, where, "repeats rows " + std::to_string(out.first) + "-" + std::to_string(out.last) + ", which are not all written above it");
  const int span = out.last - out.first + 1;
  if (m[4].matched) {
    out.times = count_in_words(m[4].str());
    if (out.times < 1) throw Error(source, where, "cannot read '" + m[4].str() + "' as how many times the rows are repeated");
    if (out.times > 1000) throw Error(source, where, "repeats its rows more than 1000 times");
    if (heading_rows == 0 && !m[5].matched && !m[6].matched)
      throw Error(source, where, "says how many times without 'more', which reads two ways: write '" + m[4].str() +
                                     " more times' (the rows again that many times), or give the rows a heading ('Rows N-M: Rep ...')");
    if (heading_rows > 0 && out.times * span != heading_rows)
      throw Error(source, where, "repeats " + std::to_string(span) + " rows " + std::to_string(out.times) + " times, " + std::to_string(out.times * span) +
                                     " rows, but its heading names " + std::to_string(heading_rows));
  } else if (heading_rows > 0) {
    // "Rows 5-8: Rep Rows 1-4." (or "Rows 5-12: Rep Rows 1-4"): the rows as often as the heading has room for.
    if (span > heading_rows) throw Error(source, where, "repeats more rows than its heading names");
    out.times = 1;
  }
  return out;
}
}  // namespace

/// Gives the row's fill (`knit`, `k to end`, `k to last N sts`) its stitches: as many as the `below` loops leave
/// after the other stitches, the N last ones taking exactly N loops. Returns false when the row has no room for it
/// (it then is not a shaped piece's row); throws for a fill the row cannot hold (two of them, or "to last N" where
/// the stitches after it take another number of loops).
bool fill_to(WrittenRow& row, int below, const std::string& source) {
  auto& items = row.repeat;
  const auto fill = std::find_if(items.begin(), items.end(), [](const Item& i) { return i.kind == Item::Fill; });
  if (fill == items.end()) return true;
  const auto where = [&](const Item& i) { return "line " + std::to_string(row.line) + ", column " + std::to_string(i.column); };
  if (std::any_of(fill + 1, items.end(), [](const Item& i) { return i.kind == Item::Fill; }))
    throw Error(source, where(*(fill + 1)), "a row holds one 'k to end' or 'k to last N sts'");
  const std::vector<Item> before(items.begin(), fill), after(fill + 1, items.end());
  if (loops_taken(after) != fill->leave)
    throw Error(source, where(*fill), "'" + fill->written + "' is followed by stitches that take " + std::to_string(loops_taken(after)) + " loops, not " +
                                          std::to_string(fill->leave));
  const int count = below - loops_taken(before) - loops_taken(after);
  if (count < 0) return false;
  Item stitch = *fill;
  stitch.kind = Item::Stitch;
  std::vector<Item> out = before;
  out.insert(out.end(), static_cast<size_t>(count), stitch);
  out.insert(out.end(), after.begin(), after.end());
  items = std::move(out);
  return true;
}

/// Writes a shaped piece's `*` repeat out as often as the `below` loops leave room for beside its edge stitches
/// (`*k2, m1; rep from * to end` over 8 sts: four times), so the row is whole. Returns false when the repeat does
/// not fill that room a whole number of times.
bool widen_repeat(WrittenRow& row, int below) {
  if (!row.starred) return true;
  const int room = below - row.edges(), width = loops_taken(row.repeat);
  if (room < width || room % width != 0) return false;
  row.repeat = row.worked(room / width);
  row.before.clear();
  row.after.clear();
  row.starred = false;
  return true;
}

/// Appends one row of worked items to the pattern: its stitch types, a cable's crossing (its loops knitted) and
/// each stitch's colour.
void append_row(Pattern& p, const std::vector<Item>& items) {
  std::vector<std::string> types;
  std::vector<int> colours;
  for (const auto& item : items) {
    if (item.kind == Item::Cable) {
      int made = 0;
      for (const auto& t : types) made += find_stitch_type(t)->top;
      p.cables.push_back({static_cast<int>(p.rows.size()), made, item.over, item.under, item.order});
      // Crossed, the `under` loops from the right lie on the left; those that crossed behind are purled when the
      // cable says so (travelling stitches).
      const bool left_behind = item.order < 0;  // the `over` loops from the left crossed behind: now on the right
      types.insert(types.end(), item.under, item.purl_behind && !left_behind ? "p" : "k");
      types.insert(types.end(), item.over, item.purl_behind && left_behind ? "p" : "k");
      colours.insert(colours.end(), item.over + item.under, std::max(item.colour, 0));
    } else {
      types.push_back(item.type);
      colours.push_back(std::max(item.colour, 0));
    }
  }
  p.rows.push_back(std::move(types));
  if (!p.palette.empty()) p.colours.push_back(std::move(colours));
}

/// A shaped piece's rows as written, each row whole; "Cast on N sts." in the description must match the first row.
Pattern shaped_piece(Pattern p, std::vector<WrittenRow>& rows, const std::string& description, const std::string& source) {
  // A piece knitted in rounds is a tube, which a piece's flat layout would silently open out.
  if (!p.flat)
    throw Error(source, "line " + std::to_string(rows[0].line),
                "is a piece worked in rounds ('Cast on N sts.' and rounds written whole): a tube, which skein does not build from written "
                "instructions yet; without the cast-on line its rounds are read as a stitch pattern");
  p.whole = true;
  static const std::regex cast_on(R"(cast\s+on\s+(\d+)\s*(?:sts|stitches)\b)", std::regex::icase);
  std::smatch m;
  if (std::regex_search(description, m, cast_on) && count_of(m[1].str()) != loops_taken(rows[0].repeat))
    throw Error(source, "line " + std::to_string(rows[0].line),
                "takes " + std::to_string(loops_taken(rows[0].repeat)) + " stitches, but the pattern casts on " + m[1].str());
  std::vector<int> row_line;
  for (auto& row : rows) {
    append_row(p, row.front(1));
    row_line.push_back(row.line);
  }
  check_stacking(p, row_line, source);
  return p;
}

/// A stitch pattern's stitch counts against its rows: "Multiple of N sts plus M" (the description's line
/// `multiple_line`) must be a width every row's repeat fills, its edge stitches included, and a count written after
/// a row ("(18 sts)") must be one the row makes (its edges plus whole repeats), the same on every row (a stitch
/// pattern keeps its count) and one the multiple allows.
void check_counts(const std::vector<WrittenRow>& rows, const std::string& description, int multiple_line, const std::string& source) {
  static const std::regex multiple_of(R"(\bmultiple\s+of\s+(\d+)(?:\s*(?:sts|stitches))?(?:\s*(?:\+|plus)\s*(\d+))?)", std::regex::icase);
  std::smatch m;
  const bool declared = std::regex_search(description, m, multiple_of);
  const int n = declared ? count_of(m[1].str()) : 0, plus = declared && m[2].matched ? count_of(m[2].str()) : 0;
  const auto modulo = [](int a, int b) { return ((a % b) + b) % b; };
  const WrittenRow* first_stated = nullptr;
  for (const auto& row : rows) {
    if (!row.starred) continue;  // a fill row takes any width; a row without '*' is one repeat, checked against the others
    const int w = loops_taken(row.repeat);
    if (declared && n > 0 && (n % w != 0 || modulo(plus - row.edges(), w) != 0))
      throw Error(source, "line " + std::to_string(multiple_line),
                  "says a multiple of " + std::to_string(n) + " sts" + (plus ? " plus " + std::to_string(plus) : "") + ", but the row on line " + std::to_string(row.line) +
                      " repeats every " + std::to_string(w) + " sts with " + std::to_string(row.edges()) + " edge stitches");
    if (row.stated <= 0) continue;
    const std::string at = "line " + std::to_string(row.line) + ", column " + std::to_string(row.stated_column);
    const int edges_made = loops_made(row.before) + loops_made(row.after), w_made = loops_made(row.repeat);
    if (row.stated < edges_made + w_made || modulo(row.stated - edges_made, w_made) != 0)
      throw Error(source, at, "the count written after the row says " + std::to_string(row.stated) + ", but the row makes " + std::to_string(edges_made) + " plus a multiple of " +
                                  std::to_string(w_made) + " stitches");
    if (declared && n > 0 && modulo(row.stated - plus, n) != 0)
      throw Error(source, at, "the count written after the row says " + std::to_string(row.stated) + ", which is not a multiple of " + std::to_string(n) + " sts" +
                                  (plus ? " plus " + std::to_string(plus) : "") + " (line " + std::to_string(multiple_line) + ")");
    if (first_stated && first_stated->stated != row.stated)
      throw Error(source, at, "the count written after the row says " + std::to_string(row.stated) + ", but the one after line " + std::to_string(first_stated->line) + " says " +
                                  std::to_string(first_stated->stated) + ": a stitch pattern keeps its count from row to row");
    if (!first_stated) first_stated = &row;
  }
}

Pattern parse_written_pattern(const std::string& text, const std::string& source) {
  Pattern p;
  p.name = std::filesystem::path(source).stem().string();
  p.format = PatternFormat::Knit;
  std::istringstream in(text);
  std::vector<WrittenRow> rows;  // Row 1 first
  struct Instructions {
    std::string body;  ///< lower-cased, from the heading's colon on
    int offset = 0, line = 0;
    bool right_side = true;
  };
  std::vector<Instructions> said;  // per row: what was written for it
  bool round = false;
  int colour = 0;  // the colour worked with: the first declared until "with B" says otherwise
  // Row `number` (1-based, the next one) worked from instructions: on its own side.
  const auto work = [&](const Instructions& w) {
    InstructionReader reader(w.body, w.offset, w.right_side, source, w.line, p.palette, colour);
    rows.push_back(split_row(reader.read(), w.right_side, w.line, source));
    rows.back().stated = reader.stated_count();
    rows.back().change = reader.stated_change();
    rows.back().stated_column = reader.stated_column();
    said.push_back(w);
  };
  // Rows a..b once more as the next rows: "Rep Row 1" on a wrong-side row is worked from the wrong side.
  const auto again = [&](int a, int b) {
    for (int k = a; k <= b; ++k) {
      Instructions w = said[k - 1];
      const int number = static_cast<int>(rows.size()) + 1;
      if (!round && (number - k) % 2 != 0) w.right_side = !w.right_side;
      work(w);
      rows.back().stated = 0;  // a row's count is said of the row where it is written, not of its repeats
      rows.back().change.reset();
    }
  };
  // "Row 2 and all WS rows: Purl.": the instructions of every wrong-side row the text leaves out.
  std::optional<Instructions> every_ws;
  // "Rows 1, 3 and 5 (RS): Knit.": rows 3 and 5, worked when their turn comes; by row number, with the heading's line.
  std::map<int, Instructions> later;
  // The rows before row `up_to` that the text gave already: left-out wrong-side rows and rows listed apart.
  const auto implied_ws = [&](int up_to) {
    for (;;) {
      const int next = static_cast<int>(rows.size()) + 1;
      if (const auto it = later.find(next); it != later.end()) {
        work(it->second);
        later.erase(it);
      } else if (every_ws && next < up_to && next % 2 == 0) {
        work(*every_ws);
      } else {
        break;
      }
    }
  };
  int line_no = 0;
  bool started = false;
  std::string description;
  int multiple_line = 0;  // the description's line that says "Multiple of N sts plus M", or 0
  // std::regex recurses per character: a bound on the line keeps a hostile file from the stack's end.
  LineReader reader(in, source, kLongestLine);
  while (reader.next()) {
    line_no = reader.number();
    std::string line = reader.line();
    if (const auto hash = comment_start(line); hash != std::string::npos) {
      const std::string comment = line.substr(hash + 1);
      const auto b = comment.find_first_not_of(" \t");
      const std::string c = b == std::string::npos ? "" : comment.substr(b);
      for (const auto& [key, field] : {std::pair{"name:", &p.name}, std::pair{"source:", &p.note}})
        if (c.rfind(key, 0) == 0) {
          *field = c.substr(std::string(key).size());
          field->erase(0, field->find_first_not_of(" \t"));
          field->erase(field->find_last_not_of(" \t\r") + 1);
        }
      line = line.substr(0, hash);
    }
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    RowHeader h;
    std::smatch again_m;
    if (started && std::regex_search(line, again_m, again_line)) {
      // "Rep Rows 1 and 2 (for pattern).", "Rep Rows 3-6 twice more.", "Rep last 2 rows 3 times more." on a line
      // of their own: those rows once more, or as many times more as said, as the next rows.
      const RowsAgain r = rows_again(again_m, static_cast<int>(rows.size()), line_no, 0, source);
      for (int k = 0; k < r.times; ++k) again(r.first, r.last);
      continue;
    }
    static const std::regex standing(
        R"(^\s*(?:rows?\s+(\d+)\s+(?:and|&)\s+)?(?:all|every)\s+(?:ws|wrong[\s-]+side|even(?:[\s-]+numbered)?)\s+rows?\s*(?:\(\s*(?:ws|wrong\s+side)\s*\))?\s*[:.])",
        std::regex::icase);
    std::smatch standing_m;
    if (std::regex_search(line, standing_m, standing)) {
      // "Row 2 and all WS rows: ..." (or "All WS rows: ..."): the wrong-side rows the text leaves out, from here on.
      const int first = standing_m[1].matched ? count_of(standing_m[1].str()) : 2;
      if (round) throw Error(source, "line " + std::to_string(line_no), "names wrong-side rows, but the pattern is worked in rounds");
      if (first % 2 != 0 || first != static_cast<int>(rows.size()) + 1 + (rows.size() % 2 == 0 ? 1 : 0))
        throw Error(source, "line " + std::to_string(line_no),
                    "says its wrong-side rows start at row " + std::to_string(first) + ", but the next wrong-side row is row " +
                        std::to_string(rows.size() + 1 + (rows.size() % 2 == 0 ? 1 : 0)));
      started = true;
      every_ws = Instructions{lower(line.substr(static_cast<size_t>(standing_m.length(0)))), static_cast<int>(standing_m.length(0)), line_no, false};
      implied_ws(first + 1);
      continue;
    }
    if (!row_header(line, h)) {
      if (lower(line).find("format written") != std::string::npos && !started) continue;
      static const std::regex heading(R"(^\s*(rows?|rnds?|rounds?)\s+\d)", std::regex::icase);
      if (std::regex_search(line, heading))
        throw Error(source, "line " + std::to_string(line_no),
                    "a row heading this reader cannot read: write 'Row N:', 'Row N (RS):', 'Rows N and M:', 'Rows N-M:' or 'Rnd N:' (patterns/FORMAT.md)");
      if (!started) {
        // "MC: cream", "Colour A: navy #1f2a44": a colour of the palette (issue 26).
        if (auto c = read_colour_declaration(line, true, static_cast<int>(p.palette.size()), source, "line " + std::to_string(line_no))) {
          check_new_colour(p.palette, *c, source, "line " + std::to_string(line_no));
          p.palette.push_back(std::move(*c));
          continue;
        }
      }
      if (!started) {  // a description before the rows: "Multiple of 4 sts plus 2", "Cast on ..."
        description += (description.empty() ? "" : " ") + line.substr(line.find_first_not_of(" \t"));
        if (!multiple_line && lower(line).find("multiple of") != std::string::npos) multiple_line = line_no;
        continue;
      }
      throw Error(source, "line " + std::to_string(line_no), "expected a row: 'Row N (RS): ...', 'Rows N and M: ...' or 'Rnd N: ...'");
    }
    if (started && h.round != round) throw Error(source, "line " + std::to_string(line_no), "mixes rows (worked flat) and rounds (in the round)");
    round = h.round;
    started = true;
    for (int r = h.first; r <= std::max(h.last, h.first); ++r)
      if (const auto it = later.find(r); it != later.end())
        throw Error(source, "line " + std::to_string(line_no),
                    std::string(round ? "round " : "row ") + std::to_string(r) + " is given twice: on line " + std::to_string(it->second.line) + " too");
    implied_ws(h.first);
    const int expected = static_cast<int>(rows.size()) + 1;
    if (h.first != expected || h.last < h.first)
      throw Error(source, "line " + std::to_string(line_no),
                  std::string(round ? "round" : "row") + " " + std::to_string(h.first) + (h.last != h.first ? "-" + std::to_string(h.last) : "") +
                      " comes where " + (round ? "round " : "row ") + std::to_string(expected) + " was expected (rows are numbered from 1, in order)");
    if (h.last - h.first > 1000) throw Error(source, "line " + std::to_string(line_no), "more than 1000 rows at once");
    std::string body = lower(line.substr(h.colon));
    for (size_t k = 0; k < h.also.size(); ++k) {
      const int r = h.also[k], before = k == 0 ? h.first : h.also[k - 1];
      if (r <= before || r > h.first + 1000)
        throw Error(source, "line " + std::to_string(line_no), "lists rows out of order: " + std::to_string(r) + " after " + std::to_string(before));
      if (std::regex_search(body, again_line))
        throw Error(source, "line " + std::to_string(line_no), "repeats rows under a heading that lists rows apart: give the rows' own instructions");
      later[r] = Instructions{body, static_cast<int>(h.colon), line_no, round || (h.side != 0 ? h.side > 0 : r % 2 == 1)};
    }
    // "Rep Rows 1 and 2." as the instructions: those rows again, as they were.
    std::smatch m;
    for (int r = h.first; r <= h.last; ++r) {
      const bool right_side = round || (h.side != 0 ? h.side > 0 : r % 2 == 1);
      if (std::regex_search(body, m, again_line)) {
        const RowsAgain again_rows = rows_again(m, static_cast<int>(rows.size()), line_no, h.last - r + 1, source);
        for (int k = 0; k < again_rows.times; ++k) again(again_rows.first, again_rows.last);
        r += again_rows.times * (again_rows.last - again_rows.first + 1) - 1;
        continue;
      }
      work({body, static_cast<int>(h.colon), line_no, right_side});
    }
  }
  implied_ws(static_cast<int>(rows.size()) + 2);  // a pattern that ends on a right-side row ends with its wrong-side row
  if (!later.empty())
    throw Error(source, "line " + std::to_string(later.begin()->second.line),
                std::string(round ? "gives round " : "gives row ") + std::to_string(later.begin()->first) + ", but no line gives " +
                    (round ? "round " : "row ") + std::to_string(rows.size() + 1) + " before it");
  if (rows.empty()) throw Error(source, "", "holds no rows: written instructions start 'Row 1: ...' or 'Rnd 1: ...'");
  if (p.note.empty()) p.note = description;
  p.flat = !round;

  // A piece (issue 26): "Cast on N sts." (where a stitch pattern says "Multiple of N sts"), each row taking the
  // loops the row below made. It is knitted once, as written, shaped or not: `knit`, `k to end` and `k to last N sts`
  // take what the row below leaves them, and a '*' repeat is worked as often as they leave room for. Cast on and
  // never shaped inside a '*' repeat, the rows are a stitch pattern's (the cast-on count one width of it).
  static const std::regex cast_on(R"(\bcast\s+on\s+(\d+)\s*(?:sts|stitches)\b)", std::regex::icase);
  std::smatch cast;
  const bool starred = std::any_of(rows.begin(), rows.end(), [](const WrittenRow& r) { return r.starred; });
  // A row with a '*' repeat that changes the count, in its repeat or its edge stitches.
  const bool shaped_repeat = std::any_of(rows.begin(), rows.end(), [](const WrittenRow& r) {
    return r.starred && (loops_made(r.repeat) != loops_taken(r.repeat) || loops_made(r.before) + loops_made(r.after) != r.edges());
  });
  if (std::regex_search(description, cast, cast_on) && (!starred || shaped_repeat)) {
    const int cast_on_count = count_of(cast[1].str());
    std::vector<WrittenRow> resolved = rows;
    bool stacks = true;
    int below = cast_on_count;
    for (size_t r = 0; r < resolved.size() && stacks; ++r) {
      if (!widen_repeat(resolved[r], below)) {
        // Shaped inside a repeat, the rows can only be a piece's: say which row does not fit.
        const WrittenRow& row = rows[r];
        const int width = loops_taken(row.repeat), room = below - row.edges();
        const std::string there = (r == 0 ? "the cast-on's " : "the row below's ") + std::to_string(below) + " sts" +
                                  (row.edges() > 0 ? " less the row's " + std::to_string(row.edges()) + " edge stitches" : "");
        const std::string left = row.edges() > 0 ? " (" + std::to_string(std::max(room, 0)) + ")" : "";
        throw Error(source, "line " + std::to_string(row.line),
                    "its '*' repeat takes " + std::to_string(width) + " loops, " +
                        (room < width ? "more than " + there + " leave" + left : "which do not fill " + there + left + " a whole number of times"));
      }
      const bool filled = fill_to(resolved[r], below, source);
      const int taken = loops_taken(resolved[r].repeat), made = loops_made(resolved[r].repeat);
      stacks = stacks && filled && (r == 0 || taken == below);
      if (!stacks && shaped_repeat) {
        // Shaped inside a repeat, the rows can only be a piece's: name the row that does not take what the row below made.
        const std::string what = filled ? "takes " + std::to_string(taken) + " loops" : "takes more loops beside its fill than that";
        throw Error(source, "line " + std::to_string(resolved[r].line),
                    std::string(r == 0 ? "the pattern casts on " : "the row below makes ") + std::to_string(below) + " sts, but this row " + what +
                        " (a piece cast on and shaped inside a '*' repeat takes, row by row, the loops the row below made)");
      }
      below = made;
      if (stacks && resolved[r].stated > 0 && resolved[r].stated != made)
        throw Error(source, "line " + std::to_string(resolved[r].line) + ", column " + std::to_string(resolved[r].stated_column),
                    "the row makes " + std::to_string(made) + " stitches, but the count written after it says " + std::to_string(resolved[r].stated));
      if (stacks && resolved[r].change && *resolved[r].change != made - taken)
        throw Error(source, "line " + std::to_string(resolved[r].line) + ", column " + std::to_string(resolved[r].stated_column),
                    "the row makes " + std::to_string(made) + " stitches from " + std::to_string(taken) + ", but the count written after it says " +
                        std::to_string(std::abs(*resolved[r].change)) + (*resolved[r].change >= 0 ? " increased" : " decreased"));
    }
    if (stacks) return shaped_piece(std::move(p), resolved, description, source);
  }
  for (const auto& row : rows)
    if (row.partial_fill > 0)
      throw Error(source, "line " + std::to_string(row.line) + ", column " + std::to_string(row.partial_fill),
                  "'knit', 'purl', 'k to end' or 'p to end' stands alone in a row of a stitch pattern; beside other stitches, or 'to last N sts', "
                  "only in a shaped piece ('Cast on N sts.', each row taking the loops the row below made)");

  // One repeat as wide as every row's: the least common multiple of their repeats' widths. Each row is laid out
  // whole, edge stitches and all, at one width, as seen from the front; the repeat is the window of that width
  // that lies inside every row's repeats and cuts no stitch (a decrease or a cable) in two.
  int width = 1, edges = rows[0].edges(), left = 0;
  for (const auto& row : rows) {
    width = std::lcm(width, loops_taken(row.repeat));
    if (width > 1000) throw Error(source, "line " + std::to_string(row.line), "makes the repeat wider than 1000 stitches");
    left = std::max(left, row.left_edge());
  }
  for (const auto& row : rows) {
    const bool fill = row.repeat.size() == 1 && row.repeat[0].kind == Item::Fill;
    if (!row.starred && !fill && loops_taken(row.repeat) != width)
      throw Error(source, "line " + std::to_string(row.line),
                  "is " + std::to_string(loops_taken(row.repeat)) + " stitches wide with no '*' repeat, but the pattern's repeat is " + std::to_string(width) +
                      ": write the rows as wide, or mark their repeats with '*...; rep from * to end'");
  }
  check_counts(rows, description, multiple_line, source);
  const int total = edges + 3 * width;
  std::vector<std::vector<Item>> whole;
  for (const auto& row : rows) {
    const int room = total - row.edges(), w = loops_taken(row.repeat);
    if (room < 0 || room % w != 0)
      throw Error(source, "line " + std::to_string(row.line),
                  "its edge stitches (" + std::to_string(row.edges()) + ") and repeat of " + std::to_string(w) + " do not fill the width of the first row's (" +
                      std::to_string(edges) + " edge stitches and repeats of " + std::to_string(loops_taken(rows[0].repeat)) + ")");
    whole.push_back(row.front(room / w));
  }
  const auto cuts = [&](const std::vector<Item>& row, int at) {  // does a stitch take loops on both sides of `at`?
    int x = 0;
    for (const auto& item : row) {
      if (x < at && x + taken(item) > at) return true;
      x += taken(item);
    }
    return false;
  };
  int start = -1;
  for (int c = left; c < left + width && start < 0; ++c)
    if (std::none_of(whole.begin(), whole.end(), [&](const auto& row) { return cuts(row, c) || cuts(row, c + width); })) start = c;
  if (start < 0) throw Error(source, "", "no window of " + std::to_string(width) + " stitches cuts every row between stitches");
  std::vector<int> row_line;
  for (size_t r = 0; r < rows.size(); ++r) {
    std::vector<Item> window;  // the items that start inside the repeat's window
    int x = 0;
    for (const auto& item : whole[r]) {
      if (x >= start && x < start + width) window.push_back(item);
      x += taken(item);
    }
    append_row(p, window);
    row_line.push_back(rows[r].line);
  }
  check_stacking(p, row_line, source);
  // The smallest repeat up the wale: "Rep Rows 1 and 2" makes rows 3 and 4 the same as 1 and 2.
  const int height = static_cast<int>(p.rows.size());
  const auto cables_of = [&](int r) {
    std::vector<std::array<int, 4>> out;
    for (const auto& c : p.cables)
      if (c.row == r) out.push_back({c.first_loop, c.over, c.under, c.order});
    return out;
  };
  for (int period = 1; period < height; ++period) {
    if (height % period != 0) continue;
    bool repeats = true;
    for (int r = period; r < height && repeats; ++r)
      repeats = p.rows[r] == p.rows[r % period] && cables_of(r) == cables_of(r % period) && (p.colours.empty() || p.colours[r] == p.colours[r % period]);
    if (!repeats) continue;
    p.rows.resize(period);
    if (!p.colours.empty()) p.colours.resize(period);
    p.cables.erase(std::remove_if(p.cables.begin(), p.cables.end(), [&](const PatternCable& c) { return c.row >= period; }), p.cables.end());
    break;
  }
  return p;
}

}  // namespace skein::mesh
