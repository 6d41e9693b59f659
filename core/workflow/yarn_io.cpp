#include "workflow/yarn_io.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <unordered_map>

#include <Eigen/Geometry>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/gltf_mesh.hpp"
#include "common/input_file.hpp"
#include "common/text.hpp"
#include "relax/segment_distance.hpp"

namespace skein::workflow {
namespace {

#pragma pack(push, 1)
struct BccHeader {
  char sign[3];
  unsigned char byte_count;
  char curve_type[2];
  char dimensions;
  char up_direction;
  std::uint64_t curve_count;
  std::uint64_t total_points;
  char info[40];
};
#pragma pack(pop)
static_assert(sizeof(BccHeader) == 64, "the .bcc header is 64 bytes");

/// Catmull-Rom point between p1 and p2 at t (uniform).
Eigen::Vector3d catmull_rom(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3, double t) {
  const double t2 = t * t, t3 = t2 * t;
  return 0.5 * ((2 * p1) + (-p0 + p2) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t2 + (-p0 + 3 * p1 - 3 * p2 + p3) * t3);
}

}  // namespace

void write_bcc(const relax::YarnCurves& yarn, const std::filesystem::path& path, bool preview) {
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        BccHeader h{};
        std::memcpy(h.sign, "BCC", 3);
        h.byte_count = 0x44;
        std::memcpy(h.curve_type, "C0", 2);
        h.dimensions = 3;
        h.up_direction = 1;  // y up
        h.curve_count = static_cast<std::uint64_t>(yarn.curves());
        h.total_points = yarn.points.size();
        std::snprintf(h.info, sizeof h.info, "skein %s, radius %.9g mm", preview ? "preview" : "yarn", yarn.radius);
        out.write(reinterpret_cast<const char*>(&h), sizeof h);
        for (int c = 0; c < yarn.curves(); ++c) {
          const std::int32_t n = yarn.curve_size(c) * (yarn.closed[c] ? -1 : 1);
          out.write(reinterpret_cast<const char*>(&n), 4);
          for (int i = yarn.curve_start[c]; i < yarn.curve_start[c + 1]; ++i) {
            const float xyz[3] = {static_cast<float>(yarn.points[i].x()), static_cast<float>(yarn.points[i].y()), static_cast<float>(yarn.points[i].z())};
            out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
          }
        }
      },
      true);
}

