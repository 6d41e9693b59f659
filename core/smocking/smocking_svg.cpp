#include "smocking/smocking_svg.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include <Eigen/Geometry>
#include <expat.h>

#include "common/error.hpp"
#include "common/input_file.hpp"

namespace skein::smocking {
namespace {

/// One drawn element: its points in the drawing's units (transforms applied), and whether it is dashed.
struct Drawn {
  std::vector<Eigen::Vector2d> points;
  bool dashed = false;
  bool line_element = false;  ///< a <line>: chains with the element before it where they meet
  int line = 0;
  std::string name;           ///< "<path id=...>" or "<line> on line N", for messages
};

/// The numbers of an SVG attribute (commas or spaces between; "1.5.5" is 1.5 then .5).
class Numbers {
public:
  explicit Numbers(std::string_view text) : m_text(text) {}
  void skip() {
    while (m_at < m_text.size() && (m_text[m_at] == ' ' || m_text[m_at] == ',' || m_text[m_at] == '\t' || m_text[m_at] == '\n' || m_text[m_at] == '\r')) ++m_at;
  }
  bool done() {
    skip();
    return m_at >= m_text.size();
  }
  char peek() {
    skip();
    return m_at < m_text.size() ? m_text[m_at] : '\0';
  }
  char take() { return m_text[m_at++]; }
  bool number(double& v) {
    skip();
    const char* begin = m_text.data() + m_at;
    if (m_at < m_text.size() && m_text[m_at] == '+') ++begin;
    const auto [end, ec] = std::from_chars(begin, m_text.data() + m_text.size(), v);
    if (ec != std::errc() || !std::isfinite(v)) return false;
    m_at = static_cast<size_t>(end - m_text.data());
    return true;
  }

private:
  std::string_view m_text;
  size_t m_at = 0;
};

struct Parser {
  std::string file;
  XML_Parser xml = nullptr;
  std::vector<Eigen::Affine2d> transforms{Eigen::Affine2d::Identity()};
  std::vector<char> dashed{0};
  int defs = 0, elements = 0;
  std::vector<Drawn> drawn;
  std::string error;  // the first error, thrown after the parser stops

  int line() const { return static_cast<int>(XML_GetCurrentLineNumber(xml)); }
  void fail(const std::string& rule) {
    if (error.empty()) error = rule;
    XML_StopParser(xml, XML_FALSE);
  }
  std::string place() const { return "line " + std::to_string(line()); }

  Eigen::Affine2d transform_of(const std::string& text) {
    Eigen::Affine2d t = Eigen::Affine2d::Identity();
    std::string_view rest(text);
    while (true) {
      const auto open = rest.find('(');
      if (open == std::string_view::npos) break;
      std::string name(rest.substr(0, open));
      name.erase(std::remove_if(name.begin(), name.end(), [](char c) { return c == ' ' || c == ',' || c == '\t' || c == '\n'; }), name.end());
      const auto close = rest.find(')', open);
      if (close == std::string_view::npos) {
        fail("a transform without its closing parenthesis: " + text);
        return t;
      }
      Numbers n(rest.substr(open + 1, close - open - 1));
      std::vector<double> v;
      for (double x; !n.done() && n.number(x);) v.push_back(x);
      Eigen::Affine2d m = Eigen::Affine2d::Identity();
      if (name == "matrix" && v.size() == 6) m.matrix().topRows<2>() << v[0], v[2], v[4], v[1], v[3], v[5];
      else if (name == "translate" && (v.size() == 1 || v.size() == 2)) m.translate(Eigen::Vector2d(v[0], v.size() == 2 ? v[1] : 0));
      else if (name == "scale" && (v.size() == 1 || v.size() == 2)) m.scale(Eigen::Vector2d(v[0], v.size() == 2 ? v[1] : v[0]));
      else {
        fail("the transform \"" + name + "\" with " + std::to_string(v.size()) + " numbers is not read (matrix, translate and scale are; a grid drawn turned is not a grid)");
        return t;
      }
      t = t * m;
      rest = rest.substr(close + 1);
    }
    return t;
  }

