#include "stitchmesh/colours.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <regex>

#include "common/error.hpp"
#include "common/text.hpp"
#include "stitchmesh/stitch_types.hpp"

namespace skein::mesh {
namespace {

std::array<double, 3> from_hex(unsigned value) {
  return {((value >> 16) & 0xff) / 255.0, ((value >> 8) & 0xff) / 255.0, (value & 0xff) / 255.0};
}

/// Colour words as yarn labels name them, and the sRGB skein draws them in.
struct NamedColour {
  const char* word;
  unsigned hex;
};
constexpr NamedColour kNamedColours[] = {
    {"white", 0xf4f4f0},  {"cream", 0xf0e6cf},    {"natural", 0xe9dcc3}, {"ivory", 0xf3efdf},  {"ecru", 0xe4d9bf},   {"oatmeal", 0xd8ccb4},
    {"beige", 0xd9c7a5},  {"tan", 0xc19a6b},      {"brown", 0x6e4a2e},   {"chocolate", 0x4a2c1d}, {"black", 0x1e1e1e}, {"charcoal", 0x3a3d40},
    {"grey", 0x8c8c8c},   {"gray", 0x8c8c8c},     {"silver", 0xbfc1c2},  {"red", 0xb3261e},    {"scarlet", 0xc8281e}, {"burgundy", 0x6d1a2a},
    {"wine", 0x6d1a2a},   {"pink", 0xe8a0b4},     {"rose", 0xc96a7f},    {"orange", 0xe07b24}, {"rust", 0xa8471f},   {"yellow", 0xf0cf3c},
    {"gold", 0xd4a531},   {"mustard", 0xc99a2e},  {"green", 0x3f7d3a},   {"olive", 0x6b6b2a},  {"moss", 0x667a3a},   {"forest", 0x2a4d2e},
    {"teal", 0x24777a},   {"turquoise", 0x3fb0ac}, {"blue", 0x2f5fa8},   {"navy", 0x1f2a44},   {"denim", 0x4a6a8f},  {"sky", 0x8cb8e0},
    {"purple", 0x6a3d8a}, {"violet", 0x7b4fa8},   {"lilac", 0xb9a2d0},   {"plum", 0x5e2750}};

/// Colours for a palette that names none: light, dark and bright ones that stay apart side by side.
constexpr unsigned kDefaultColours[] = {0xf0e6cf, 0x1f2a44, 0xb3261e, 0x3f7d3a, 0xd4a531, 0x8c8c8c, 0x6a3d8a, 0x24777a};

}  // namespace

std::optional<PatternColour> read_colour_declaration(const std::string& line, bool prefix_optional, int index, const std::string& source,
                                                     const std::string& where) {
  static const std::regex with_prefix(R"(^\s*(?:colou?r|yarn)\s+([A-Za-z0-9]+)\s*(?:\(\s*([A-Za-z0-9]+)\s*\)\s*)?[:=]\s*(.*?)\s*$)", std::regex::icase);
  static const std::regex bare(R"(^\s*(MC|CC[1-9]?|[A-Z])\s*(?:\(\s*([A-Za-z0-9]+)\s*\)\s*)?[:=]\s*(.*?)\s*$)", std::regex::icase);
  std::smatch m;
  if (!std::regex_match(line, m, with_prefix) && !(prefix_optional && std::regex_match(line, m, bare))) return std::nullopt;
  PatternColour c;
  c.name = m[1].str();
  c.alias = m[2].str();
  for (const std::string& name : {c.name, c.alias}) {
    if (name.empty()) continue;
    const std::string lowered = lower(name);
    if (name.size() > 8) throw Error(source, where, "a colour's name is at most 8 letters or digits, found '" + name + "'");
    if (lowered == "k" || lowered == "p" || find_stitch_type(lowered) || std::isdigit(static_cast<unsigned char>(lowered[0])))
      throw Error(source, where, "'" + name + "' cannot name a colour: it reads as a stitch or a count (name colours MC, CC, A, B, ...)");
  }
  std::string body = m[3].str();
  static const std::regex hex(R"(#([0-9A-Za-z]*))"), bare_hex(R"(\b([0-9A-Fa-f]{6})\b)");
  std::smatch h;
  bool have = false;
  if (!std::regex_search(body, h, hex)) std::regex_search(body, h, bare_hex);  // "1f2a44": a code without its '#'
  const std::string code = h.empty() ? std::string() : h.str(0);  // one string: begin() and end() of the same one
  if (!code.empty() && (code[0] == '#' || std::any_of(code.begin(), code.end(), [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)); }))) {
    if (h[1].length() != 6 || !std::all_of(h[1].first, h[1].second, [](char ch) { return std::isxdigit(static_cast<unsigned char>(ch)); }))
      throw Error(source, where, "a colour code is # and six hex digits (#f0e6cf), found '" + h.str(0) + "'");
    c.srgb = from_hex(static_cast<unsigned>(std::stoul(h[1].str(), nullptr, 16)));
    have = true;
    body.erase(static_cast<size_t>(h.position(0)), static_cast<size_t>(h.length(0)));
    static const std::regex empty_brackets(R"(\(\s*\))");
    body = std::regex_replace(body, empty_brackets, "");
  }
  c.description = trim(body);
  if (!have) {
    const std::string words = lower(c.description);
    size_t best = std::string::npos;
    for (const auto& named : kNamedColours) {
      std::smatch w;
      const std::regex word("\\b" + std::string(named.word) + "\\b");
      if (std::regex_search(words, w, word) && static_cast<size_t>(w.position(0)) < best) {
        best = static_cast<size_t>(w.position(0));
        c.srgb = from_hex(named.hex);
        have = true;
      }
    }
  }
  if (!have) c.srgb = from_hex(kDefaultColours[static_cast<size_t>(index) % std::size(kDefaultColours)]);
  return c;
}

