#include "stitchmesh/project.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "stitchmesh/stitch_types.hpp"

namespace skein::mesh {
namespace {

void put(std::string& out, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);  // shortest form that reads back exactly
  out.append(buf, r.ptr);
}
void put(std::string& out, int x) { out += std::to_string(x); }

char label_char(EdgeLabel l) { return l == EdgeLabel::Wale ? 'W' : l == EdgeLabel::Course ? 'C' : '-'; }

/// Reads one line's whitespace-separated tokens and reports errors at that line.
class LineReader {
public:
  LineReader(const std::string& name, int line, std::string_view text) : m_name(name), m_line(line) {
    size_t i = 0;
    while (i < text.size()) {
      while (i < text.size() && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r')) ++i;
      const size_t j = i;
      while (i < text.size() && text[i] != ' ' && text[i] != '\t' && text[i] != '\r') ++i;
      if (i > j) m_tokens.push_back(text.substr(j, i - j));
    }
  }
  [[noreturn]] void fail(const std::string& rule) const { throw Error(m_name, "line " + std::to_string(m_line), rule); }
  size_t size() const { return m_tokens.size(); }
  std::string_view word(size_t i) const { return m_tokens[i]; }
  void expect_count(size_t min, size_t max, const char* what) const {
    if (m_tokens.size() < min || m_tokens.size() > max)
      fail(std::string("expected ") + what + ", found " + std::to_string(m_tokens.size() - 1) + (m_tokens.size() == 2 ? " value" : " values") +
           " after '" + std::string(m_tokens[0]) + "'");
  }
  double real(size_t i) const {
    double x = 0;
    const auto t = m_tokens[i];
    const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size()) fail("'" + std::string(t) + "' is not a number");
    return x;
  }
  int integer(size_t i, long min, long max) const {
    long x = 0;
    const auto t = m_tokens[i];
    const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size()) fail("'" + std::string(t) + "' is not an integer");
    if (x < min || x > max) fail(std::string(t) + " is out of range (expected " + std::to_string(min) + " to " + std::to_string(max) + ")");
    return static_cast<int>(x);
  }
  int line() const { return m_line; }

private:
  const std::string& m_name;
  int m_line;
  std::vector<std::string_view> m_tokens;
};

constexpr long kMaxCount = 1L << 30;

}  // namespace

std::string project_text(const Project& p) {
  std::string out;
  out += "skein " + std::to_string(kProjectVersion) + "\n";
  out += "stitch-size ";
  put(out, p.stitch_size.width);
  out += ' ';
  put(out, p.stitch_size.height);
  out += '\n';
  for (const auto& setting : p.settings) out += "set " + setting.key + ' ' + setting.value + '\n';
  if (p.input) {
    out += "input-mesh\n";
    for (const auto& v : p.input->points()) {
      out += "v ";
      put(out, v.x()), out += ' ', put(out, v.y()), out += ' ', put(out, v.z());
      out += '\n';
    }
    for (const auto& f : p.input->faces()) {
      out += 'f';
      for (int v : f) out += ' ', put(out, v);
      out += '\n';
    }
  }
  if (p.input && p.labels) {
    out += "labels\n";
    for (int f = 0; f < p.input->num_faces(); ++f) {
      const FaceLabel& fl = p.labels->faces[f];
      if (!fl.labeled()) continue;
      out += "face ", put(out, f), out += ' ', put(out, fl.row), out += ' ', put(out, fl.left), out += ' ', put(out, fl.right), out += '\n';
    }
    for (int e = 0; e < p.input->num_edges(); ++e) {
      const EdgeLabel l = p.labels->edges[e];
      const int n = p.values ? p.values->edge[e] : 0;
      const int marked = p.values ? p.values->marked[e] : 0;
      if (l == EdgeLabel::None && n == 0) continue;
      out += "edge ", put(out, e), out += ' ', out += label_char(l), out += ' ', put(out, n), out += ' ', put(out, marked), out += '\n';
    }
  }
  if (p.stitch) {
    out += "stitch-mesh\n";
    for (const auto& v : p.stitch->vertices) {
      out += "v ";
      put(out, v.x()), out += ' ', put(out, v.y()), out += ' ', put(out, v.z());
      out += '\n';
    }
    for (const auto& f : p.stitch->faces) {
      out += "f ", put(out, f.row), out += ' ', put(out, f.bottom), out += ' ', out += f.type, out += ' ', put(out, f.input_face);
      for (int v : f.vertices) out += ' ', put(out, v);
      out += '\n';
    }
    for (const auto& [edge, mark] : p.stitch->cables) {
      out += "cable ", put(out, edge.first), out += ' ', put(out, edge.second), out += ' ', put(out, mark.shift), out += ' ', put(out, mark.order);
      out += '\n';
    }
    // Colours: the palette, then runs of faces of one colour other than the first.
    for (const auto& c : p.stitch->palette) {
      out += "colour " + c.name + ' ' + colour_code(c.srgb).substr(1);
      std::istringstream words(c.description);  // one line, single spaces, no comment mark
      for (std::string w; words >> w;) {
        std::replace(w.begin(), w.end(), '#', '_');
        out += ' ' + w;
      }
      out += '\n';
    }
    const auto& faces = p.stitch->faces;
    for (size_t f = 0; !p.stitch->palette.empty() && f < faces.size();) {
      size_t g = f + 1;
      while (g < faces.size() && faces[g].colour == faces[f].colour) ++g;
      if (faces[f].colour != 0) {
        out += "face-colour ", put(out, static_cast<int>(f)), out += ' ', put(out, static_cast<int>(g - 1)), out += ' ', put(out, faces[f].colour);
        out += '\n';
      }
      f = g;
    }
  }
  out += "end\n";
  return out;
}