relax::YarnCurves read_bcc(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;  // a name the file system refuses (too long, ...) is reported, not thrown
  if (!in) throw Error(name, "", std::filesystem::exists(path, ec) ? "cannot be opened for reading" : ec ? "cannot be read: " + ec.message() : "no such file");
  in.seekg(0, std::ios::end);
  const std::uint64_t size = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0);
  BccHeader h{};
  if (size < sizeof h || !in.read(reinterpret_cast<char*>(&h), sizeof h)) throw Error(name, "byte 0", "shorter than the 64-byte .bcc header");
  if (std::memcmp(h.sign, "BCC", 3) != 0) throw Error(name, "byte 0", "does not start with 'BCC'");
  if (h.byte_count != 0x44) throw Error(name, "byte 3", "expected 0x44 (4-byte counts and floats)");
  if (std::memcmp(h.curve_type, "C0", 2) != 0)
    throw Error(name, "byte 4", std::string("curve type '") + std::string(h.curve_type, 2) + "' is not C0 (Catmull-Rom)");
  if (h.dimensions != 3) throw Error(name, "byte 6", "dimensions " + std::to_string(int(h.dimensions)) + ", expected 3");
  // Every curve takes at least 4 bytes and every point 12: bound the counts by the file size before allocating.
  if (h.curve_count > (size - 64) / 4 || h.total_points > (size - 64) / 12)
    throw Error(name, "byte 8", "curve or point count larger than the file can hold");
  relax::YarnCurves y;
  y.points.reserve(h.total_points);
  std::uint64_t offset = 64;
  for (std::uint64_t c = 0; c < h.curve_count; ++c) {
    std::int32_t n = 0;
    if (!in.read(reinterpret_cast<char*>(&n), 4)) throw Error(name, "byte " + std::to_string(offset), "file ends inside curve " + std::to_string(c));
    offset += 4;
    const std::uint64_t count = static_cast<std::uint64_t>(n < 0 ? -static_cast<std::int64_t>(n) : n);
    if (count == 0) throw Error(name, "byte " + std::to_string(offset - 4), "curve " + std::to_string(c) + " has no points");
    if (y.points.size() + count > h.total_points)
      throw Error(name, "byte " + std::to_string(offset - 4), "curve " + std::to_string(c) + " has more points than the header's total");
    for (std::uint64_t i = 0; i < count; ++i) {
      float xyz[3];
      if (!in.read(reinterpret_cast<char*>(xyz), sizeof xyz))
        throw Error(name, "byte " + std::to_string(offset), "file ends inside curve " + std::to_string(c));
      if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
        throw Error(name, "byte " + std::to_string(offset), "a coordinate is not a finite number");
      offset += 12;
      y.points.emplace_back(xyz[0], xyz[1], xyz[2]);
    }
    y.curve_start.push_back(static_cast<int>(y.points.size()));
    y.closed.push_back(n < 0);
  }
  if (y.points.size() != h.total_points)
    throw Error(name, "header", "says " + std::to_string(h.total_points) + " points, the curves hold " + std::to_string(y.points.size()));
  if (offset != size) throw Error(name, "byte " + std::to_string(offset), std::to_string(size - offset) + " bytes follow the last curve");
  // skein writes "radius R mm" into the header's text; other tools' files leave the radius unknown (0).
  const std::string info(h.info, strnlen(h.info, sizeof h.info));
  if (const auto at = info.find("radius "); at != std::string::npos) y.radius = std::atof(info.c_str() + at + 7);
  y.point_face.assign(y.points.size(), -1);
  y.point_type.assign(y.points.size(), -1);
  return y;
}

void write_obj_polylines(const relax::YarnCurves& yarn, const std::filesystem::path& path, bool preview, const std::string& unit) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << (preview ? "# skein preview: " : "# skein yarn: ") << yarn.curves() << " curves, " << yarn.points.size() << " control points, radius " << yarn.radius << " " << unit << "\n";
    char buf[96];
    for (const auto& p : yarn.points) {
      std::snprintf(buf, sizeof buf, "v %.7g %.7g %.7g\n", p.x(), p.y(), p.z());
      out << buf;
    }
    // One two-point `l` record per segment: Blender's OBJ importer (3.4) keeps only the first segment of a
    // longer record, and every other reader takes these too.
    for (int c = 0; c < yarn.curves(); ++c) {
      out << "o yarn" << c << '\n';
      const int first = yarn.curve_start[c], last = yarn.curve_start[c + 1];
      for (int i = first; i + 1 < last; ++i) out << "l " << i + 1 << ' ' << i + 2 << '\n';
      if (yarn.closed[c] && last - first > 2) out << "l " << last << ' ' << first + 1 << '\n';
    }
  });
}

std::vector<std::vector<Eigen::Vector3d>> sample_curves(const relax::YarnCurves& yarn, int samples) {
  std::vector<std::vector<Eigen::Vector3d>> out;
  for (int c = 0; c < yarn.curves(); ++c) {
    const int n = yarn.curve_size(c), s = yarn.curve_start[c];
    const bool closed = yarn.closed[c];
    const auto P = [&](int i) {
      if (closed) return yarn.points[s + ((i % n) + n) % n];
      return yarn.points[s + std::clamp(i, 0, n - 1)];
    };
    std::vector<Eigen::Vector3d> curve;
    const int segments = closed ? n : n - 1;
    for (int i = 0; i < segments; ++i)
      for (int k = 0; k < samples; ++k) curve.push_back(catmull_rom(P(i - 1), P(i), P(i + 1), P(i + 2), static_cast<double>(k) / samples));
    curve.push_back(closed ? curve.front() : P(n - 1));
    out.push_back(std::move(curve));
  }
  return out;
}

