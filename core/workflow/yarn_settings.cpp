#include "workflow/yarn_settings.hpp"

#include <map>
#include <string>

#include "common/error.hpp"
#include "workflow/yarn_options.hpp"

namespace skein::workflow {

void YarnSettings::validate() const {
  // Every option's range as the schema gives it (yarn_options.hpp), then what ties options together.
  for (const auto& option : yarn_options())
    if (option.kind == YarnOption::Kind::Number || option.kind == YarnOption::Kind::Integer) option.check(std::stod(option.get(*this)));
  relax.validate();
  local.validate();
}

namespace {

/// The options a project saves, by their `set` keys (yarn.KEY), in the order they are written.
std::map<std::string, const YarnOption*> project_keys() {
  std::map<std::string, const YarnOption*> out;
  for (const auto& option : yarn_options())
    if (option.in_project) out["yarn." + option.key] = &option;
  return out;
}

}  // namespace

std::vector<mesh::ProjectSetting> yarn_setting_lines(const YarnSettings& settings) {
  std::vector<mesh::ProjectSetting> out;
  for (const auto& [key, option] : project_keys()) out.push_back({key, option->get(settings)});
  return out;
}

YarnSettings read_yarn_settings(const std::vector<mesh::ProjectSetting>& lines, const std::string& file) {
  YarnSettings settings;
  const auto place = [](const mesh::ProjectSetting& line) { return line.line > 0 ? "line " + std::to_string(line.line) : "setting " + line.key; };
  const auto keys = project_keys();
  for (const auto& line : lines) {
    const auto it = keys.find(line.key);
    if (it == keys.end()) {
      std::string known;
      for (const auto& [key, option] : keys) known += (known.empty() ? "" : ", ") + key;
      throw Error(file, place(line), "'" + line.key + "' is not a setting this skein knows (" + known + ")");
    }
    YarnSettings one = settings;
    try {
      it->second->set(one, line.value);
      one.validate();
    } catch (const Error& e) {
      throw Error(file, place(line), line.key + ": " + e.rule());
    }
    settings = one;
  }
  return settings;
}

}  // namespace skein::workflow
