#pragma once
// Reading a JSON file a user wrote (jobs, sweeps): every error names the file, the key and what was expected.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "workflow/yarn_options.hpp"

namespace skein::cli {

/// Parses the text of a JSON file a user wrote; a syntax error names its byte, a number too large for a double
/// (found by fuzzing) is refused too, both as an Error naming the file.
inline nlohmann::json parse_user_json(const std::string& text, const std::filesystem::path& file) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(file.string(), "byte " + std::to_string(e.byte), std::string("is not valid JSON: ") + e.what());
  } catch (const nlohmann::json::exception& e) {
    throw Error(file.string(), "", std::string("is not valid JSON: ") + e.what());
  }
}

/// Reads the members of one JSON object of a job or sweep file, naming "key.sub" and what was expected in its errors.
class Keys {
  using json = nlohmann::json;
  using path = std::filesystem::path;

public:
  Keys(const json& object, std::string prefix, const path& file) : m_object(object), m_prefix(std::move(prefix)), m_file(file) {
    if (!object.is_object()) fail(m_prefix.empty() ? "the job" : m_prefix, "expected an object {...}, found " + object.dump());
  }

  /// Every key must be one of `known`.
  void only(const std::set<std::string>& known) const {
    for (const auto& [key, value] : m_object.items())
      if (!known.count(key)) {
        std::string names;
        for (const auto& k : known) names += (names.empty() ? "" : ", ") + k;
        fail(name(key), "is not a key here (known: " + names + ")");
      }
  }
  bool has(const std::string& key) const { return m_object.contains(key); }
  const json& at(const std::string& key) const { return m_object.at(key); }

  double number(const std::string& key, double fallback, double low, double high) const {
    if (!has(key)) return fallback;
    const auto& v = at(key);
    if (!v.is_number()) fail(name(key), "expected a number, found " + v.dump());
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < low || x > high) fail(name(key), "expected a number in [" + fmt(low) + ", " + fmt(high) + "], found " + v.dump());
    return x;
  }
  long integer(const std::string& key, long fallback, long low, long high) const {
    if (!has(key)) return fallback;
    const auto& v = at(key);
    if (!v.is_number_integer()) fail(name(key), "expected a whole number, found " + v.dump());
    const long x = v.get<long>();
    if (x < low || x > high) fail(name(key), "expected a whole number in [" + std::to_string(low) + ", " + std::to_string(high) + "], found " + v.dump());
    return x;
  }
  /// A yarn option's number, in the range the schema gives it (relax/yarn_options.hpp): the same as on the command
  /// line, in a project and in the app.
  double option(const std::string& key, double fallback) const {
    if (!has(key)) return fallback;
    const auto& spec = workflow::yarn_option(key);
    const auto& v = at(key);
    const bool whole = spec.kind == workflow::YarnOption::Kind::Integer;
    // A whole number may be written as 1e3 or 1000.0 (JSON has one kind of number).
    if (!v.is_number() || (whole && v.get<double>() != std::floor(v.get<double>())))
      fail(name(key), std::string("expected a ") + (whole ? "whole " : "") + "number, found " + v.dump());
    const double x = v.get<double>();
    if (!spec.allows(x)) fail(name(key), std::string("expected a ") + (whole ? "whole " : "") + "number in " + spec.range() + ", found " + v.dump());
    return x;
  }
  bool flag(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    if (!at(key).is_boolean()) fail(name(key), "expected true or false, found " + at(key).dump());
    return at(key).get<bool>();
  }
  std::string text(const std::string& key, const std::string& fallback) const {
    if (!has(key)) return fallback;
    if (!at(key).is_string() || at(key).get<std::string>().empty()) fail(name(key), "expected a non-empty string, found " + at(key).dump());
    return at(key).get<std::string>();
  }
  std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& choices) const {
    const std::string v = text(key, fallback);
    if (std::find(choices.begin(), choices.end(), v) == choices.end()) {
      std::string names;
      for (size_t i = 0; i < choices.size(); ++i)
        names += (i == 0 ? "\"" : i + 1 == choices.size() ? " or \"" : ", \"") + choices[i] + "\"";
      fail(name(key), "expected " + names + ", found \"" + v + "\"");
    }
    return v;
  }
  /// A file named relative to the file's folder, which must exist.
  path file(const std::string& key) const {
    const path p = (m_file.parent_path() / text(key, "")).lexically_normal();
    std::error_code error;  // a name the file system refuses (too long, ...) is an error in the job, not a crash
    if (!std::filesystem::exists(p, error)) fail(name(key), "names " + p.string() + ", which " + (error ? "cannot be read: " + error.message() : "does not exist"));
    return p;
  }
  std::string name(const std::string& key) const { return m_prefix.empty() ? key : m_prefix + "." + key; }
  [[noreturn]] void fail(const std::string& key, const std::string& rule) const { throw Error(m_file.string(), "key '" + key + "'", rule); }

private:
  static std::string fmt(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  }
  const json& m_object;
  std::string m_prefix;
  const path& m_file;
};

}  // namespace skein::cli