std::vector<std::vector<Eigen::Vector3d>> tube_rings(const std::vector<Eigen::Vector3d>& pts, double radius, int sides) {
  std::vector<std::vector<Eigen::Vector3d>> rings;
  if (pts.size() < 2) return rings;
  Eigen::Vector3d normal = (pts[1] - pts[0]).normalized().unitOrthogonal();
  for (size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector3d t = (pts[std::min(i + 1, pts.size() - 1)] - pts[i == 0 ? 0 : i - 1]).normalized();
    normal -= normal.dot(t) * t;  // parallel transport
    normal = normal.norm() > 1e-9 ? normal.normalized() : t.unitOrthogonal();
    const Eigen::Vector3d binormal = t.cross(normal);
    std::vector<Eigen::Vector3d> ring;
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * M_PI * k / sides;
      ring.push_back(pts[i] + radius * (std::cos(a) * normal + std::sin(a) * binormal));
    }
    rings.push_back(std::move(ring));
  }
  return rings;
}

namespace {
/// A yarn's tubes, one block per curve: the rings' points with a normal each (out from the centreline, so
/// that renderers shade the tubes smooth), and quads between consecutive rings (indices within the block).
struct TubeBlock {
  std::vector<Eigen::Vector3d> positions, normals;
  std::vector<std::array<int, 4>> quads;
  std::vector<int> quad_colour;  ///< per quad: the yarn's colour there (YarnCurves::point_colour), or 0 without colours
};
std::vector<TubeBlock> tube_blocks(const relax::YarnCurves& yarn, const TubeOptions& options) {
  std::vector<TubeBlock> blocks;
  const int per_segment = std::max(1, options.samples_per_segment);
  const auto curves = sample_curves(yarn, per_segment);
  const bool coloured = yarn.point_colour.size() == yarn.points.size() && !yarn.colours.empty();
  for (int curve = 0; curve < static_cast<int>(curves.size()); ++curve) {
    const auto& pts = curves[curve];
    if (pts.size() < 2) continue;
    TubeBlock b;
    const auto rings = tube_rings(pts, yarn.radius, options.sides);
    for (size_t i = 0; i < rings.size(); ++i)
      for (const auto& p : rings[i]) b.positions.push_back(p), b.normals.push_back((p - pts[i]).normalized());
    for (int i = 0; i + 1 < static_cast<int>(pts.size()); ++i)
      for (int k = 0; k < options.sides; ++k) {
        const int a = i * options.sides + k, c = i * options.sides + (k + 1) % options.sides;
        b.quads.push_back({a, c, c + options.sides, a + options.sides});
        const int point = yarn.curve_start[curve] + std::min(yarn.curve_size(curve) - 1, i / per_segment);  // where this stretch starts
        b.quad_colour.push_back(coloured ? yarn.point_colour[point] : 0);
      }
    blocks.push_back(std::move(b));
  }
  return blocks;
}
}  // namespace

namespace {
/// A colour as renderers take material colours: linear, from the palette's sRGB.
std::array<double, 3> linear_colour(const std::array<double, 3>& srgb) {
  std::array<double, 3> out;
  for (int k = 0; k < 3; ++k) out[k] = srgb[k] <= 0.04045 ? srgb[k] / 12.92 : std::pow((srgb[k] + 0.055) / 1.055, 2.4);
  return out;
}

/// A material's name from a palette colour's: letters, digits, '-' and '_' only.
std::string material_name(const relax::YarnCurves::Colour& colour) {
  std::string name = "yarn-";
  for (char ch : colour.name) name += std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' ? ch : '_';
  return name;
}
}  // namespace

