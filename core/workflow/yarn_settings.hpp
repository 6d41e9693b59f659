#pragma once
#include <string>
#include <vector>

#include "relax/yarn_relax.hpp"
#include "stitchmesh/project.hpp"
#include "workflow/yarn_local.hpp"

namespace skein::workflow {

/// What a yarn relaxation (whole, or local after stitch edits) and the stand-in preview run with, as the app
/// sets it (Relax > Yarn settings) and saves it with the project: the CLI's relax-yarn options of the same names.
struct YarnSettings {
  relax::YarnRelaxOptions relax;   ///< method, stop rule, audit, active set, contact sampling
  double take_up = 1.0;     ///< rest length of the yarn × its emitted length (make_yarn_system); not used with a weight
  /// A yarn weight class (mesh::yarn_weights' name), or empty: the yarn emitted at a tenth of the stitch width. With
  /// one, the yarn is emitted and relaxed at the weight's compressed contact radius, cut to Munden's loop length for
  /// the stitch width and drawn at its full radius (garment_fabric), as relax-yarn --yarn does.
  std::string weight;
  LocalRelaxOptions local;  ///< rings relaxed and held after stitch edits
  void validate() const;    ///< throws skein::Error for a value out of range
};

/// The settings as a project's `set` lines, every key written (docs/FORMATS.md: yarn.method, yarn.tolerance,
/// yarn.stop_scale, yarn.max_steps, yarn.take_up, yarn.audit, yarn.active_set, yarn.contact_spacing,
/// yarn.jam_steps, yarn.rings, yarn.halo, yarn.weight).
std::vector<mesh::ProjectSetting> yarn_setting_lines(const YarnSettings& settings);

/// The settings a project's `set` lines give, the defaults where a key is missing; throws skein::Error naming
/// `file`, the line and the rule broken for a key this skein does not know (the yarn's are the only settings a
/// project holds), a value that is not one, or a value out of range.
YarnSettings read_yarn_settings(const std::vector<mesh::ProjectSetting>& lines, const std::string& file);

}  // namespace skein::workflow
