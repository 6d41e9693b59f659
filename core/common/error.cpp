#include "common/error.hpp"

namespace skein {
namespace {
std::string compose(const std::string& file, const std::string& place, const std::string& rule) {
  std::string s;
  if (!file.empty()) s += file + ": ";
  if (!place.empty()) s += place + ": ";
  return s + rule;
}
}  // namespace

Error::Error(std::string file, std::string place, std::string rule)
    : std::runtime_error(compose(file, place, rule)),
      m_file(std::move(file)), m_place(std::move(place)), m_rule(std::move(rule)) {}
}  // namespace skein