Project parse_project(const std::string& text, const std::string& name) {
  Project p;
  enum class Section { None, Input, Labels, Stitch, End } section = Section::None;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> faces;
  int input_line = 0;
  struct FaceLine { int line, face, row, left, right; };
  struct EdgeLine { int line, edge; EdgeLabel label; int n, marked; };
  std::vector<FaceLine> face_lines;
  std::vector<EdgeLine> edge_lines;
  bool have_labels = false, have_stitch = false, have_header = false;
  StitchMesh stitch;
  std::vector<int> stitch_face_lines;
  struct CableLine { int line, u, v, shift, order; };
  std::vector<CableLine> cable_lines;
  struct ColourLine { int line, first, last, colour; };
  std::vector<ColourLine> colour_lines;

  int line_no = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    const std::string_view raw(text.data() + pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    const size_t hash = raw.find('#');
    const LineReader line(name, line_no, hash == std::string_view::npos ? raw : raw.substr(0, hash));
    if (line.size() == 0) continue;
    const std::string_view key = line.word(0);
    if (section == Section::End) line.fail("nothing may follow 'end'");
    if (!have_header) {
      if (key != "skein" || line.size() != 2) line.fail("a skein project starts with 'skein <version>'");
      const int version = line.integer(1, 0, 1000000);
      if (version != kProjectVersion)
        line.fail("version " + std::to_string(version) + " is not supported (this skein reads version " + std::to_string(kProjectVersion) + ")");
      have_header = true;
    } else if (key == "stitch-size") {
      line.expect_count(3, 3, "width and height in mm");
      p.stitch_size = {line.real(1), line.real(2)};
      if (!(p.stitch_size.width > 0 && p.stitch_size.height > 0) || !std::isfinite(p.stitch_size.width + p.stitch_size.height))
        line.fail("stitch width and height must be positive numbers");
    } else if (key == "set") {
      line.expect_count(3, 3, "a key and a value");
      const std::string name(line.word(1));
      if (!std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-'; }))
        line.fail("setting key '" + name + "' may hold only letters, digits, '.', '_' and '-'");
      for (const auto& earlier : p.settings)
        if (earlier.key == name) line.fail("'" + name + "' is set twice (first at line " + std::to_string(earlier.line) + ")");
      p.settings.push_back({name, std::string(line.word(2)), line_no});
    } else if (key == "input-mesh") {
      if (section != Section::None) line.fail("'input-mesh' must come before 'labels' and 'stitch-mesh', once");
      section = Section::Input;
      input_line = line_no;
    } else if (key == "labels") {
      if (section != Section::Input) line.fail("'labels' must follow 'input-mesh'");
      section = Section::Labels;
      have_labels = true;
    } else if (key == "stitch-mesh") {
      if (section == Section::Stitch) line.fail("a project holds one 'stitch-mesh'");
      section = Section::Stitch;
      have_stitch = true;
    } else if (key == "end") {
      line.expect_count(1, 1, "nothing");
      section = Section::End;
    } else if (key == "v" && (section == Section::Input || section == Section::Stitch)) {
      line.expect_count(4, 4, "3 coordinates");
      const Eigen::Vector3d x(line.real(1), line.real(2), line.real(3));
      (section == Section::Input ? points : stitch.vertices).push_back(x);
    } else if (key == "f" && section == Section::Input) {
      line.expect_count(4, 1 << 16, "at least 3 vertex ids");
      std::vector<int> f;
      for (size_t i = 1; i < line.size(); ++i) f.push_back(line.integer(i, 0, static_cast<long>(points.size()) - 1));
      faces.push_back(std::move(f));
    } else if (key == "f" && section == Section::Stitch) {
      line.expect_count(8, 1 << 16, "row, bottom count, stitch type, input face and at least 4 vertex ids");
      StitchFace f;
      f.row = line.integer(1, 0, kMaxCount);
      f.bottom = line.integer(2, 1, kMaxCount);
      f.type = std::string(line.word(3));
      if (!find_stitch_type(f.type)) line.fail("'" + f.type + "' is not a known stitch type");
      f.input_face = line.integer(4, -1, kMaxCount);
      for (size_t i = 5; i < line.size(); ++i) f.vertices.push_back(line.integer(i, 0, static_cast<long>(stitch.vertices.size()) - 1));
      if (f.bottom > f.size() - 3) line.fail("bottom count " + std::to_string(f.bottom) + " leaves no top edge and two wale edges in a face of " + std::to_string(f.size()) + " vertices");
      stitch.faces.push_back(std::move(f));
      stitch_face_lines.push_back(line_no);
    } else if (key == "cable" && section == Section::Stitch) {
      line.expect_count(5, 5, "two vertex ids, shift and order");
      cable_lines.push_back({line_no, line.integer(1, 0, kMaxCount), line.integer(2, 0, kMaxCount), line.integer(3, -kMaxCount, kMaxCount),
                             line.integer(4, -1, 1)});
    } else if (key == "colour" && section == Section::Stitch) {
      line.expect_count(3, 1 << 10, "a name, an sRGB colour as six hex digits and a description");
      PatternColour c;
      c.name = std::string(line.word(1));
      const std::string hex(line.word(2));
      if (hex.size() != 6 || !std::all_of(hex.begin(), hex.end(), [](char ch) { return std::isxdigit(static_cast<unsigned char>(ch)); }))
        line.fail("a colour is six hex digits (f0e6cf), found '" + hex + "'");
      const unsigned value = static_cast<unsigned>(std::stoul(hex, nullptr, 16));
      c.srgb = {((value >> 16) & 0xff) / 255.0, ((value >> 8) & 0xff) / 255.0, (value & 0xff) / 255.0};
      for (size_t i = 3; i < line.size(); ++i) c.description += (i > 3 ? " " : "") + std::string(line.word(i));
      if (find_colour(stitch.palette, c.name) >= 0) line.fail("colour '" + c.name + "' is given twice");
      stitch.palette.push_back(std::move(c));
    } else if (key == "face-colour" && section == Section::Stitch) {
      line.expect_count(4, 4, "first and last face id and a colour index");
      colour_lines.push_back({line_no, line.integer(1, 0, kMaxCount), line.integer(2, 0, kMaxCount), line.integer(3, 0, kMaxCount)});
    } else if (key == "face" && section == Section::Labels) {
      line.expect_count(5, 5, "face id, row, left and right wale edge");
      face_lines.push_back({line_no, line.integer(1, 0, kMaxCount), line.integer(2, 0, kMaxCount), line.integer(3, 0, kMaxCount),
                            line.integer(4, 0, kMaxCount)});
    } else if (key == "edge" && section == Section::Labels) {
      line.expect_count(5, 5, "edge id, label (W, C or -), tessellation value and marked flag");
      const std::string_view l = line.word(2);
      if (l != "W" && l != "C" && l != "-") line.fail("edge label must be W (wale), C (course) or - (none), found '" + std::string(l) + "'");
      edge_lines.push_back({line_no, line.integer(1, 0, kMaxCount), l == "W" ? EdgeLabel::Wale : l == "C" ? EdgeLabel::Course : EdgeLabel::None,
                            line.integer(3, 0, kMaxCount), line.integer(4, 0, 1)});
    } else {
      line.fail("'" + std::string(key) + "' is not expected here");
    }
  }
  if (!have_header) throw Error(name, "", "empty file: a skein project starts with 'skein <version>'");
  if (section != Section::End) throw Error(name, "line " + std::to_string(line_no), "the file ends without 'end' (truncated?)");

  if (input_line > 0) {
    try {
      p.input.emplace(std::move(points), std::move(faces), name);
    } catch (const Error& e) {
      throw Error(name, "input-mesh at line " + std::to_string(input_line) + ", " + e.place(), e.rule());
    }
  }
  if (have_labels) {
    const InputMesh& mesh = *p.input;
    Labeling labels(mesh);
    TessellationValues values{std::vector<int>(mesh.num_edges(), 0), std::vector<char>(mesh.num_edges(), 0)};
    bool any_value = false;
    for (const auto& fl : face_lines) {
      const auto fail = [&](const std::string& rule) { throw Error(name, "line " + std::to_string(fl.line), rule); };
      if (fl.face >= mesh.num_faces()) fail("face " + std::to_string(fl.face) + " does not exist");
      const int n = static_cast<int>(mesh.face(fl.face).size());
      if (fl.left >= n || fl.right >= n) fail("face " + std::to_string(fl.face) + " has " + std::to_string(n) + " edges");
      labels.faces[fl.face] = {fl.row, fl.left, fl.right};
      labels.rows = std::max(labels.rows, fl.row + 1);
    }
    for (const auto& el : edge_lines) {
      if (el.edge >= mesh.num_edges()) throw Error(name, "line " + std::to_string(el.line), "edge " + std::to_string(el.edge) + " does not exist");
      labels.edges[el.edge] = el.label;
      values.edge[el.edge] = el.n;
      values.marked[el.edge] = static_cast<char>(el.marked);
      any_value |= el.n > 0;
    }
    if (any_value) {
      for (const auto& el : edge_lines)
        if (el.n == 0) throw Error(name, "line " + std::to_string(el.line), "tessellation value 0: every edge needs a value of at least 1");
      if (static_cast<int>(edge_lines.size()) != mesh.num_edges())
        throw Error(name, "labels", "tessellation values are given for " + std::to_string(edge_lines.size()) + " of " + std::to_string(mesh.num_edges()) + " edges");
      p.values = std::move(values);
    }
    p.labels = std::move(labels);
  }
  if (have_stitch) {
    for (const auto& c : cable_lines) {
      if (c.u >= static_cast<int>(stitch.vertices.size()) || c.v >= static_cast<int>(stitch.vertices.size()))
        throw Error(name, "line " + std::to_string(c.line), "cable edge refers to a vertex that does not exist");
      stitch.cables[std::minmax(c.u, c.v)] = {c.shift, c.order};
    }
    for (const auto& c : colour_lines) {
      const auto fail = [&](const std::string& rule) { throw Error(name, "line " + std::to_string(c.line), rule); };
      if (c.colour >= static_cast<int>(stitch.palette.size()))
        fail("colour " + std::to_string(c.colour) + " is not one of the " + std::to_string(stitch.palette.size()) + " colours given");
      if (c.last < c.first) fail("face-colour's last face " + std::to_string(c.last) + " comes before its first " + std::to_string(c.first));
      if (c.last >= static_cast<int>(stitch.faces.size()))
        fail("faces " + std::to_string(c.first) + " to " + std::to_string(c.last) + " are not faces of the stitch mesh (it has " +
             std::to_string(stitch.faces.size()) + ")");
      for (int f = c.first; f <= c.last; ++f) stitch.faces[static_cast<size_t>(f)].colour = c.colour;
    }
    for (const auto& f : stitch.faces)
      if (f.input_face >= 0 && (!p.input || f.input_face >= p.input->num_faces()))
        throw Error(name, "stitch-mesh", "a face refers to input face " + std::to_string(f.input_face) + ", which does not exist");
    p.stitch = std::move(stitch);
  }
  return p;
}

void write_project(const Project& project, const std::filesystem::path& path) {
  const std::string text = project_text(project);
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

Project read_project(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;  // a name the file system refuses (too long, ...) is reported, not thrown
  if (!in) throw Error(path.string(), "", std::filesystem::exists(path, ec) ? "cannot be opened for reading" : ec ? "cannot be read: " + ec.message() : "no such file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  if (text.find('\0') != std::string::npos) throw Error(path.string(), "", "is a binary file, not a skein project");
  return parse_project(text, path.string());
}

}  // namespace skein::mesh