void write_tube_obj(const relax::YarnCurves& yarn, const std::filesystem::path& path, const TubeOptions& options) {
  const auto blocks = tube_blocks(yarn, options);
  // Yarn in colours: a material library beside the OBJ (the same name, .mtl), one material per colour.
  const bool coloured = yarn.point_colour.size() == yarn.points.size() && !yarn.colours.empty();
  std::filesystem::path library = path;
  library.replace_extension(".mtl");
  if (coloured)
    write_file_atomically(library, [&](std::ostream& out) {
      out << "# skein yarn colours (linear RGB)\n";
      char buf[96];
      for (const auto& colour : yarn.colours) {
        const auto rgb = linear_colour(colour.srgb);
        std::snprintf(buf, sizeof buf, "Kd %.4f %.4f %.4f\n", rgb[0], rgb[1], rgb[2]);
        out << "newmtl " << material_name(colour) << "\n" << buf << "Ka 0 0 0\nKs 0.05 0.05 0.05\nNs 10\nillum 2\n\n";
      }
    });
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# skein yarn tubes: radius " << yarn.radius << " " << options.unit << ", " << options.sides << " sides\n";
    if (coloured) out << "mtllib " << library.filename().string() << "\n";
    char buf[96];
    long base = 1;
    for (size_t c = 0; c < blocks.size(); ++c) {
      out << "o yarn" << c << '\n';
      for (const auto& p : blocks[c].positions) {
        std::snprintf(buf, sizeof buf, "v %.6g %.6g %.6g\n", p.x(), p.y(), p.z());
        out << buf;
      }
      for (const auto& n : blocks[c].normals) {
        std::snprintf(buf, sizeof buf, "vn %.5f %.5f %.5f\n", n.x(), n.y(), n.z());
        out << buf;
      }
      const auto corner = [&](int v) { return std::to_string(base + v) + "//" + std::to_string(base + v); };
      int material = -1;
      for (size_t i = 0; i < blocks[c].quads.size(); ++i) {
        const auto& q = blocks[c].quads[i];
        if (coloured && blocks[c].quad_colour[i] != material) {
          material = blocks[c].quad_colour[i];
          out << "usemtl " << material_name(yarn.colours[static_cast<size_t>(material)]) << '\n';
        }
        out << "f " << corner(q[0]) << ' ' << corner(q[1]) << ' ' << corner(q[2]) << ' ' << corner(q[3]) << '\n';
      }
      base += static_cast<long>(blocks[c].positions.size());
    }
  });
}

void write_tube_gltf(const relax::YarnCurves& yarn, const std::filesystem::path& path, const TubeOptions& options) {
  const auto blocks = tube_blocks(yarn, options);
  // Yarn in colours: one primitive (and material) per colour; else one primitive with the viewer's material.
  const bool coloured = yarn.point_colour.size() == yarn.points.size() && !yarn.colours.empty();
  GltfMesh mesh;
  mesh.mesh_name = "yarn";
  mesh.node_name = "skein yarn, radius " + std::to_string(yarn.radius) + " mm";
  mesh.primitives.resize(coloured ? yarn.colours.size() : 1);
  if (coloured)
    for (size_t k = 0; k < yarn.colours.size(); ++k) {
      mesh.primitives[k].material = material_name(yarn.colours[k]);
      mesh.primitives[k].linear_rgb = linear_colour(yarn.colours[k].srgb);
    }
  for (const auto& b : blocks) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (size_t i = 0; i < b.positions.size(); ++i) {
      mesh.positions.push_back({b.positions[i][0], b.positions[i][1], b.positions[i][2]});
      mesh.normals.push_back({b.normals[i][0], b.normals[i][1], b.normals[i][2]});
    }
    for (size_t i = 0; i < b.quads.size(); ++i)
      for (int v : {b.quads[i][0], b.quads[i][1], b.quads[i][2], b.quads[i][0], b.quads[i][2], b.quads[i][3]})
        mesh.primitives[coloured ? static_cast<size_t>(b.quad_colour[i]) : 0].indices.push_back(base + static_cast<std::uint32_t>(v));
  }
  if (mesh.positions.empty()) throw Error(path.string(), "", "the yarn has no curve of two or more points to make a tube of");
  write_gltf_mesh(mesh, path);
}