  /// The points of <polyline points="..."> or a path's straight segments, in the element's own units.
  void path_points(const std::string& d, Drawn& base) {
    Numbers n(d);
    Eigen::Vector2d at(0, 0), start(0, 0);
    char command = 0;
    Drawn current = base;
    const auto flush = [&] {
      if (current.points.size() >= 2) drawn.push_back(current);
      current.points.clear();
    };
    while (!n.done()) {
      if (std::isalpha(static_cast<unsigned char>(n.peek()))) command = n.take();
      const bool relative = std::islower(static_cast<unsigned char>(command));
      double x = 0, y = 0;
      switch (std::toupper(static_cast<unsigned char>(command))) {
        case 'M':
        case 'L':
          if (!n.number(x) || !n.number(y)) return fail("a path's M or L needs two numbers, in " + base.name);
          at = relative ? at + Eigen::Vector2d(x, y) : Eigen::Vector2d(x, y);
          if (std::toupper(static_cast<unsigned char>(command)) == 'M') {
            flush();
            start = at;
            command = relative ? 'l' : 'L';  // numbers after a moveto are linetos
          }
          current.points.push_back(at);
          break;
        case 'H':
          if (!n.number(x)) return fail("a path's H needs a number, in " + base.name);
          at.x() = relative ? at.x() + x : x;
          current.points.push_back(at);
          break;
        case 'V':
          if (!n.number(y)) return fail("a path's V needs a number, in " + base.name);
          at.y() = relative ? at.y() + y : y;
          current.points.push_back(at);
          break;
        case 'Z':
          return fail(base.name + " closes (Z): a stitching path has two ends");
        default:
          return fail(base.name + " has a curve or arc (" + std::string(1, command ? command : '?') +
                      "): draw stitching lines as straight segments (M, L, H, V)");
      }
    }
    (void)start;
    flush();
  }

  bool dashed_style(const char** attributes, bool inherited) const {
    bool dash = inherited;
    for (int i = 0; attributes[i]; i += 2) {
      const std::string key = attributes[i], value = attributes[i + 1];
      if (key == "stroke-dasharray") dash = value != "none" && !value.empty();
      if (key == "style") {
        const auto at = value.find("stroke-dasharray");
        if (at != std::string::npos) {
          const auto colon = value.find(':', at), end = value.find(';', at);
          const std::string v = colon == std::string::npos ? "" : value.substr(colon + 1, end == std::string::npos ? std::string::npos : end - colon - 1);
          dash = v.find("none") == std::string::npos && v.find_first_not_of(" ") != std::string::npos;
        }
      }
    }
    return dash;
  }