size_t comment_start(const std::string& line) {
  for (size_t at = line.find('#'); at != std::string::npos; at = line.find('#', at + 1))
    if (at + 1 == line.size() || !std::isalnum(static_cast<unsigned char>(line[at + 1]))) return at;
  return std::string::npos;
}

void check_new_colour(const std::vector<PatternColour>& palette, const PatternColour& c, const std::string& source, const std::string& where) {
  for (const std::string& name : {c.name, c.alias})
    if (!name.empty() && find_colour(palette, name) >= 0) throw Error(source, where, "colour '" + name + "' is declared twice");
}

std::string colour_code(const std::array<double, 3>& srgb) {
  char text[8];
  const auto byte = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
  std::snprintf(text, sizeof text, "#%02x%02x%02x", byte(srgb[0]), byte(srgb[1]), byte(srgb[2]));
  return text;
}

int find_colour(const std::vector<PatternColour>& palette, const std::string& name) {
  const std::string wanted = lower(name);
  for (size_t i = 0; i < palette.size(); ++i)
    if (lower(palette[i].name) == wanted || (!palette[i].alias.empty() && lower(palette[i].alias) == wanted)) return static_cast<int>(i);
  return -1;
}

std::vector<int> merge_palette(std::vector<PatternColour>& palette, const std::vector<PatternColour>& added) {
  std::vector<int> index;
  for (const auto& c : added) {
    int i = find_colour(palette, c.name);
    if (i < 0) i = static_cast<int>(palette.size()), palette.push_back(c);
    index.push_back(i);
  }
  return index;
}

void colour_yarn(relax::YarnCurves& yarn, const std::vector<int>& face_colour, const std::vector<PatternColour>& palette) {
  yarn.point_colour.clear();
  yarn.colours.clear();
  if (palette.empty()) return;
  for (const auto& c : palette) yarn.colours.push_back({c.name, c.srgb});
  const int n = static_cast<int>(yarn.points.size());
  const auto of_face = [&](int p) {
    const int f = p < static_cast<int>(yarn.point_face.size()) ? yarn.point_face[p] : -1;
    return f >= 0 && f < static_cast<int>(face_colour.size()) ? face_colour[f] : -1;
  };
  yarn.point_colour.assign(n, -1);
  for (int c = 0; c < yarn.curves(); ++c) {
    const int begin = yarn.curve_start[c], end = yarn.curve_start[c + 1];
    for (int p = begin; p < end; ++p) yarn.point_colour[p] = of_face(p);
    // Points of no face: the nearest coloured point along the yarn (the earlier one on a tie), else the first colour.
    std::vector<int> filled(yarn.point_colour.begin() + begin, yarn.point_colour.begin() + end);
    for (int p = begin; p < end; ++p) {
      if (yarn.point_colour[p] >= 0) continue;
      int colour = -1;
      for (int d = 1; d < end - begin && colour < 0; ++d) {
        if (p - d >= begin && filled[p - d - begin] >= 0) colour = filled[p - d - begin];
        else if (p + d < end && filled[p + d - begin] >= 0) colour = filled[p + d - begin];
      }
      yarn.point_colour[p] = colour >= 0 ? colour : 0;
    }
  }
}

std::vector<double> yarn_length_by_colour(const relax::YarnCurves& yarn) {
  std::vector<double> length(yarn.colours.size(), 0.0);
  if (yarn.point_colour.size() != yarn.points.size()) return length;
  for (int c = 0; c < yarn.curves(); ++c) {
    const int begin = yarn.curve_start[c], end = yarn.curve_start[c + 1];
    for (int p = begin; p < end; ++p) {
      const int q = p + 1 < end ? p + 1 : (yarn.closed[c] ? begin : -1);
      if (q >= 0) length[yarn.point_colour[p]] += (yarn.points[q] - yarn.points[p]).norm();
    }
  }
  return length;
}

}  // namespace skein::mesh
