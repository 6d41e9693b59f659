#pragma once
// The yarn relaxation's options as users set them, declared once (issue 23): name, kind, range, unit and help.
// The CLI's flags, job and sweep keys, a project's `set yarn.KEY` lines and the app's Yarn settings dialog all
// take their ranges and help from here, so an option has one range wherever it is given.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "workflow/yarn_settings.hpp"

namespace skein::workflow {

struct YarnOption {
  enum class Kind { Number, Integer, Flag, Choice };
  std::string key;   ///< job and sweep key; a project's `yarn.KEY`; the CLI's `--KEY` with '-' for '_'
  Kind kind = Kind::Number;
  double low = 0, high = 0;  ///< Number and Integer: the values allowed, inclusive ...
  bool above_low = false;    ///< ... except `low` itself when set (a stiffness that must be positive)
  std::vector<std::string> choices;  ///< Choice: the words allowed
  std::string unit;  ///< shown with the value ("× r", "s"); empty for a pure number
  std::string help;  ///< one line, for the CLI's help, the dialog's tooltip and docs
  bool in_project = false;  ///< saved with a project as `set yarn.KEY VALUE`
  std::string cli;          ///< the CLI's flag where it is not `--KEY` (audit: --no-audit; weight: --yarn)
  /// The value in `settings` as a project writes it, and set from such text (throws skein::Error with the rule
  /// broken, no file or place: the reader adds them).
  std::function<std::string(const YarnSettings&)> get;
  std::function<void(YarnSettings&, const std::string&)> set;

  std::string flag() const;  ///< `cli`, or "--" + the key with '-' for '_'
  bool allows(double value) const;
  std::string range() const;  ///< "[low, high]" or "(low, high]", for messages
  /// Throws skein::Error naming the key when `value` is out of range.
  void check(double value) const;
};

/// Every option, in the order the dialog and the docs list them.
const std::vector<YarnOption>& yarn_options();
/// One option by its key; throws skein::Error for a key that is none.
const YarnOption& yarn_option(std::string_view key);

}  // namespace skein::workflow