void write_point_ids(const relax::YarnCurves& yarn, const mesh::StitchMesh& mesh, const std::filesystem::path& path) {
  const int faces = static_cast<int>(mesh.faces.size());
  for (size_t p = 0; p < yarn.point_face.size(); ++p)
    if (yarn.point_face[p] >= faces)
      throw Error(path.string(), "point " + std::to_string(p), "names face " + std::to_string(yarn.point_face[p]) + " of a stitch mesh of " + std::to_string(faces));
  write_file_atomically(path, [&](std::ostream& out) {
    out << "point,curve,face,row,type\n";
    for (int c = 0; c < yarn.curves(); ++c)
      for (int p = yarn.curve_start[c]; p < yarn.curve_start[c + 1]; ++p) {
        const int f = p < static_cast<int>(yarn.point_face.size()) ? yarn.point_face[p] : -1;
        out << p << ',' << c << ',' << f << ',' << (f >= 0 ? mesh.faces[f].row : -1) << ',' << (f >= 0 ? mesh.faces[f].type : "") << '\n';
      }
  });
}

std::vector<PointId> read_point_ids(const std::filesystem::path& path, const relax::YarnCurves& yarn) {
  check_input_file(path, (yarn.points.size() + 1) * 4200);  // the header and one line of at most 4096 a point
  std::ifstream in(path);
  if (!in) throw Error(path.string(), "", "cannot be read");
  const auto fail = [&](int line, const std::string& rule) { throw Error(path.string(), text_place(line), rule); };
  const int n = static_cast<int>(yarn.points.size());
  std::vector<PointId> ids;
  LineReader reader(in, path.string(), 4096);
  std::string line;
  int line_no = 0;
  const auto next = [&] {
    if (!reader.next()) return false;
    line = reader.line();
    line_no = reader.number();
    return true;
  };
  if (!next() || line != "point,curve,face,row,type") fail(1, "expected the header 'point,curve,face,row,type'");
  while (next()) {
    if (line.empty()) continue;
    std::vector<std::string> fields;
    for (size_t from = 0;;) {
      const size_t comma = line.find(',', from);
      fields.push_back(line.substr(from, comma - from));
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
    if (fields.size() != 5) fail(line_no, "expected 5 fields (point,curve,face,row,type), found " + std::to_string(fields.size()));
    long v[4];
    for (int k = 0; k < 4; ++k) {
      char* end = nullptr;
      errno = 0;
      v[k] = std::strtol(fields[k].c_str(), &end, 10);
      if (fields[k].empty() || *end != '\0' || errno != 0 || v[k] < -1 || v[k] > 1L << 31)
        fail(line_no, "field " + std::to_string(k + 1) + " is not a whole number of -1 or more: '" + fields[k] + "'");
    }
    const int point = static_cast<int>(ids.size());
    if (point >= n) fail(line_no, "names more control points than the yarn's " + std::to_string(n));
    if (v[0] != point) fail(line_no, "names point " + std::to_string(v[0]) + " where point " + std::to_string(point) + " comes");
    if (v[1] != yarn.yarn_of(point))
      fail(line_no, "puts point " + std::to_string(point) + " on curve " + std::to_string(v[1]) + "; the yarn has it on curve " + std::to_string(yarn.yarn_of(point)));
    if ((v[2] < 0) != (v[3] < 0)) fail(line_no, "a face needs its row, and a row its face (-1,-1 for a point of no face)");
    ids.push_back({static_cast<int>(v[1]), static_cast<int>(v[2]), static_cast<int>(v[3]), fields[4]});
  }
  if (static_cast<int>(ids.size()) != n)
    throw Error(path.string(), "", "names " + std::to_string(ids.size()) + " control points; the yarn has " + std::to_string(n));
  return ids;
}

YarnStats yarn_stats(const relax::YarnCurves& yarn) {
  YarnStats s;
  s.curves = yarn.curves();
  s.control_points = static_cast<int>(yarn.points.size());
  s.radius = yarn.radius;
  struct Segment {
    int a, b, curve;
    double from, to;  ///< arc length along the curve's control polygon at its ends
  };
  std::vector<Segment> segments;
  std::vector<double> curve_length(yarn.curves(), 0);
  double longest = 0;
  for (int c = 0; c < yarn.curves(); ++c) {
    s.closed_curves += yarn.closed[c];
    const int first = yarn.curve_start[c], last = yarn.curve_start[c + 1];
    const auto add = [&](int a, int b) {
      const double len = (yarn.points[b] - yarn.points[a]).norm();
      segments.push_back({a, b, c, curve_length[c], curve_length[c] + len});
      curve_length[c] += len;
      longest = std::max(longest, len);
    };
    for (int i = first; i + 1 < last; ++i) add(i, i + 1);
    if (yarn.closed[c] && last - first > 2) add(last - 1, first);
    s.total_length += curve_length[c];
  }
  // Each segment's box, padded by r, goes into every grid cell it touches; two segments closer than 2r have
  // padded boxes that meet, so they share a cell. Pairs are tested cell by cell.
  s.min_segment_distance = std::numeric_limits<double>::infinity();
  if (segments.empty()) return s;
  std::vector<double> lengths;
  for (const auto& seg : segments) lengths.push_back(seg.to - seg.from);
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  const double pad = yarn.radius, cell = std::max({3 * lengths[lengths.size() / 2], 4 * yarn.radius, 1e-6});
  std::vector<std::pair<std::uint64_t, int>> entries;
  entries.reserve(segments.size() * 4);
  const auto cell_key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x & 0x1fffff) << 42) | (static_cast<std::uint64_t>(y & 0x1fffff) << 21) | static_cast<std::uint64_t>(z & 0x1fffff);
  };
  for (size_t i = 0; i < segments.size(); ++i) {
    const Eigen::Vector3d &a = yarn.points[segments[i].a], &b = yarn.points[segments[i].b];
    const Eigen::Array3d lo = (a.array().min(b.array()) - pad) / cell, hi = (a.array().max(b.array()) + pad) / cell;
    for (auto x = static_cast<std::int64_t>(std::floor(lo.x())); x <= static_cast<std::int64_t>(std::floor(hi.x())); ++x)
      for (auto y = static_cast<std::int64_t>(std::floor(lo.y())); y <= static_cast<std::int64_t>(std::floor(hi.y())); ++y)
        for (auto z = static_cast<std::int64_t>(std::floor(lo.z())); z <= static_cast<std::int64_t>(std::floor(hi.z())); ++z)
          entries.emplace_back(cell_key(x, y, z), static_cast<int>(i));
  }
  std::sort(entries.begin(), entries.end());
  // Adjacent: sharing a point, or less than 2r apart along one yarn (a tight bend is not a contact).
  const double near = 2 * yarn.radius;
  const auto adjacent = [&](const Segment& x, const Segment& y) {
    if (x.a == y.a || x.a == y.b || x.b == y.a || x.b == y.b) return true;
    if (x.curve != y.curve) return false;
    const double gap = std::max(y.from - x.to, x.from - y.to);
    const double around = yarn.closed[x.curve] ? curve_length[x.curve] - (std::max(x.to, y.to) - std::min(x.from, y.from)) : gap;
    return std::min(gap, around) < near;
  };
  for (size_t begin = 0; begin < entries.size();) {
    size_t end = begin;
    while (end < entries.size() && entries[end].first == entries[begin].first) ++end;
    for (size_t i = begin; i < end; ++i)
      for (size_t j = i + 1; j < end; ++j) {
        const Segment &x = segments[entries[i].second], &y = segments[entries[j].second];
        if (adjacent(x, y)) continue;
        const double d = relax::segment_distance(yarn.points[x.a], yarn.points[x.b], yarn.points[y.a], yarn.points[y.b]);
        if (d < s.min_segment_distance) s.min_segment_distance = d, s.closest = {x.a, y.a};
      }
    begin = end;
  }
  return s;
}

}  // namespace skein::workflow
