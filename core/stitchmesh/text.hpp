#pragma once
// Small string helpers the pattern readers share (knit text, written instructions, charts, WIF drafts).
#include <algorithm>
#include <cctype>
#include <string>

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

}  // namespace skein::mesh
