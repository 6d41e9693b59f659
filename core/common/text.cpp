#include "common/text.hpp"

#include "common/error.hpp"

namespace skein {

std::string text_place(int line, int column) {
  return "line " + std::to_string(line) + (column > 0 ? ", column " + std::to_string(column) : "");
}

LineReader::LineReader(std::istream& in, std::string source, size_t longest) : m_in(in), m_source(std::move(source)), m_longest(longest) {}

bool LineReader::next() {
  if (!std::getline(m_in, m_line)) return false;
  ++m_number;
  if (m_number == 1 && m_line.rfind("\xEF\xBB\xBF", 0) == 0) m_line.erase(0, 3);  // a UTF-8 byte-order mark is not text
  if (!m_line.empty() && m_line.back() == '\r') m_line.pop_back();
  if (m_longest > 0 && m_line.size() > m_longest) fail("is longer than " + std::to_string(m_longest) + " characters");
  return true;
}

void LineReader::fail(const std::string& rule, int column) const { throw Error(m_source, place(column), rule); }

}  // namespace skein
