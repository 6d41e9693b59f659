#pragma once
// What every text reader shares (knit text, written instructions, charts, WIF drafts, stitch models, smocking
// patterns, point ids): lines numbered from 1 with a byte-order mark and carriage returns dropped and a bound on
// their length, words with their columns, and the place an error names ("line 3, column 7").
#include <algorithm>
#include <cctype>
#include <istream>
#include <string>
#include <vector>

namespace skein {

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

/// The place in a text file an error names: "line 3", or "line 3, column 7" for a column above 0.
std::string text_place(int line, int column = 0);

/// Reads a text file line by line for a reader: numbers its lines from 1, drops a UTF-8 byte-order mark before the
/// first and the carriage return that ends a line written on Windows, and refuses a line longer than `longest`
/// bytes (0: no bound), naming the file and the line.
class LineReader {
public:
  LineReader(std::istream& in, std::string source, size_t longest = 0);
  bool next();  ///< the next line, false at the end
  const std::string& line() const { return m_line; }
  int number() const { return m_number; }
  std::string place(int column = 0) const { return text_place(m_number, column); }
  /// Throws skein::Error naming the file, this line (and `column` when above 0) and `rule`.
  [[noreturn]] void fail(const std::string& rule, int column = 0) const;

private:
  std::istream& m_in;
  std::string m_source, m_line;
  size_t m_longest;
  int m_number = 0;
};

}  // namespace skein
