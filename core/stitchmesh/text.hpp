#pragma once
// Small string helpers the pattern readers share (knit text, written instructions, charts, WIF drafts, smocking).
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

namespace skein::mesh {

/// `s` without leading and trailing spaces, tabs and carriage returns.
inline std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

/// `s` in lower case (ASCII letters; other bytes kept).
inline std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// A word of a line and where it starts.
struct Token {
  std::string text;
  int column;  ///< 1-based
};

/// The words of `line`, split at spaces, tabs and carriage returns.
inline std::vector<Token> split(const std::string& line) {
  std::vector<Token> out;
  for (size_t i = 0; i < line.size();) {
    if (std::isspace(static_cast<unsigned char>(line[i]))) {
      ++i;
      continue;
    }
    const size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    out.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return out;
}

}  // namespace skein::mesh
