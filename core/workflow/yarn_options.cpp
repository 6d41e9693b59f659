#include "workflow/yarn_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "stitchmesh/fabric.hpp"

namespace skein::workflow {
namespace {

using Kind = YarnOption::Kind;

std::string text(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);  // shortest form that reads back exactly
  return std::string(buf, r.ptr);
}

template <class T>
T parse(const std::string& value) {
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

YarnOption make(std::string key, Kind kind, double low, double high, std::string unit, std::string help, bool in_project,
                std::function<std::string(const YarnSettings&)> get, std::function<void(YarnSettings&, const std::string&)> set) {
  YarnOption o;
  o.key = std::move(key);
  o.kind = kind;
  o.low = low;
  o.high = high;
  o.unit = std::move(unit);
  o.help = std::move(help);
  o.in_project = in_project;
  o.get = std::move(get);
  o.set = std::move(set);
  return o;
}

/// A real-valued option read and written through `field`, which gives the value's place in the settings.
YarnOption real(std::string key, double low, double high, std::string unit, std::string help, bool in_project,
                std::function<double&(YarnSettings&)> field) {
  return make(std::move(key), Kind::Number, low, high, std::move(unit), std::move(help), in_project,
              [field](const YarnSettings& s) {
                YarnSettings copy = s;
                return text(field(copy));
              },
              [field](YarnSettings& s, const std::string& v) { field(s) = parse<double>(v); });
}

template <class T>
YarnOption whole(std::string key, double low, double high, std::string unit, std::string help, bool in_project, std::function<T&(YarnSettings&)> field) {
  return make(std::move(key), Kind::Integer, low, high, std::move(unit), std::move(help), in_project,
              [field](const YarnSettings& s) {
                YarnSettings copy = s;
                return std::to_string(field(copy));
              },
              [field](YarnSettings& s, const std::string& v) { field(s) = parse<T>(v); });
}

YarnOption flag(std::string key, std::string help, bool in_project, std::function<bool&(YarnSettings&)> field) {
  return make(std::move(key), Kind::Flag, 0, 1, "", std::move(help), in_project,
              [field](const YarnSettings& s) {
                YarnSettings copy = s;
                return std::string(field(copy) ? "true" : "false");
              },
              [field](YarnSettings& s, const std::string& v) { field(s) = boolean(v); });
}

/// One of `choices`; `set` sees only those words (a weight's reader also takes its aliases: give it `own_reader`).
YarnOption choice(std::string key, std::vector<std::string> choices, std::string help, bool in_project, std::function<std::string(const YarnSettings&)> get,
                  std::function<void(YarnSettings&, const std::string&)> set, bool own_reader = false) {
  YarnOption o = make(std::move(key), Kind::Choice, 0, 0, "", std::move(help), in_project, std::move(get), {});
  o.choices = std::move(choices);
  std::string list;
  for (size_t i = 0; i < o.choices.size(); ++i) list += (i == 0 ? "" : i + 1 == o.choices.size() ? " or " : ", ") + o.choices[i];
  o.set = [set, own_reader, list, words = o.choices](YarnSettings& s, const std::string& v) {
    if (own_reader) {
      set(s, v);
    } else if (std::find(words.begin(), words.end(), v) == words.end()) {
      throw Error("", "", "'" + v + "' is not " + list);
    } else {
      set(s, v);
    }
  };
  return o;
}

constexpr double kSteps = 1e9;  // the most steps, rings of checkpoints ... anyone could mean
constexpr double kStiffness = 1e9;

std::vector<YarnOption> make_options() {
  std::vector<YarnOption> o;
  o.push_back(choice("method", {"fire", "euler", "lbfgs"}, "integrator: fire (quasi-static, fast), euler (Leaf Algorithm 1) or lbfgs (quasi-Newton, CPU)",
                     true, [](const YarnSettings& s) { return to_string(s.relax.method); },
                     [](YarnSettings& s, const std::string& v) { s.relax.method = relax::parse_yarn_method(v); }));
  o.push_back(choice("stop_rule", {"leaf", "force"},
                     "leaf (Leaf eq. 5: the tolerance and stall, relative to the first step) or force (the largest force per yarn length at "
                     "most the force tolerance × B/r³, and the energy fell less than the energy stall of itself over the stall window)",
                     false, [](const YarnSettings& s) { return to_string(s.relax.stop_rule); },
                     [](YarnSettings& s, const std::string& v) { s.relax.stop_rule = relax::parse_stop_rule(v); }));
  o.push_back(real("tolerance", 0, 1, "", "Leaf eq. 5 ε1: stop when |∇E| / |∇E₀| is below this ...", true,
                   [](YarnSettings& s) -> double& { return s.relax.tolerance; }));
  o.push_back(real("stall", 0, 1, "", "... and |∇E| changes by less than this fraction per step (ε2)", false,
                   [](YarnSettings& s) -> double& { return s.relax.stall; }));
  o.push_back(choice("stop_scale", {"first", "clipped"},
                     "Leaf eq. 5's |∇E₀|: first (whole) or clipped (each point's force clipped to the largest of all but the largest 0.1 %, so "
                     "that a few kinks of the emitted yarn do not end the run early; CPU only)",
                     true, [](const YarnSettings& s) { return std::string(s.relax.clipped_scale ? "clipped" : "first"); },
                     [](YarnSettings& s, const std::string& v) { s.relax.clipped_scale = v == "clipped"; }));
  YarnOption force = real("force_tolerance", 0, 1e6, "B/r³", "with the force rule: the largest force per yarn length", false,
                          [](YarnSettings& s) -> double& { return s.relax.force_tolerance; });
  force.above_low = true;
  o.push_back(force);
  o.push_back(whole<long>("stall_window", 1, kSteps, "steps", "with the force rule: steps of the energy's stall", false,
                          [](YarnSettings& s) -> long& { return s.relax.stall_window; }));
  o.push_back(real("energy_stall", 0, 1, "", "with the force rule: the energy's largest fall over the window, a share of itself", false,
                   [](YarnSettings& s) -> double& { return s.relax.energy_stall; }));
  o.push_back(whole<long>("max_steps", 0, kSteps, "steps", "step cap", true, [](YarnSettings& s) -> long& { return s.relax.max_steps; }));
  o.push_back(real("max_seconds", 0, 1e9, "s", "wall-time cap (0: none)", false, [](YarnSettings& s) -> double& { return s.relax.max_seconds; }));
  o.push_back(whole<long>("jam_steps", 0, kSteps, "steps",
                          "stop, not converged, when for this many steps in a row the guard held yarn against yarn on every step and the energy "
                          "fell by less than the jam drop of itself over them (0: never)",
                          true, [](YarnSettings& s) -> long& { return s.relax.jam_steps; }));
  o.push_back(real("jam_drop", 0, 1, "", "with the jam steps: the energy's relative fall over them that still counts as relaxing", false,
                   [](YarnSettings& s) -> double& { return s.relax.jam_drop; }));
  YarnOption move = real("max_move", 0, 10, "× r", "ε: largest move of any yarn point per step (at most half the contact margin)", false,
                         [](YarnSettings& s) -> double& { return s.relax.guard.max_move; });
  move.above_low = true;
  o.push_back(move);
  o.push_back(real("contact_margin", 0, 100, "× r", "contact cache margin beyond touching (at least twice the movement limit)", false,
                   [](YarnSettings& s) -> double& { return s.relax.contact_margin; }));
  o.back().above_low = true;
  o.push_back(real("time_step", 0, 10, "s", "Euler's step and FIRE's first step (0: 0.002 for Euler, 0.02 for FIRE)", false,
                   [](YarnSettings& s) -> double& { return s.relax.time_step; }));
  o.push_back(flag("audit", "audit every step for pull-through with the independent topology auditor", true,
                   [](YarnSettings& s) -> bool& { return s.relax.audit; }));
  o.back().cli = "--no-audit";
  o.push_back(flag("active_set", "converged points stop being integrated until their force grows or a neighbour moves (CPU only; the stop rule still sees every point)",
                   true, [](YarnSettings& s) -> bool& { return s.relax.active_set.enabled; }));
  o.push_back(real("contact_spacing", 0, relax::ContactSampling::kMaxCoveringSpacing, "× r",
                   "adaptive contact samples: the fewest per segment with no gap of yarn over this between two (at most 2√2 ≈ 2.828, so that "
                   "crossing yarns always feel contact; 0: Leaf's odd count over L / 2r)",
                   true, [](YarnSettings& s) -> double& { return s.relax.sampling.spacing; }));
  o.push_back(whole<long>("checkpoint_every", 0, kSteps, "steps", "steps between checkpoints", false,
                          [](YarnSettings& s) -> long& { return s.relax.checkpoint_every; }));
  o.push_back(real("checkpoint_minutes", 0, 1e6, "min", "minutes between checkpoints", false,
                   [](YarnSettings& s) -> double& { return s.relax.checkpoint_minutes; }));
  o.push_back(real("k_bend", 0, kStiffness, "", "bending stiffness (Leaf eq. 7)", false, [](YarnSettings& s) -> double& { return s.relax.params.k_bend; }));
  o.push_back(real("k_stretch", 0, kStiffness, "", "internal stretch stiffness (Leaf eq. 8)", false,
                   [](YarnSettings& s) -> double& { return s.relax.params.k_stretch; }));
  o.push_back(real("k_length", 0, kStiffness, "", "length penalty stiffness (Leaf eq. 1)", false,
                   [](YarnSettings& s) -> double& { return s.relax.params.k_length; }));
  YarnOption contact = real("k_contact", 0, kStiffness, "", "contact stiffness (Leaf eq. 9)", false,
                            [](YarnSettings& s) -> double& { return s.relax.params.k_contact; });
  contact.above_low = true;
  o.push_back(contact);
  o.push_back(real("k_global", 0, kStiffness, "", "mass-proportional damping (Leaf eq. 11), Euler only", false,
                   [](YarnSettings& s) -> double& { return s.relax.params.k_global; }));
  o.push_back(real("k_dt", 0, kStiffness, "", "tangential contact damping (Leaf eq. 12), Euler only", false,
                   [](YarnSettings& s) -> double& { return s.relax.params.k_dt; }));
  o.push_back(real("k_dn", 0, kStiffness, "", "normal contact damping (Leaf eq. 12), Euler only", false,
                   [](YarnSettings& s) -> double& { return s.relax.params.k_dn; }));
  o.push_back(real("take_up", 0.1, 10, "", "rest length of the yarn × its emitted length: below 1 the yarn pulls tighter (0.8: fabric under tension, where lace opens and ribs come in)", true,
                   [](YarnSettings& s) -> double& { return s.take_up; }));
  std::vector<std::string> weights{"none"};
  for (const auto& w : mesh::yarn_weights()) weights.push_back(w.name);
  o.push_back(choice("weight", weights,
                     "a yarn weight class: the yarn is emitted and relaxed at its compressed contact radius, cut to Munden's loop length for the "
                     "stitch width and drawn at its full radius (none: a tenth of the stitch width)",
                     true, [](const YarnSettings& s) { return s.weight.empty() ? std::string("none") : s.weight; },
                     [](YarnSettings& s, const std::string& v) {
                       try {
                         s.weight = v == "none" ? std::string() : mesh::find_yarn_weight(v).name;
                       } catch (const Error& e) {
                         throw Error("", "", "'" + v + "' " + e.rule() + ", or none");
                       }
                     },
                     true));
  o.back().cli = "--yarn";
  o.push_back(whole<int>("rings", 0, LocalRelaxOptions{}.max_rings, "rings", "after stitch edits: rings of stitches around the changed ones that relax (grown while the outermost still moves)",
                         true, [](YarnSettings& s) -> int& { return s.local.rings; }));
  o.push_back(whole<int>("halo", 1, 8, "rings", "after stitch edits: rings beyond those, held in place", true,
                         [](YarnSettings& s) -> int& { return s.local.halo; }));
  return o;
}

}  // namespace

std::string YarnOption::flag() const {
  if (!cli.empty()) return cli;
  std::string out = "--" + key;
  std::replace(out.begin(), out.end(), '_', '-');
  return out;
}

bool YarnOption::allows(double value) const {
  if (kind != Kind::Number && kind != Kind::Integer) return true;
  return std::isfinite(value) && (above_low ? value > low : value >= low) && value <= high;
}

std::string YarnOption::range() const {
  const auto shown = [](double x) {  // six digits: 2√2 as 2.82843
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return std::string(buf);
  };
  return (above_low ? "(" : "[") + shown(low) + ", " + shown(high) + "]";
}

void YarnOption::check(double value) const {
  if (!allows(value)) throw Error("", key, "must be in " + range() + (unit.empty() ? "" : " " + unit) + ", found " + text(value));
}

const std::vector<YarnOption>& yarn_options() {
  static const std::vector<YarnOption> all = make_options();
  return all;
}

const YarnOption& yarn_option(std::string_view key) {
  for (const auto& o : yarn_options())
    if (o.key == key) return o;
  throw Error("", std::string(key), "is not a yarn option");
}

}  // namespace skein::workflow
