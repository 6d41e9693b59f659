#pragma once
#include <string>
#include <vector>

#include "stitchmesh/input_mesh.hpp"

namespace skein::models {

/// The bundled garment meshes, built from rings of quads with a clean row structure (y up, front +z, mm).
/// Each is deterministic, so the committed files in models/ can be checked against a fresh build.
mesh::InputMesh swatch();   ///< flat 120 x 100 mm piece, 4 x 4 quads
mesh::InputMesh tube();     ///< open cylinder, 12 quads around, 5 rings
mesh::InputMesh beanie();   ///< brim, body and a crown that narrows to a small opening (crown decreases)
mesh::InputMesh mitten();   ///< cuff, hand with a thumb joined at the gusset, closed top
mesh::InputMesh tea_cozy(); ///< two panels with spout and handle openings, joined under a dome
mesh::InputMesh sweater();  ///< body, two sleeves joined at the armholes into a yoke, neck opening

struct Garment {
  std::string name;
  mesh::InputMesh (*make)();
};
/// All of them, in the order above.
const std::vector<Garment>& garments();

}  // namespace skein::models
