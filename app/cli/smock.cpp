#include "smock.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/gltf_mesh.hpp"
#include "render/raster.hpp"
#include "render/smocking_view.hpp"

namespace skein::cli {
namespace {

json matrix_json(const Eigen::MatrixXd& m) {
  json out = json::array();
  for (int c = 0; c < m.cols(); ++c) {
    json col = json::array();
    for (int r = 0; r < m.rows(); ++r) col.push_back(m(r, c));
    out.push_back(std::move(col));
  }
  return out;
}

/// The lifted threads (eqs. 6-8) as OBJ: each stitch from its first point down or up to its midpoint and on to
/// its second point, two-point `l` records (every OBJ importer keeps those whole).
void write_threads_obj(const smocking::Embedding& e, const smocking::Lift& lift, const std::string& path) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# skein smock: the threads' positional constraints (Zhou 2024 eqs. 6-8) [mm], z towards the front\n";
    std::vector<int> vertex_of(e.rest.cols(), 0);
    for (size_t k = 0; k < lift.points.size(); ++k) {
      vertex_of[lift.points[k]] = static_cast<int>(k) + 1;
      out << "v " << lift.point_positions(0, k) << " " << lift.point_positions(1, k) << " 0\n";
    }
    for (int k = 0; k < lift.midpoints.cols(); ++k) out << "v " << lift.midpoints(0, k) << " " << lift.midpoints(1, k) << " " << lift.midpoints(2, k) << "\n";
    int thread = -1;
    for (size_t k = 0; k < e.stitches.size(); ++k) {
      const auto& s = e.stitches[k];
      if (s.thread != thread) out << "o thread_" << (thread = s.thread) << "\n";
      const int m = static_cast<int>(lift.points.size() + k) + 1;
      out << "l " << vertex_of[s.a] << " " << m << "\nl " << m << " " << vertex_of[s.b] << "\n";
    }
  });
}

/// The smocked fabric as a triangle mesh [mm], z towards the front: OBJ, or glTF (.glb, .gltf; in metres) with
/// smooth normals and a two-sided fabric material, by the path's extension.
void write_cloth(const smocking::Cloth& cloth, const std::string& path) {
  const auto extension = std::filesystem::path(path).extension();
  if (extension == ".obj") {
    write_file_atomically(path, [&](std::ostream& out) {
      out << "# skein smock: the smocked fabric (Zhou 2024 §4.2) [mm], z towards the front\n";
      for (int v = 0; v < cloth.positions.cols(); ++v) out << "v " << cloth.positions(0, v) << " " << cloth.positions(1, v) << " " << cloth.positions(2, v) << "\n";
      for (const auto& t : cloth.triangles) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
    });
    return;
  }
  GltfMesh mesh;
  mesh.mesh_name = "fabric";
  mesh.node_name = "skein smocked fabric";
  Eigen::Matrix3Xd normals = Eigen::Matrix3Xd::Zero(3, cloth.positions.cols());
  GltfPrimitive fabric;
  fabric.material = "fabric";
  fabric.linear_rgb = {0.78, 0.70, 0.86};  // draw_smocked_fabric's light cloth colour
  fabric.double_sided = true;
  for (const auto& t : cloth.triangles) {
    const Eigen::Vector3d n = (cloth.positions.col(t[1]) - cloth.positions.col(t[0])).cross(cloth.positions.col(t[2]) - cloth.positions.col(t[0]));
    for (int v : t) {
      normals.col(v) += n;  // area-weighted
      fabric.indices.push_back(static_cast<std::uint32_t>(v));
    }
  }
  for (int v = 0; v < cloth.positions.cols(); ++v) {
    const double length = normals.col(v).norm();
    const Eigen::Vector3d n = length > 0 ? Eigen::Vector3d(normals.col(v) / length) : Eigen::Vector3d::UnitZ();
    mesh.positions.push_back({cloth.positions(0, v), cloth.positions(1, v), cloth.positions(2, v)});
    mesh.normals.push_back({n.x(), n.y(), n.z()});
  }
  mesh.primitives.push_back(std::move(fabric));
  write_gltf_mesh(mesh, path);
}

}  // namespace

