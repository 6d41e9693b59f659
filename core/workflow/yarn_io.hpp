#pragma once
#include <filesystem>
#include <string>
#include <utility>

#include "relax/yarn_curves.hpp"
#include "stitchmesh/stitch_mesh.hpp"

namespace skein::workflow {

using relax::YarnCurves;

/// Cem Yuksel's binary curve collection (.bcc): a 64-byte header ("BCC", 0x44, "C0" = Catmull-Rom, 3
/// dimensions, up axis, uint64 curve count, uint64 point count, 40 bytes of text), then per curve an int32
/// point count (negative for a closed loop) and its points as float xyz. Written atomically. `preview`: the
/// text says "skein preview" instead of "skein yarn" (yarn placed for a preview, not relaxed).
void write_bcc(const relax::YarnCurves& yarn, const std::filesystem::path& path, bool preview = false);
/// Reads a .bcc written by skein or any tool of that layout; per-point face and type are unknown (-1).
/// Throws skein::Error naming the file, the byte offset and the rule for malformed files.
relax::YarnCurves read_bcc(const std::filesystem::path& path);

/// OBJ polylines (`l` records, one per curve; closed curves repeat their first point), as Blender imports them.
/// `preview`: the first comment says "skein preview" instead of "skein yarn".
/// `unit` names what the coordinates are in, for the header comment (the caller scales them).
void write_obj_polylines(const relax::YarnCurves& yarn, const std::filesystem::path& path, bool preview = false, const std::string& unit = "mm");

/// A tube mesh around the Catmull-Rom curves, for any renderer.
struct TubeOptions {
  int sides = 8;              ///< polygon sides around the yarn
  int samples_per_segment = 4;  ///< spline samples between two control points
  std::string unit = "mm";      ///< what the coordinates are in, for the header comment
};
void write_tube_obj(const relax::YarnCurves& yarn, const std::filesystem::path& path, const TubeOptions& options = {});
/// The same tubes as glTF 2.0 (tinygltf): one mesh of triangles with normals, positions in metres (glTF's unit;
/// `yarn` in mm, options.unit ignored); binary (.glb) when `path` ends in .glb, else JSON with the buffer inside.
void write_tube_gltf(const relax::YarnCurves& yarn, const std::filesystem::path& path, const TubeOptions& options = {});

/// The stitch ids of a yarn's control points (issue 27), as CSV with a header: `point,curve,face,row,type` per
/// control point, numbered as the .bcc or OBJ written from the same yarn numbers them; `face` is the stitch-mesh
/// face the point was emitted in, `row` and `type` that face's; -1 and an empty type for a point of no face.
/// Throws skein::Error when the yarn names a face `mesh` does not have.
void write_point_ids(const relax::YarnCurves& yarn, const mesh::StitchMesh& mesh, const std::filesystem::path& path);

/// One control point's stitch, as a stitch ids file gives it.
struct PointId {
  int curve = 0, face = -1, row = -1;
  std::string type;
};
/// Reads a stitch ids file written for `yarn` (write_point_ids): one line per control point, in order, each on
/// the curve the yarn has it on. Throws skein::Error naming the file, the line and the rule broken (the header,
/// the field count, numbers, a point out of order, a curve that is not the point's, a face with no row or a
/// row with no face, more or fewer lines than the yarn has points).
std::vector<PointId> read_point_ids(const std::filesystem::path& path, const relax::YarnCurves& yarn);

/// Rings of `sides` points of the given radius around a sampled curve, in a parallel-transported frame so
/// that the tube does not twist: one ring per sample.
std::vector<std::vector<Eigen::Vector3d>> tube_rings(const std::vector<Eigen::Vector3d>& samples, double radius, int sides);

/// Samples the Catmull-Rom curves (uniform parameterisation, as in the .bcc "C0" type).
std::vector<std::vector<Eigen::Vector3d>> sample_curves(const relax::YarnCurves& yarn, int samples_per_segment);

/// Figures of a yarn set: counts, total control-polygon length, and the smallest distance between two
/// non-adjacent control-polygon segments, found with a uniform grid. Segments are adjacent when they share a
/// point or lie less than 2r apart along one yarn (a tight bend of one yarn is not a contact).
struct YarnStats {
  int curves = 0, closed_curves = 0, control_points = 0;
  double total_length = 0;          ///< [mm], control polygon
  double min_segment_distance = 0;  ///< [mm]; exact below 2r (where yarns overlap); +inf when no two come that close
  std::pair<int, int> closest{-1, -1};  ///< first points of the two closest segments
  double radius = 0;
};
YarnStats yarn_stats(const relax::YarnCurves& yarn);

}  // namespace skein::workflow
