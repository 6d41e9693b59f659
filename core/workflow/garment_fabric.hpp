#pragma once
// A garment's yarn as a yarn weight's fabric (issue 24; docs/yarn.md, "Garments of a yarn weight"): the weight's
// yarn relaxed at its compressed contact radius and written and drawn at its full one, each stitch's yarn cut (or
// let out) to Munden's loop length for the stitch width. `skein relax-yarn --yarn`, jobs' "yarn" and the app's
// Yarn settings share it.
#include <string>

#include "relax/yarn_system.hpp"
#include "stitchmesh/fabric.hpp"

namespace skein::workflow {

struct GarmentFabric {
  std::string yarn;                 ///< the weight class's name
  double radius = 0;                ///< [mm] its full radius: the yarn as written and drawn
  double contact_radius = 0;        ///< [mm] the radius it is emitted and relaxed at (mesh::kYarnCompression × radius)
  double munden_loop_length = 0;    ///< [mm] Munden's loop length for the stitch width (mesh::Gauge::loop_length)
};
/// The fabric of `weight` (a name or alias, mesh::find_yarn_weight) knitted at stitches of `size`.
GarmentFabric garment_fabric(const std::string& weight, const mesh::StitchSize& size);

/// A garment's yarn per stitch: all its rest lengths over its stitch faces (borders included); Munden's l for a
/// whole garment, as a repeat's yarn over its stitches is for a periodic patch.
double garment_loop_length(const relax::YarnSystem& system, int stitches);
/// The take-up that cuts (or lets out) yarn of `loop` mm per stitch to Munden's loop length `munden`; throws
/// skein::Error naming `file` and `option` outside 0.1 to 2, its rule ending in `remedy`.
double take_up_to_munden(double loop, double munden, const std::string& file, const std::string& option,
                         const std::string& remedy = "give --take-up");

}  // namespace skein::workflow