json smock(SmockArgs args) {
  const bool drawing = std::filesystem::path(args.input).extension() == ".svg";
  if (!drawing && !args.style.empty()) throw Error("", "--style", "is for an .svg drawing; a .smock file says its style itself");
  if (drawing) {
    if (args.style == "canadian") args.svg.style = smocking::Style::Canadian;
    else if (args.style == "english") args.svg.style = smocking::Style::English;
    else if (!args.style.empty() && args.style != "italian") throw Error("", "--style", "expected italian, canadian or english, found \"" + args.style + "\"");
  }
  const auto pattern = drawing ? smocking::read_smocking_svg(args.input, args.svg) : smocking::read_smocking_pattern(args.input);
  auto& o = args.options;
  o.gamma = args.gamma.value_or(pattern.gamma);
  if (args.pull == "along") {
    o.pull_along_stitches = true;
  } else {
    double px = 0, py = 0;
    char comma = 0, rest = 0;
    std::istringstream in(args.pull);
    if (!(in >> px >> comma >> py) || comma != ',' || (in >> rest))
      throw Error("", "--pull", "expected X,Y (the pulling direction) or \"along\", found \"" + args.pull + "\"");
    o.pull = {px, py};
    if (!o.pull.allFinite() || o.pull.norm() == 0) throw Error("", "--pull", "a pulling direction of non-zero length, found \"" + args.pull + "\"");
  }
  try {
    args.cloth_options.validate();
  } catch (const Error& e) {  // only --subdivisions of the cloth's options is set from the command line
    throw Error("", "--" + e.place(), e.rule());
  }
  if (const auto ext = std::filesystem::path(args.cloth).extension(); !args.cloth.empty() && ext != ".obj" && ext != ".glb" && ext != ".gltf")
    throw Error(args.cloth, "--cloth", "writes .obj, .glb or .gltf, found '" + ext.string() + "'");
  for (const auto& [option, path] : {std::pair{"--png", args.png}, {"--chart-png", args.chart_png}, {"--cloth-png", args.cloth_png}})
    if (!path.empty() && std::filesystem::path(path).extension() != ".png")
      throw Error(path, option, "writes a PNG picture: name it .png, found '" + std::filesystem::path(path).extension().string() + "'");
  for (const auto& path : {args.output, args.obj, args.png, args.chart_png, args.report, args.write_smock, args.cloth, args.cloth_png})
    if (!path.empty() && path != "-") check_writable(path);
  if (!args.write_smock.empty()) {
    write_file_atomically(args.write_smock, [&](std::ostream& out) { out << smocking::smocking_text(pattern); });
    spdlog::info("wrote {}", args.write_smock);
  }
  spdlog::info("{}: {} smocking, {} x {} grid points {} mm apart, {} thread{}, {} stitches; gathering to gamma {}", args.input,
               style_name(pattern.style), pattern.columns, pattern.rows, pattern.spacing, pattern.threads.size(), pattern.threads.size() == 1 ? "" : "s",
               pattern.num_stitches(), o.gamma);
  const Stopwatch clock;
  const auto e = smocking::embed(pattern, o);
  const double seconds = clock.seconds();
  const auto lift = smocking::lift(e);
  spdlog::info("{} after {} iterations: the threads at {:.4f} of their sewn length (goal {}), the fabric off eq. 1b by up to {:.1f} %", stop_name(e.stopped),
               e.iterations, e.shrinkage_before_settling, o.gamma, 100 * e.stretch_before_settling);
  if (e.stopped == smocking::EmbedStop::Stalled && pattern.style != smocking::Style::Canadian && e.shrinkage() < 1.02 * e.taut())
    spdlog::warn("the threads are taut: every stitch is down to the fabric's thickness ({:.3g} mm), {:.4f} of their sewn length (eq. 1c's lower bound); "
                 "a smaller --thickness or a larger gamma", e.thickness, e.taut());
  else if (e.stopped != smocking::EmbedStop::Reached)
    spdlog::warn("the threads did not reach gamma {}: {}", o.gamma,
                 e.stopped == smocking::EmbedStop::Stalled ? "they stopped shortening (stitches across the pull do not shorten: try --pull along)" : "the iteration cap");
  for (double f : o.snapshots)
    if (std::none_of(e.snapshots.begin(), e.snapshots.end(), [&](const auto& s) { return s.first == f; }))
      spdlog::warn("no snapshot at {}: the threads got to {:.4f} of their length", f, e.shrinkage());
  if (o.settle && (e.largest_stretch > 1.001 * o.settle_tolerance || e.shortest_fabric < 1 - 1.001 * o.settle_tolerance))
    spdlog::warn("eq. 1b does not hold where the run ended: the fabric stretched {:.1f} %, neighbours {:.2f} thicknesses apart (the threads ask more "
                 "of the fabric than it can give without folding over itself)",
                 100 * e.largest_stretch, e.shortest_fabric);
  if (o.settle)
    spdlog::info("settled in {} sweeps: the threads at {:.4f}, the fabric stretched at most {:.2f} %, neighbours at least {:.2f} thicknesses apart ({:.3f} s in all)",
                 e.settle_iterations, e.shrinkage(), 100 * e.largest_stretch, e.shortest_fabric, seconds);
  json report = {{"input", args.input},
                 {"pattern", pattern.name},
                 {"source", pattern.note},
                 {"style", style_name(pattern.style)},
                 {"grid", {pattern.columns, pattern.rows}},
                 {"spacing_mm", pattern.spacing},
                 {"threads", pattern.threads.size()},
                 {"stitches", e.stitches.size()},
                 {"stitching_points", lift.points.size()},
                 {"gamma", o.gamma},
                 {"thickness_mm", e.thickness},
                 {"pull", o.pull_along_stitches ? json("along") : json({o.pull.x(), o.pull.y()})},
                 {"stopped_by", stop_name(e.stopped)},
                 {"iterations", e.iterations},
                 {"settle_iterations", e.settle_iterations},
                 {"largest_fabric_violation_before_settling", e.stretch_before_settling},
                 {"shrinkage_before_settling", e.shrinkage_before_settling},
                 {"seconds", seconds},
                 {"thread_length_sewn_mm", e.threads_rest},
                 {"thread_length_mm", e.threads},
                 {"shrinkage", e.shrinkage()},
                 {"taut", pattern.style == smocking::Style::Canadian ? json(nullptr) : json(e.taut())},  // knots aim at 0, not τ
                 {"largest_fabric_stretch", e.largest_stretch},
                 {"closest_fabric_over_thickness", e.shortest_fabric}};
  std::optional<smocking::Cloth> cloth;
  if (!args.cloth.empty() || !args.cloth_png.empty()) {
    Stopwatch watch;
    cloth = smocking::smock_cloth(pattern, e, lift, args.cloth_options);
    const long crossings = smocking::exact_intersections(*cloth);
    const double cloth_seconds = watch.seconds();
    spdlog::info("3-D fabric: {} points, {} triangles, {} frames, {} Newton steps ({} cut short by the collision bound), {:.1f} s; "
                 "closest non-neighbours {:.3f} mm (barrier reach {:.3f} mm), {} intersecting triangle pairs",
                 cloth->positions.cols(), cloth->triangles.size(), cloth->frames, cloth->newton_iterations, cloth->ccd_limited_steps, cloth_seconds,
                 cloth->smallest_distance, cloth->reach, crossings);
    report["cloth"] = {{"points", cloth->positions.cols()},
                       {"triangles", cloth->triangles.size()},
                       {"subdivisions", args.cloth_options.subdivisions},
                       {"frames", cloth->frames},
                       {"newton_iterations", cloth->newton_iterations},
                       {"collision_limited_steps", cloth->ccd_limited_steps},
                       {"shifted_steps", cloth->shifted_steps},
                       {"seconds", cloth_seconds},
                       {"energy", cloth->energy},
                       {"barrier_reach_mm", cloth->reach},
                       {"barrier_stiffness", cloth->barrier_stiffness},
                       {"smallest_distance_mm", cloth->smallest_distance},
                       {"largest_stretch", cloth->largest_stretch},
                       {"target_rms_mm", cloth->target_error},
                       {"intersections", crossings}};
  }
  if (!args.output.empty()) {
    json out = report;
    out["rest"] = matrix_json(e.rest);
    out["positions"] = matrix_json(e.positions);
    json stitches = json::array();
    for (size_t k = 0; k < e.stitches.size(); ++k) {
      const auto& s = e.stitches[k];
      stitches.push_back({{"thread", s.thread}, {"from", s.a}, {"to", s.b}, {"side", s.front ? "front" : "back"},
                          {"midpoint", {lift.midpoints(0, k), lift.midpoints(1, k), lift.midpoints(2, k)}}});
    }
    out["stitches_lifted"] = std::move(stitches);
    out["stitching_point_indices"] = lift.points;
    out["stitching_point_positions"] = matrix_json(lift.point_positions);
    json snapshots = json::array();
    for (const auto& [fraction, x] : e.snapshots) snapshots.push_back({{"fraction", fraction}, {"positions", matrix_json(x)}});
    out["snapshots"] = std::move(snapshots);
    write_json(out, args.output);
  }
  if (!args.obj.empty()) write_threads_obj(e, lift, args.obj);
  if (!args.png.empty()) render::write_png(render::draw_smocking(pattern, e), args.png);
  if (!args.chart_png.empty()) render::write_png(render::draw_shrinkage_chart(e, o.gamma), args.chart_png);
  if (!args.cloth.empty()) write_cloth(*cloth, args.cloth);
  if (!args.cloth_png.empty()) render::write_png(render::draw_smocked_fabric(*cloth), args.cloth_png);
  if (!args.report.empty()) write_json(report, args.report);
  for (const auto& path : {args.output, args.obj, args.png, args.chart_png, args.report, args.cloth, args.cloth_png})
    if (!path.empty() && path != "-") spdlog::info("wrote {}", path);
  return report;
}

int run_smock(const SmockArgs& args) { return smock(args)["stopped_by"] == "reached" ? 0 : 1; }

}  // namespace skein::cli
