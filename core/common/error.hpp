#pragma once
#include <stdexcept>
#include <string>

namespace skein {

/// The one error type thrown at every boundary with the outside (files, options, devices, edits).
/// what() reads "FILE:PLACE: RULE" so a user can find the problem without a debugger.
class Error : public std::runtime_error {
public:
  /// @param file   the file (or "" when none is involved)
  /// @param place  where in it: "line 12", "face 40", "edge 3-7" (or "")
  /// @param rule   what is wrong, as expected vs found
  Error(std::string file, std::string place, std::string rule);
  explicit Error(std::string rule) : Error("", "", std::move(rule)) {}

  const std::string& file() const { return m_file; }
  const std::string& place() const { return m_place; }
  const std::string& rule() const { return m_rule; }

private:
  std::string m_file, m_place, m_rule;
};

}  // namespace skein
