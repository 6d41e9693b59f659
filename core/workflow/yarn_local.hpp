#pragma once
// Local re-relaxation after stitch edits. Leaf 2018 (Limitations) names it a shortcoming that "every time a pattern is
// updated ... we completely recreate the yarn curves, discarding any relaxation progress": here the edited
// garment's yarn starts from the previous relaxed yarn wherever its stitches did not change, and only the
// changed stitches and a few rings of stitches around them relax, the rest held where it is.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "relax/yarn_curves.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/stitch_mesh.hpp"

namespace skein::workflow {

/// The new yarn's start from the previous relaxation. An unchanged stitch emits the very points it emitted
/// before, so each new point emitted where a previous one was takes that point's relaxed position; the rest
/// (the yarn of changed stitches) are emitted positions moved as the nearest matched point of their yarn.
struct Splice {
  Eigen::Matrix3Xd points;    ///< per point of the new yarn [mm]
  std::vector<char> matched;  ///< per point: emitted where a previous point was
  int changed() const;        ///< points not matched
};
/// `previous_relaxed` holds the relaxed positions of `previous_emitted`'s points (the same curves); throws
/// skein::Error when it does not.
Splice splice_previous(const relax::YarnCurves& emitted, const relax::YarnCurves& previous_emitted, const Eigen::Matrix3Xd& previous_relaxed);
/// The same from the previous relaxed yarn as curves (a .bcc read back, the app's last result); throws skein::Error
/// when they are not the curves of `previous_emitted` (curve or point counts differ: not relaxed from it).
Splice splice_previous(const relax::YarnCurves& emitted, const relax::YarnCurves& previous_emitted, const relax::YarnCurves& previous_relaxed);

/// Per point, its stitch: its own face, or for points of no face (cables, turns, borders) the face of the
/// nearest point along its yarn that has one (-1 when none does).
std::vector<int> owner_faces(const relax::YarnCurves& yarn);

/// Per face of `mesh`: 1 for the faces within `rings` rings of `seeds` (ring k: faces sharing a vertex with
/// ring k - 1; ring 0: the seeds).
std::vector<char> face_rings(const mesh::StitchMesh& mesh, const std::vector<int>& seeds, int rings);

struct LocalRelaxOptions {
  int rings = 1;               ///< faces within this many rings of a changed stitch relax
  int halo = 1;                ///< and this many rings more are held in place around them
  double boundary_move = 0.1;  ///< [r]: the rings grow by one while the outermost relaxed ring moves more
  int max_rings = 8;           ///< ... up to this many
  void validate() const;       ///< throws skein::Error for values out of range
};

struct LocalRelaxReport {
  int changed_points = 0;       ///< new points with no previous one
  int changed_stitches = 0;     ///< their stitches
  int rings = 0;                ///< rings relaxed in the end
  int relaxed_points = 0;       ///< points relaxed (last round)
  int held_points = 0;          ///< points held around them (last round)
  int rounds = 0;               ///< relaxations run (1 + growths)
  double last_boundary_move = 0;  ///< [r]: the outermost relaxed ring's largest move in the last round
  long splice_crossings = 0;    ///< centreline crossings on the way from the new emission to the splice
  long steps = 0;               ///< summed over rounds
  double wall_seconds = 0;      ///< the rounds, splice check included
  long pull_through_events = 0;  ///< the auditor's, summed (-1 when it did not run)
  bool converged = false;       ///< the last round
  relax::StopReason stopped_by = relax::StopReason::None;  ///< the last round's, or UnsafeSplice (nothing relaxed: relax it all)
};

/// Relaxes the changed stitches of `mesh` and `rings` rings around them (growing while the outermost ring
/// still moves), the `halo` rings beyond held in place and everything else untouched, starting from
/// `splice`. `emitted`: the yarn emitted from `mesh` (its positions give the rest lengths); `take_up` and
/// `take_up_by_type` as for make_yarn_system. Each round relaxes only the points it needs, with the CPU
/// relaxer, `options` and shape preservation from the mesh. The splice is certified first: the auditor runs on
/// the straight move from the new emission to the splice, and a crossing of new yarn (a segment with a point
/// not matched) stops it ("unsafe splice"), points unchanged; pairs of unchanged yarn kept their relation
/// through the previous, audited relaxation. Returns every point's position; points outside the relaxed rings
/// keep the splice's exactly.
Eigen::Matrix3Xd relax_locally(const mesh::StitchMesh& mesh, const relax::YarnCurves& emitted, const Splice& splice, const relax::YarnRelaxOptions& options,
                               const LocalRelaxOptions& local, double take_up, const std::map<std::string, double>& take_up_by_type,
                               LocalRelaxReport& report);

}  // namespace skein::workflow
