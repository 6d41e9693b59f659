#include "stitchmesh/stitch_model.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "common/error.hpp"
#include "common/input_file.hpp"
#include "common/text.hpp"
#include "skein/config.hpp"
#include "stitchmesh/stitch_types.hpp"

namespace skein::mesh {
namespace {

constexpr double kMaxOffset = 8.0;  // |h| in yarn radii

std::optional<Crossing> parse_crossing(std::string_view t) {
  if (t == "L") return Crossing{Crossing::Side::Left, 0, 0};
  if (t == "R") return Crossing{Crossing::Side::Right, 0, 0};
  if (t.size() < 3 || (t[0] != 'B' && t[0] != 'T') || (t.back() != 'a' && t.back() != 'b')) return std::nullopt;
  int edge = 0;
  const auto r = std::from_chars(t.data() + 1, t.data() + t.size() - 1, edge);
  if (r.ec != std::errc() || r.ptr != t.data() + t.size() - 1 || edge < 0) return std::nullopt;
  return Crossing{t[0] == 'B' ? Crossing::Side::Bottom : Crossing::Side::Top, edge, t.back() == 'a' ? 0 : 1};
}

std::string number(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

}  // namespace

std::string Crossing::name() const {
  switch (side) {
    case Side::Left: return "L";
    case Side::Right: return "R";
    case Side::Bottom: return "B" + std::to_string(edge) + (slot == 0 ? "a" : "b");
    case Side::Top: return "T" + std::to_string(edge) + (slot == 0 ? "a" : "b");
  }
  return "?";
}

Eigen::Vector2d StitchModel::crossing_uv(const Crossing& c) const {
  switch (c.side) {
    case Crossing::Side::Left: return {0, kWaleCrossing};
    case Crossing::Side::Right: return {1, kWaleCrossing};
    case Crossing::Side::Bottom: return {(c.edge + kCourseSlots[c.slot]) / bottom, 0};
    case Crossing::Side::Top: return {(c.edge + kCourseSlots[c.slot]) / top, 1};
  }
  return {0, 0};
}

StitchModel parse_stitch_model(const std::string& text, const std::string& file) {
  StitchModel m;
  bool have_name = false, have_shape = false, notes_done = false;
  std::istringstream in(text);
  LineReader reader(in, file);
  const auto fail = [&](const std::string& rule) { reader.fail(rule); };
  std::map<std::string, int> used;  // crossing name → uses
  while (reader.next()) {
    const std::string& raw = reader.line();
    if (!raw.empty() && raw[0] == '#') {
      if (!notes_done) m.note += (m.note.empty() ? "" : "\n") + raw.substr(raw.size() > 1 && raw[1] == ' ' ? 2 : 1);
      continue;
    }
    notes_done = true;
    std::istringstream words(raw.substr(0, raw.find('#')));
    std::vector<std::string> tok;
    for (std::string w; words >> w;) tok.push_back(w);
    if (tok.empty()) continue;
    if (tok[0] == "stitch") {
      if (have_name) fail("a second 'stitch' line: a file holds one stitch model");
      if (tok.size() != 2) fail("expected 'stitch NAME'");
      m.name = tok[1];
      have_name = true;
    } else if (tok[0] == "shape") {
      if (have_shape) fail("a second 'shape' line: the pieces read so far were checked against the first");
      if (tok.size() < 3 || tok.size() > 4 || (tok.size() == 4 && tok[3] != "no-wale"))
        fail("expected 'shape BOTTOM TOP' or 'shape BOTTOM TOP no-wale'");
      char* end = nullptr;
      m.bottom = static_cast<int>(std::strtol(tok[1].c_str(), &end, 10));
      if (*end) fail("'" + tok[1] + "' is not an edge count");
      m.top = static_cast<int>(std::strtol(tok[2].c_str(), &end, 10));
      if (*end) fail("'" + tok[2] + "' is not an edge count");
      if (m.bottom < 0 || m.top < 0 || m.bottom > 8 || m.top > 8 || m.bottom + m.top == 0) fail("edge counts must be 0 to 8, not both 0");
      m.wale_edges = tok.size() == 3;
      have_shape = true;
    } else if (tok[0] == "piece") {
      if (!have_shape) fail("'shape' must come before the first piece");
      if (tok.size() != 1) fail("'piece' takes no values");
      m.pieces.emplace_back();
    } else {
      if (m.pieces.empty()) fail("'" + tok[0] + "' is not a keyword (stitch, shape, piece) and no piece is open");
      auto& piece = m.pieces.back();
      ModelPoint p;
      if (tok.size() == 1) {
        p.crossing = parse_crossing(tok[0]);
        if (!p.crossing) fail("'" + tok[0] + "' is not a crossing (L, R, B<i>a, B<i>b, T<i>a, T<i>b)");
        const Crossing& c = *p.crossing;
        if ((c.side == Crossing::Side::Left || c.side == Crossing::Side::Right) && !m.wale_edges)
          fail("crossing " + tok[0] + ": this model has no wale edges");
        if (c.side == Crossing::Side::Bottom && c.edge >= m.bottom)
          fail("crossing " + tok[0] + ": the model has " + std::to_string(m.bottom) + " bottom edges");
        if (c.side == Crossing::Side::Top && c.edge >= m.top) fail("crossing " + tok[0] + ": the model has " + std::to_string(m.top) + " top edges");
        if (piece.points.size() >= 1 && piece.points.back().crossing && piece.points.size() > 1)
          fail("crossing " + tok[0] + " follows the piece's closing crossing; start a new piece");
        if (++used[c.name()] > 1) fail("crossing " + tok[0] + " is used twice; each crossing belongs to one piece end");
      } else if (tok.size() == 3) {
        double x[3];
        for (int i = 0; i < 3; ++i) {
          const auto r = std::from_chars(tok[i].data(), tok[i].data() + tok[i].size(), x[i]);
          if (r.ec != std::errc() || r.ptr != tok[i].data() + tok[i].size() || !std::isfinite(x[i])) fail("'" + tok[i] + "' is not a number");
        }
        if (x[0] < 0 || x[0] > 1 || x[1] < 0 || x[1] > 1) fail("point (" + tok[0] + ", " + tok[1] + ") lies outside the canonical polygon [0,1]²");
        if (std::abs(x[2]) > kMaxOffset) fail("offset " + tok[2] + " is more than " + number(kMaxOffset) + " yarn radii");
        if (piece.points.size() > 1 && piece.points.back().crossing) fail("a point follows the piece's closing crossing; start a new piece");
        p.uvh = {x[0], x[1], x[2]};
      } else {
        fail("expected a crossing name or 'u v h'");
      }
      piece.points.push_back(p);
    }
  }
  const auto fail_model = [&](const std::string& rule) { throw Error(file, "", rule); };
  if (!have_name) fail_model("no 'stitch NAME' line");
  if (!have_shape) fail_model("no 'shape BOTTOM TOP' line");
  if (m.pieces.empty()) fail_model("no yarn piece");
  for (size_t i = 0; i < m.pieces.size(); ++i) {
    const auto& pts = m.pieces[i].points;
    if (pts.size() < 2) fail_model("piece " + std::to_string(i + 1) + " has fewer than 2 points");
    for (size_t k = 1; k + 1 < pts.size(); ++k)
      if (pts[k].crossing) fail_model("piece " + std::to_string(i + 1) + " has a crossing in its middle");
  }
  // Yuksel §4.2: one crossing on each wale edge, two on each course edge.
  const auto need = [&](const std::string& name, const std::string& what) {
    if (!used.count(name)) fail_model("no piece crosses " + what + " (" + name + ")");
  };
  if (m.wale_edges) {
    need("L", "the left wale edge");
    need("R", "the right wale edge");
  }
  for (int i = 0; i < m.bottom; ++i)
    for (const char* s : {"a", "b"}) need("B" + std::to_string(i) + s, "bottom edge " + std::to_string(i) + " twice");
  for (int i = 0; i < m.top; ++i)
    for (const char* s : {"a", "b"}) need("T" + std::to_string(i) + s, "top edge " + std::to_string(i) + " twice");
  if (const StitchType* t = find_stitch_type(m.name); t && (t->bottom != m.bottom || t->top != m.top || !m.wale_edges))
    fail_model("stitch type '" + m.name + "' needs shape " + std::to_string(t->bottom) + " " + std::to_string(t->top) + " with wale edges");
  for (auto& piece : m.pieces)
    for (auto& p : piece.points)
      if (p.crossing) p.uvh = Eigen::Vector3d(m.crossing_uv(*p.crossing).x(), m.crossing_uv(*p.crossing).y(), 0);  // on the surface
  return m;
}

std::string format_stitch_model(const StitchModel& m) {
  std::string out;
  std::istringstream notes(m.note);
  for (std::string line; std::getline(notes, line);) out += "# " + line + "\n";
  out += "stitch " + m.name + "\n";
  out += "shape " + std::to_string(m.bottom) + " " + std::to_string(m.top) + (m.wale_edges ? "" : " no-wale") + "\n";
  for (const auto& piece : m.pieces) {
    out += "piece\n";
    for (const auto& p : piece.points)
      out += "  " + (p.crossing ? p.crossing->name() : number(p.uvh.x()) + " " + number(p.uvh.y()) + " " + number(p.uvh.z())) + "\n";
  }
  return out;
}

StitchLibrary StitchLibrary::load(const std::filesystem::path& folder) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) throw Error(folder.string(), "", "the stitch library folder does not exist");
  const auto files = files_with_extension(folder, ".stitch");
  StitchLibrary lib;
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    if (!in) throw Error(f.string(), "", "cannot be opened for reading");
    std::stringstream buffer;
    buffer << in.rdbuf();
    StitchModel m = parse_stitch_model(buffer.str(), f.string());
    if (m.name != f.stem().string()) throw Error(f.string(), "", "names stitch '" + m.name + "'; the file must be called " + m.name + ".stitch");
    lib.m_models.emplace(m.name, std::move(m));
  }
  if (lib.m_models.empty()) throw Error(folder.string(), "", "holds no .stitch files");
  return lib;
}

std::filesystem::path StitchLibrary::bundled_folder() {
  if (const char* env = std::getenv("SKEIN_STITCHES"); env && *env) return env;
  return std::filesystem::path(SKEIN_SOURCE_DIR) / "stitches";
}

const StitchLibrary& StitchLibrary::bundled() {
  static const StitchLibrary lib = load(bundled_folder());
  return lib;
}

const StitchModel* StitchLibrary::find(const std::string& name) const {
  const auto it = m_models.find(name);
  return it == m_models.end() ? nullptr : &it->second;
}

const StitchModel& StitchLibrary::at(const std::string& name) const {
  if (const auto* m = find(name)) return *m;
  throw Error("", "stitch '" + name + "'", "the stitch library has no model for it");
}

}  // namespace skein::mesh
