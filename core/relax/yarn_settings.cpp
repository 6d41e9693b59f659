#include "relax/yarn_settings.hpp"

#include <charconv>
#include <functional>
#include <map>

#include "common/error.hpp"
#include "stitchmesh/fabric.hpp"

namespace skein::relax {
namespace {

std::string text(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);  // shortest form that reads back exactly
  return std::string(buf, r.ptr);
}

/// One key: how it is written from the settings and how a value is read into them.
struct Key {
  std::function<std::string(const YarnSettings&)> write;
  std::function<void(YarnSettings&, const std::string&)> read;
};

template <class T>
T number(const std::string& value) {
  T x{};
  const auto r = std::from_chars(value.data(), value.data() + value.size(), x);
  if (r.ec != std::errc() || r.ptr != value.data() + value.size())
    throw Error("", "", "'" + value + "' is not " + (std::is_integral_v<T> ? "an integer" : "a number"));
  return x;
}

bool boolean(const std::string& value) {
  if (value == "true") return true;
  if (value == "false") return false;
  throw Error("", "", "'" + value + "' is neither true nor false");
}

const std::map<std::string, Key>& keys() {
  static const std::map<std::string, Key> table{
      {"yarn.method", {[](const YarnSettings& s) { return to_string(s.relax.method); }, [](YarnSettings& s, const std::string& v) { s.relax.method = parse_yarn_method(v); }}},
      {"yarn.tolerance", {[](const YarnSettings& s) { return text(s.relax.tolerance); }, [](YarnSettings& s, const std::string& v) { s.relax.tolerance = number<double>(v); }}},
      {"yarn.max_steps", {[](const YarnSettings& s) { return std::to_string(s.relax.max_steps); }, [](YarnSettings& s, const std::string& v) { s.relax.max_steps = number<long>(v); }}},
      {"yarn.take_up", {[](const YarnSettings& s) { return text(s.take_up); }, [](YarnSettings& s, const std::string& v) { s.take_up = number<double>(v); }}},
      {"yarn.audit", {[](const YarnSettings& s) { return std::string(s.relax.audit ? "true" : "false"); }, [](YarnSettings& s, const std::string& v) { s.relax.audit = boolean(v); }}},
      {"yarn.active_set", {[](const YarnSettings& s) { return std::string(s.relax.active_set.enabled ? "true" : "false"); },
                           [](YarnSettings& s, const std::string& v) { s.relax.active_set.enabled = boolean(v); }}},
      {"yarn.contact_spacing", {[](const YarnSettings& s) { return text(s.relax.sampling.spacing); }, [](YarnSettings& s, const std::string& v) { s.relax.sampling.spacing = number<double>(v); }}},
      {"yarn.stop_scale", {[](const YarnSettings& s) { return std::string(s.relax.clipped_scale ? "clipped" : "first"); },
                           [](YarnSettings& s, const std::string& v) {
                             if (v != "first" && v != "clipped") throw Error("", "", "'" + v + "' is neither first nor clipped");
                             s.relax.clipped_scale = v == "clipped";
                           }}},
      {"yarn.jam_steps", {[](const YarnSettings& s) { return std::to_string(s.relax.jam_steps); }, [](YarnSettings& s, const std::string& v) { s.relax.jam_steps = number<long>(v); }}},
      {"yarn.rings", {[](const YarnSettings& s) { return std::to_string(s.local.rings); }, [](YarnSettings& s, const std::string& v) { s.local.rings = number<int>(v); }}},
      {"yarn.weight", {[](const YarnSettings& s) { return s.weight.empty() ? std::string("none") : s.weight; },
                       [](YarnSettings& s, const std::string& v) {
                         try {
                           s.weight = v == "none" ? std::string() : mesh::find_yarn_weight(v).name;
                         } catch (const Error& e) {
                           throw Error("", "", "'" + v + "' " + e.rule() + ", or none");
                         }
                       }}},
      {"yarn.halo", {[](const YarnSettings& s) { return std::to_string(s.local.halo); }, [](YarnSettings& s, const std::string& v) { s.local.halo = number<int>(v); }}},
  };
  return table;
}

}  // namespace

void YarnSettings::validate() const {
  relax.validate();
  local.validate();
  if (!(take_up >= 0.1 && take_up <= 10)) throw Error("", "yarn settings", "the take-up must be between 0.1 and 10, found " + std::to_string(take_up));
}

std::vector<mesh::ProjectSetting> yarn_setting_lines(const YarnSettings& settings) {
  std::vector<mesh::ProjectSetting> out;
  for (const auto& [key, how] : keys()) out.push_back({key, how.write(settings)});
  return out;
}

YarnSettings read_yarn_settings(const std::vector<mesh::ProjectSetting>& lines, const std::string& file) {
  YarnSettings settings;
  const auto place = [](const mesh::ProjectSetting& line) { return line.line > 0 ? "line " + std::to_string(line.line) : "setting " + line.key; };
  for (const auto& line : lines) {
    const auto it = keys().find(line.key);
    if (it == keys().end()) {
      std::string known;
      for (const auto& [key, how] : keys()) known += (known.empty() ? "" : ", ") + key;
      throw Error(file, place(line), "'" + line.key + "' is not a setting this skein knows (" + known + ")");
    }
    YarnSettings one = settings;
    try {
      it->second.read(one, line.value);
      one.validate();
    } catch (const Error& e) {
      throw Error(file, place(line), line.key + ": " + e.rule());
    }
    settings = one;
  }
  return settings;
}

}  // namespace skein::relax