  void start(const std::string& name, const char** attributes) {
    std::string transform, id;
    for (int i = 0; attributes[i]; i += 2) {
      if (std::string(attributes[i]) == "transform") transform = attributes[i + 1];
      if (std::string(attributes[i]) == "id") id = attributes[i + 1];
    }
    transforms.push_back(transforms.back() * (transform.empty() ? Eigen::Affine2d::Identity() : transform_of(transform)));
    dashed.push_back(dashed_style(attributes, dashed.back()));
    if (name == "defs" || name == "clipPath" || name == "mask" || name == "pattern" || name == "symbol" || name == "marker") ++defs;
    if (defs > 0 || (name != "line" && name != "polyline" && name != "path" && name != "polygon")) return;
    if (++elements > 1'000'000) return fail("more than a million drawn elements");
    Drawn d;
    d.dashed = dashed.back();
    d.line = line();
    d.name = "<" + name + (id.empty() ? "" : " id=\"" + id + "\"") + "> on line " + std::to_string(d.line);
    if (name == "polygon") return fail(d.name + " is closed: a stitching path has two ends (draw it as a polyline)");
    const auto attribute = [&](const char* key) -> std::string {
      for (int i = 0; attributes[i]; i += 2)
        if (std::string(attributes[i]) == key) return attributes[i + 1];
      return {};
    };
    const size_t before = drawn.size();
    if (name == "line") {
      d.line_element = true;
      double v[4];
      const char* keys[4] = {"x1", "y1", "x2", "y2"};
      for (int k = 0; k < 4; ++k) {
        const std::string text = attribute(keys[k]);
        Numbers n(text);
        if (text.empty()) v[k] = 0;  // SVG's default
        else if (!n.number(v[k]) || !n.done()) return fail(d.name + ": " + keys[k] + " is not a number: \"" + text + "\"");
      }
      d.points = {{v[0], v[1]}, {v[2], v[3]}};
      drawn.push_back(d);
    } else if (name == "polyline") {
      Numbers n(attribute("points"));
      for (double x, y; !n.done();) {
        if (!n.number(x) || !n.number(y)) return fail(d.name + ": its points are not pairs of numbers");
        d.points.emplace_back(x, y);
      }
      if (d.points.size() >= 2) drawn.push_back(d);
    } else {
      path_points(attribute("d"), d);
    }
    for (size_t k = before; k < drawn.size(); ++k)
      for (auto& p : drawn[k].points) p = transforms.back() * p;
  }
  void end(const std::string& name) {
    transforms.pop_back();
    dashed.pop_back();
    if (name == "defs" || name == "clipPath" || name == "mask" || name == "pattern" || name == "symbol" || name == "marker") --defs;
  }
};

std::string local_name(const char* name) {
  const std::string n(name);
  const auto colon = n.rfind(':');
  return colon == std::string::npos ? n : n.substr(colon + 1);
}

}  // namespace

SmockingPattern read_smocking_svg(const std::filesystem::path& file, const SvgImport& import) {
  check_input_file(file, 16u << 20);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string(), "", "cannot be opened for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_smocking_svg(buffer.str(), file, import);
}

SmockingPattern parse_smocking_svg(const std::string& text, const std::filesystem::path& file, const SvgImport& import) {
  Parser parser;
  parser.file = file.string();
  parser.xml = XML_ParserCreate(nullptr);
  if (!parser.xml) throw Error(file.string(), "", "the XML parser could not be made (out of memory)");
  XML_SetUserData(parser.xml, &parser);
  XML_SetElementHandler(
      parser.xml, [](void* p, const char* name, const char** attributes) { static_cast<Parser*>(p)->start(local_name(name), attributes); },
      [](void* p, const char* name) { static_cast<Parser*>(p)->end(local_name(name)); });
  const bool ok = XML_Parse(parser.xml, text.data(), static_cast<int>(text.size()), XML_TRUE) == XML_STATUS_OK;
  const std::string place = "line " + std::to_string(XML_GetCurrentLineNumber(parser.xml)) + ", column " +
                            std::to_string(XML_GetCurrentColumnNumber(parser.xml) + 1);
  const std::string xml_error = ok ? "" : XML_ErrorString(XML_GetErrorCode(parser.xml));
  XML_ParserFree(parser.xml);
  if (!parser.error.empty()) throw Error(file.string(), place, parser.error);
  if (!ok) throw Error(file.string(), place, "is not well-formed XML: " + xml_error);
  if (parser.drawn.empty()) throw Error(file.string(), "", "draws no stitching line (line, polyline or path elements)");

  // The grid: its spacing (given, or the smallest step between the stitch ends' coordinates) and origin.
  std::vector<double> xs, ys;
  for (const auto& d : parser.drawn)
    for (const auto& p : d.points) xs.push_back(p.x()), ys.push_back(p.y());
  const double x0 = *std::min_element(xs.begin(), xs.end()), y0 = *std::min_element(ys.begin(), ys.end());
  const double extent = std::max(*std::max_element(xs.begin(), xs.end()) - x0, *std::max_element(ys.begin(), ys.end()) - y0);
  double grid = import.grid;
  if (grid <= 0) {
    grid = extent;
    for (auto* values : {&xs, &ys}) {
      std::sort(values->begin(), values->end());
      for (size_t k = 1; k < values->size(); ++k)
        if (const double step = (*values)[k] - (*values)[k - 1]; step > 1e-6 * extent) grid = std::min(grid, step);
    }
    if (!(grid > 0)) throw Error(file.string(), "", "every stitch end is at one point: no grid to find");
  }
  if (extent / grid > 4000) throw Error(file.string(), "", "the stitches span more than 4000 grid squares of " + std::to_string(grid));

  SmockingPattern pattern;
  pattern.name = file.stem().string();
  pattern.note = "read from the drawing " + file.filename().string();
  pattern.style = import.style;
  pattern.spacing = import.spacing;
  const auto snap = [&](const Drawn& d, const Eigen::Vector2d& p) {
    const Eigen::Vector2d g = (p - Eigen::Vector2d(x0, y0)) / grid;
    const Eigen::Vector2d r = g.array().round();
    if ((g - r).cwiseAbs().maxCoeff() > 0.2) {
      std::ostringstream s;
      s << d.name << ": the point (" << p.x() << ", " << p.y() << ") is " << (g - r).cwiseAbs().maxCoeff() << " of a grid square (" << grid
        << ") off the grid: give the grid's spacing (--svg-grid) or draw on the grid";
      throw Error(file.string(), "line " + std::to_string(d.line), s.str());
    }
    return Eigen::Vector2i(static_cast<int>(r.x()) + import.margin, static_cast<int>(r.y()) + import.margin);
  };
  // Threads: each element one, a <line> continuing the thread before it where it starts at its end.
  std::vector<std::vector<bool>> sides;
  for (const auto& d : parser.drawn) {
    std::vector<Eigen::Vector2i> points;
    for (const auto& p : d.points) points.push_back(snap(d, p));
    const bool chain = d.line_element && import.style != Style::Canadian && !pattern.threads.empty() && pattern.threads.back().points.back() == points.front();
    if (!chain) {
      Thread t;
      t.points = {points.front()};
      t.line = d.line;
      t.first_front = !d.dashed;
      pattern.threads.push_back(std::move(t));
      sides.emplace_back();
    }
    auto& t = pattern.threads.back();
    for (size_t k = 1; k < points.size(); ++k) {
      t.points.push_back(points[k]);
      // A <line> is one stitch on the side its stroke says; a polyline's or path's stitches alternate from it.
      sides.back().push_back(d.line_element ? !d.dashed : ((k - 1) % 2 == 0) == !d.dashed);
    }
    // Canadian lines are separate knots whatever they draw; an Italian or English thread alternates sides.
    if (import.style != Style::Canadian)
      for (size_t k = 1; k < sides.back().size(); ++k)
        if (sides.back()[k] == sides.back()[k - 1])
          throw Error(file.string(), "line " + std::to_string(d.line),
                      d.name + ": stitch " + std::to_string(k + 1) + " of the thread that starts on line " + std::to_string(t.line) + " is on the " +
                          (sides.back()[k] ? "front" : "back") + " like the one before it: a thread's stitches alternate front (solid) and back (dashed)");
  }
  int columns = 0, rows = 0;
  for (const auto& t : pattern.threads)
    for (const auto& p : t.points) columns = std::max(columns, p.x() + 1), rows = std::max(rows, p.y() + 1);
  pattern.columns = columns + import.margin;
  pattern.rows = rows + import.margin;
  check_threads(pattern, file.string());
  return pattern;
}

std::string smocking_text(const SmockingPattern& p) {
  const auto shortest = [](double v) {  // the shortest text that reads back to the same double
    char buffer[32];
    return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
  };
  std::ostringstream s;
  if (!p.name.empty()) s << "# name: " << p.name << "\n";
  if (!p.note.empty()) s << "# source: " << p.note << "\n";
  s << "format smocking\nstyle " << style_name(p.style) << "\ngrid " << p.columns << " " << p.rows << "\nspacing " << shortest(p.spacing) << "\ngamma " << shortest(p.gamma) << "\n";
  for (const auto& t : p.threads) {
    s << "path " << (t.first_front ? "front" : "back");
    for (const auto& q : t.points) s << " " << q.x() << "," << q.y();
    s << "\n";
  }
  for (const auto& b : p.beads) s << "bead " << b.a.x() << "," << b.a.y() << " " << b.b.x() << "," << b.b.y() << " " << shortest(b.diameter) << "\n";
  return s.str();
}

}  // namespace skein::smocking
