#include "stitchmesh/pattern.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "common/error.hpp"
#include "common/input_file.hpp"
#include "common/text.hpp"
#include "stitchmesh/chart_pattern.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/stitch_types.hpp"
#include "stitchmesh/wif_pattern.hpp"
#include "stitchmesh/written_pattern.hpp"

namespace skein::mesh {
namespace {

/// Leaf 2018 Table 2's tiles: knit, purl, the slipped front and back stitches, and the lace tiles (a yarn-over
/// beside a decrease, as many loops made as taken), each one stitch-mesh face.
struct Tile {
  const char* code;
  const char* type;
};
constexpr Tile kTiles[] = {{"K", "k"}, {"P", "p"}, {"F", "sk"}, {"B", "s"}, {"YS", "ys"}, {"2U", "2u"}, {"Y3Y", "y3y"}};

struct Row {
  std::vector<Token> tokens;
  int line;
};

std::string known_types() {
  std::string names;
  for (const auto& t : stitch_types()) names += (names.empty() ? "" : " ") + t.name;
  return names;
}


}  // namespace

int loops_taken(const std::vector<std::string>& row) {
  int n = 0;
  for (const auto& t : row) n += find_stitch_type(t)->bottom;
  return n;
}
int loops_made(const std::vector<std::string>& row) {
  int n = 0;
  for (const auto& t : row) n += find_stitch_type(t)->top;
  return n;
}

int Pattern::width() const {
  if (format == PatternFormat::Woven) return over.empty() ? 0 : static_cast<int>(over[0].size());
  return rows.empty() ? 0 : loops_taken(rows[0]);
}
int Pattern::height() const { return static_cast<int>(format == PatternFormat::Woven ? over.size() : rows.size()); }
int Pattern::stitches() const {
  int n = 0;
  for (const auto& row : rows) n += static_cast<int>(row.size());
  return n;
}

Pattern stacked(const Pattern& pattern, int times) {
  if (pattern.format == PatternFormat::Woven || pattern.whole || times < 1)
    throw Error("", "pattern " + pattern.name, "only a knit's repeat stacks (not a woven or a shaped piece), at least once");
  Pattern out = pattern;
  const int h = pattern.height();
  for (int k = 1; k < times; ++k) {
    out.rows.insert(out.rows.end(), pattern.rows.begin(), pattern.rows.end());
    out.colours.insert(out.colours.end(), pattern.colours.begin(), pattern.colours.end());
    for (PatternCable cable : pattern.cables) {
      cable.row += k * h;
      out.cables.push_back(cable);
    }
  }
  return out;
}

Pattern parse_pattern(const std::string& text, const std::string& source) {
  if (is_wif_pattern(text)) return parse_wif_pattern(text, source);
  if (is_chart_pattern(text)) return parse_chart_pattern(text, source);
  if (is_written_pattern(text)) return parse_written_pattern(text, source);
  Pattern p;
  p.name = std::filesystem::path(source).stem().string();
  std::istringstream in(text);
  LineReader reader(in, source);
  int line_no = 0;
  bool have_format = false;
  std::vector<Row> lines;         // top line first, as written
  std::vector<Row> colour_lines;  // after `colours`: the colour of each stitch, laid out as the rows
  bool in_colours = false;
  const auto at = text_place;
  while (reader.next()) {
    line_no = reader.number();
    std::string line = reader.line();
    if (const auto hash = comment_start(line); hash != std::string::npos) {
      const std::string comment = trim(line.substr(hash + 1));
      for (const auto& [key, field] : {std::pair{"name:", &p.name}, std::pair{"source:", &p.note}})
        if (comment.rfind(key, 0) == 0) *field = trim(comment.substr(std::string(key).size()));
      line = line.substr(0, hash);
    }
    const auto tokens = split(line);
    if (tokens.empty()) continue;
    if (!have_format) {
      const std::string f = tokens.size() == 2 && tokens[0].text == "format" ? tokens[1].text : "";
      if (f == "knit") p.format = PatternFormat::Knit;
      else if (f == "tiles") p.format = PatternFormat::Tiles;
      else if (f == "woven") p.format = PatternFormat::Woven;
      else throw Error(source, at(line_no, tokens[0].column), "expected the format first: 'format knit', 'format tiles' or 'format woven', or written instructions that start "
                                                            "'Row 1: ...' or 'Rnd 1: ...' (patterns/FORMAT.md)");
      have_format = true;
      continue;
    }
    if (p.format != PatternFormat::Woven) {
      // Colour (issue 26): `colour A: cream #f0e6cf` lines, then after `colours` a colour name per stitch.
      if (auto c = read_colour_declaration(line, false, static_cast<int>(p.palette.size()), source, at(line_no, 0))) {
        if (in_colours || !lines.empty()) throw Error(source, at(line_no, 0), "a colour declaration after the rows: declare the colours first");
        check_new_colour(p.palette, *c, source, at(line_no, 0));
        p.palette.push_back(std::move(*c));
        continue;
      }
      if (tokens.size() > 1 && (tokens[0].text == "colour" || tokens[0].text == "color"))
        throw Error(source, at(line_no, 0), "a colour is declared 'colour NAME: DESCRIPTION' (colour MC: cream #f0e6cf), found '" + trim(line) + "'");
      if (tokens.size() == 1 && (tokens[0].text == "colours" || tokens[0].text == "colors")) {
        if (in_colours) throw Error(source, at(line_no, 0), "a second 'colours' block");
        if (p.palette.empty()) throw Error(source, at(line_no, 0), "'colours' with no colour declared: declare them first ('colour A: cream')");
        in_colours = true;
        continue;
      }
    }
    (in_colours ? colour_lines : lines).push_back({tokens, line_no});
  }
  if (!have_format) throw Error(source, "", "is empty: a pattern starts with 'format knit', 'format tiles' or 'format woven' and has at least one row");
  if (lines.empty()) throw Error(source, "", "holds no rows after its format line");

  if (p.format == PatternFormat::Woven) {
    for (auto it = lines.rbegin(); it != lines.rend(); ++it) {
      std::vector<char> row;
      for (const auto& t : it->tokens)
        for (size_t k = 0; k < t.text.size(); ++k) {
          const char c = t.text[k];
          if (c != '0' && c != '1')
            throw Error(source, at(it->line, t.column + static_cast<int>(k)), std::string("expected 0 (warp over weft) or 1 (weft over warp), found '") + c + "'");
          row.push_back(c == '1');
        }
      if (!p.over.empty() && row.size() != p.over[0].size())
        throw Error(source, at(it->line, 0), "has " + std::to_string(row.size()) + " columns but line " + std::to_string(lines.back().line) +
                                                 " has " + std::to_string(p.over[0].size()) + ": a woven pattern is a rectangular grid");
      p.over.push_back(std::move(row));
    }
    return p;
  }

  // Knits: rows of stitch types, bottom row first.
  std::vector<int> row_line;
  for (auto it = lines.rbegin(); it != lines.rend(); ++it) {
    std::vector<std::string> row;
    for (const auto& t : it->tokens) {
      if (p.format == PatternFormat::Knit) {
        int over = 0, under = 0;
        char order = '+', tail = 0;
        const int fields = std::sscanf(t.text.c_str(), "cable%dx%d%c%c", &over, &under, &order, &tail);
        if (t.text.rfind("cable", 0) == 0 && fields >= 2) {
          if (over < 1 || over > 3 || under < 1 || under > 3 || fields == 4 || (fields == 3 && order != '+' && order != '-'))
            throw Error(source, at(it->line, t.column), "a cable is cableAxB, cableAxB+ (in front) or cableAxB- (behind) with A and B from 1 to 3, found '" + t.text + "'");
          p.cables.push_back({static_cast<int>(p.rows.size()), loops_made(row), over, under, order == '-' ? -1 : 1});
          row.insert(row.end(), over + under, "k");
          continue;
        }
        if (!find_stitch_type(t.text))
          throw Error(source, at(it->line, t.column),
                      "unknown stitch '" + t.text + "'; the stitch types are: " + known_types() + ", and cables cableAxB[+|-]");
        row.push_back(t.text);
        continue;
      }
      const Tile* tile = nullptr;
      for (const auto& candidate : kTiles)
        if (t.text == candidate.code) tile = &candidate;
      if (tile) {
        row.push_back(tile->type);
        continue;
      }
      throw Error(source, at(it->line, t.column), "unknown tile '" + t.text + "'; the tiles are K P F B YS 2U Y3Y (Leaf 2018 Table 2), separated by spaces");
    }
    p.rows.push_back(std::move(row));
    row_line.push_back(it->line);
  }
  check_stacking(p, row_line, source);
  if (!p.palette.empty()) {
    // Each colour line gives its row's stitches their colours, one name per stitch face (a cable's each), or one
    // name for the whole row; no colours block: every stitch in the first colour.
    if (!colour_lines.empty() && colour_lines.size() != lines.size())
      throw Error(source, at(colour_lines.front().line, 0),
                  "the colours block has " + std::to_string(colour_lines.size()) + (colour_lines.size() == 1 ? " line" : " lines") +
                      " but the pattern " + std::to_string(lines.size()) + (lines.size() == 1 ? " row" : " rows"));
    for (size_t r = 0; r < p.rows.size(); ++r) {
      std::vector<int> colours(p.rows[r].size(), 0);
      if (!colour_lines.empty()) {
        const Row& c = colour_lines[colour_lines.size() - 1 - r];
        if (c.tokens.size() != 1 && c.tokens.size() != colours.size())
          throw Error(source, at(c.line, 0), "gives " + std::to_string(c.tokens.size()) + " colours for row " + std::to_string(r + 1) + " (line " +
                                                 std::to_string(row_line[r]) + "), which has " + std::to_string(colours.size()) +
                                                 " stitches (a cable's each): one colour per stitch, or one for the whole row");
        for (size_t k = 0; k < colours.size(); ++k) {
          const Token& t = c.tokens[c.tokens.size() == 1 ? 0 : k];
          const int i = find_colour(p.palette, t.text);
          if (i < 0) {
            std::string names;
            for (const auto& d : p.palette) names += (names.empty() ? "" : ", ") + d.name;
            throw Error(source, at(c.line, t.column), "'" + t.text + "' is not a declared colour (" + names + ")");
          }
          colours[k] = i;
        }
      }
      p.colours.push_back(std::move(colours));
    }
  } else if (!colour_lines.empty()) {
    throw Error(source, at(colour_lines.front().line, 0), "colour lines with no colours declared");
  }
  return p;
}


void check_stacking(const Pattern& p, const std::vector<int>& row_line, const std::string& source) {
  // Every row takes the loops the row below it made; the first row takes the last row's, so the repeat stacks.
  const auto at = [](int line) { return "line " + std::to_string(line); };
  const int n = static_cast<int>(p.rows.size());
  for (int r = 0; r < n; ++r) {
    if (p.whole && r + 1 == n) break;  // a shaped piece is knitted once: its last row is bound off, not stacked
    const int above = (r + 1) % n, made = loops_made(p.rows[r]), taken = loops_taken(p.rows[above]);
    if (made == taken) continue;
    const auto loops = [](int count) { return std::to_string(count) + (count == 1 ? " loop" : " loops"); };
    if (above == 0)
      throw Error(source, at(row_line[0]), "the first row takes " + loops(taken) + " but the last row (line " + std::to_string(row_line[r]) +
                                               ") makes " + std::to_string(made) + ", so the repeat cannot stack");
    throw Error(source, at(row_line[above]), "this row takes " + loops(taken) + " but the row below it (line " + std::to_string(row_line[r]) +
                                                 ") makes " + std::to_string(made) +
                                                 (p.whole ? "" : " (a repeating stitch pattern keeps its count from row to row; a shaped piece is written "
                                                                 "with 'Cast on N sts.' and every row whole)"));
  }
}

Pattern read_pattern(const std::filesystem::path& file) {
  check_input_file(file, 16u << 20);  // a pattern is text: 16 MB is far past any
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string(), "", "cannot be opened for reading");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_pattern(text.str(), file.string());
}

bool remeshes(const Pattern& pattern) {
  if (!pattern.cables.empty()) return true;
  for (const auto& row : pattern.rows)
    for (const auto& name : row)
      if (const auto* t = find_stitch_type(name); t->bottom != 1 || t->top != 1) return true;
  return false;
}

int repeat_face(const Pattern& pattern, int across, int column, int level, int place) {
  int index = level * across * pattern.stitches();
  for (const auto& row : pattern.rows) {
    const int n = static_cast<int>(row.size());
    if (place < n) return index + column * n + place;
    index += across * n;
    place -= n;
  }
  throw Error("", "pattern " + pattern.name, "has " + std::to_string(pattern.stitches()) + " faces in a repeat, fewer than the place asked for");
}

StitchMesh pattern_stitch_mesh(const Pattern& pattern, int across, int up, const StitchSize& size) {
  size.validate();
  if (pattern.format == PatternFormat::Woven) throw Error("", "pattern " + pattern.name, "is woven: it has no stitch mesh (use woven_yarn)");
  if (across < 1 || up < 1 || across > 4096 || up > 4096)
    throw Error("", "tiling", "the repeat counts must be 1 to 4096, found " + std::to_string(across) + " x " + std::to_string(up));
  if (pattern.whole && (across != 1 || up != 1))
    throw Error("", "pattern " + pattern.name, "is a shaped piece, knitted once: it is not tiled (--tile 1x1), found " + std::to_string(across) + " x " +
                                                   std::to_string(up));
  StitchMesh mesh;
  mesh.palette = pattern.palette;
  const auto vertex = [&](double x, double y) {
    mesh.vertices.emplace_back(x, y, 0.0);
    return static_cast<int>(mesh.vertices.size()) - 1;
  };
  // Every row's loops spread evenly over the width of the first row's, so that the loops an increase makes
  // are as wide as any other (its wale edges lean instead).
  const double width = pattern.width() * across * size.width;
  std::vector<int> bottom;
  for (int k = 0; k <= pattern.width() * across; ++k) bottom.push_back(vertex(k * size.width, 0));
  for (int r = 0; r < up * pattern.height(); ++r) {
    const auto& row = pattern.rows[r % pattern.height()];
    // A shaped piece's rows are as wide as their loops, centred on the first row's (decreases narrow the fabric);
    // a repeat's spread over its width.
    const double y = (r + 1) * size.height, loop = pattern.whole ? size.width : width / (across * loops_made(row));
    const double x0 = pattern.whole ? 0.5 * (width - loops_made(row) * size.width) : 0.0;
    std::vector<int> top{vertex(x0, y)};
    size_t a = 0;
    for (int copy = 0; copy < across; ++copy)
      for (size_t place = 0; place < row.size(); ++place) {
        const StitchType& type = *find_stitch_type(row[place]);
        const size_t c = top.size() - 1;
        for (int j = 1; j <= type.top; ++j) top.push_back(vertex(x0 + static_cast<double>(c + j) * loop, y));
        StitchFace face;
        face.bottom = type.bottom;
        face.row = r;
        face.type = type.name;
        if (!pattern.palette.empty()) face.colour = pattern.colours[r % pattern.height()][place];
        for (int i = 0; i <= type.bottom; ++i) face.vertices.push_back(bottom[a + i]);
        for (int j = type.top; j >= 0; --j) face.vertices.push_back(top[c + j]);
        mesh.faces.push_back(std::move(face));
        a += type.bottom;
      }
    // Cables: the course edges above their stitches, unless this is the top row.
    if (r + 1 < up * pattern.height())
      for (int copy = 0; copy < across; ++copy)
        for (const auto& cable : pattern.cables) {
          if (cable.row != r % pattern.height()) continue;
          const int first = copy * loops_made(row) + cable.first_loop;
          for (int k = first; k < first + cable.over + cable.under; ++k) mesh.cables[std::minmax(top[k], top[k + 1])] = {cable.over, cable.order};
        }
    bottom = std::move(top);
  }
  return mesh;
}

namespace {

/// The W x H plain stitches of one repeat from its bottom-left stitch `corner` (rows bottom-up, left to right),
/// or empty when they are not a grid of distinct plain stitches: each row's stitches side by side, each stitch
/// worked into the one below it.
std::vector<std::vector<int>> repeat_grid(const StitchMesh& mesh, const EdgeTable& table, int corner, int w, int h) {
  std::vector<std::vector<int>> grid(h, std::vector<int>(w, -1));
  std::set<int> seen;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const int f = c > 0 ? step(mesh, table, grid[r][c - 1], Step::Right) : r > 0 ? step(mesh, table, grid[r - 1][0], Step::Up) : corner;
      if (f < 0 || !is_plain(mesh.faces[f]) || !seen.insert(f).second) return {};
      if (r > 0 && step(mesh, table, grid[r - 1][c], Step::Up) != f) return {};
      grid[r][c] = f;
    }
  return grid;
}

/// n + 1 points spread evenly by arc length along the polyline `line`.
std::vector<Eigen::Vector3d> spread(const std::vector<Eigen::Vector3d>& line, int n) {
  std::vector<double> s{0};
  for (size_t i = 1; i < line.size(); ++i) s.push_back(s.back() + (line[i] - line[i - 1]).norm());
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k <= n; ++k) {
    const double t = s.back() * k / n;
    size_t i = 1;
    while (i + 1 < line.size() && s[i] < t) ++i;
    const double a = s[i] > s[i - 1] ? std::clamp((t - s[i - 1]) / (s[i] - s[i - 1]), 0.0, 1.0) : 0.0;
    out.push_back((1 - a) * line[i - 1] + a * line[i]);
  }
  return out;
}

/// Yuksel 2012 §5.3: each repeat's W x H plain stitches are removed and the pattern's faces generated in their
/// place. The repeat's border keeps its vertices (its first row takes W loops and its last makes W); the
/// course lines inside it get as many edges as the pattern's rows make loops, spread evenly along the old line.
/// `colour`: the mesh's palette index of each pattern colour (empty for a pattern in one colour: the new stitches
/// then keep the colour of the stitch they lie over).
StitchMesh replace_repeats(const StitchMesh& mesh, const std::vector<std::vector<std::vector<int>>>& repeats, const Pattern& pattern,
                           const std::vector<int>& colour) {
  StitchMesh out = mesh;
  const int w = pattern.width(), h = pattern.height();
  std::vector<char> removed(mesh.faces.size(), 0);
  std::set<int> freed;  // old vertices inside repeats, dropped unless taken again
  std::vector<StitchFace> added;
  const EdgeTable table = edge_table(mesh);
  for (const auto& grid : repeats) {
    // The course lines, bottom to top: line r runs under row r (line h over the last row).
    std::vector<std::vector<int>> lines(h + 1);
    for (int r = 0; r <= h; ++r) {
      const auto& f = mesh.faces[grid[std::min(r, h - 1)][0]];
      lines[r].push_back(r < h ? f.vertex(0) : f.vertex(3));
      for (int c = 0; c < w; ++c) {
        const auto& g = mesh.faces[grid[std::min(r, h - 1)][c]];
        lines[r].push_back(r < h ? g.vertex(1) : g.vertex(2));
      }
    }
    for (int r = 1; r < h; ++r) {
      for (size_t k = 0; k + 1 < lines[r].size(); ++k) out.cables.erase(std::minmax(lines[r][k], lines[r][k + 1]));
      const int n = loops_made(pattern.rows[r - 1]);
      std::vector<Eigen::Vector3d> old;
      for (int v : lines[r]) old.push_back(mesh.vertices[v]);
      const auto at = spread(old, n);
      std::vector<int> line{lines[r].front()};
      for (int k = 1; k < n; ++k) {
        const int v = k < w ? lines[r][k] : static_cast<int>(out.vertices.size());
        if (k < w) out.vertices[v] = at[k];
        else out.vertices.push_back(at[k]);
        line.push_back(v);
      }
      for (int k = n; k < w; ++k) freed.insert(lines[r][k]);
      line.push_back(lines[r].back());
      lines[r] = std::move(line);
    }
    for (int r = 0; r < h; ++r) {
      for (int f : grid[r]) removed[f] = 1;
      const auto& row = pattern.rows[r];
      const int taken = loops_taken(row);
      int a = 0, c = 0;
      for (size_t place = 0; place < row.size(); ++place) {
        const StitchType& type = *find_stitch_type(row[place]);
        // The old stitch under the new one's middle gives its input face.
        const int under = grid[r][std::min(w - 1, (2 * a + type.bottom) * w / (2 * taken))];
        StitchFace face;
        face.bottom = type.bottom;
        face.row = mesh.faces[under].row;
        face.type = type.name;
        face.input_face = mesh.faces[under].input_face;
        face.colour = colour.empty() ? mesh.faces[under].colour : colour[static_cast<size_t>(pattern.colours[r][place])];
        for (int i = 0; i <= type.bottom; ++i) face.vertices.push_back(lines[r][a + i]);
        for (int j = type.top; j >= 0; --j) face.vertices.push_back(lines[r + 1][c + j]);
        added.push_back(std::move(face));
        a += type.bottom;
        c += type.top;
      }
    }
    // Cables: on the course edges above their stitches, the repeat's top line included where a stitch is above.
    for (const auto& cable : pattern.cables)
      for (int k = cable.first_loop; k < cable.first_loop + cable.over + cable.under; ++k) {
        const int u = lines[cable.row + 1][k], v = lines[cable.row + 1][k + 1];
        const auto uses = table.find(edge_key(u, v));
        if (cable.row + 1 < h || (uses != table.end() && uses->second.count == 2)) out.cables[std::minmax(u, v)] = {cable.over, cable.order};
      }
  }
  std::vector<StitchFace> faces;
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    if (!removed[f]) faces.push_back(std::move(out.faces[f]));
  faces.insert(faces.end(), std::make_move_iterator(added.begin()), std::make_move_iterator(added.end()));
  out.faces = std::move(faces);
  // Drop the freed vertices no new face took, renumbering the rest.
  for (const auto& face : out.faces)
    for (int v : face.vertices) freed.erase(v);
  if (!freed.empty()) {
    std::vector<int> index(out.vertices.size(), -1);
    std::vector<Eigen::Vector3d> kept;
    for (size_t v = 0; v < out.vertices.size(); ++v)
      if (!freed.count(static_cast<int>(v))) index[v] = static_cast<int>(kept.size()), kept.push_back(out.vertices[v]);
    out.vertices = std::move(kept);
    for (auto& face : out.faces)
      for (int& v : face.vertices) v = index[v];
    std::map<std::pair<int, int>, CableMark> cables;
    for (const auto& [edge, mark] : out.cables) cables[std::minmax(index[edge.first], index[edge.second])] = mark;
    out.cables = std::move(cables);
  }
  return out;
}

}  // namespace

StitchMesh tile_pattern(const StitchMesh& mesh, const std::vector<int>& faces, const Pattern& pattern, int origin, TileReport* report) {
  if (pattern.format == PatternFormat::Woven) throw Error("", "pattern " + pattern.name, "is woven: it cannot be tiled onto a stitch mesh");
  if (pattern.whole) throw Error("", "pattern " + pattern.name, "is a shaped piece, knitted as its own fabric: it cannot be tiled onto a stitch mesh");
  const int n = static_cast<int>(mesh.faces.size());
  if (origin < 0 || origin >= n) throw Error("", "face " + std::to_string(origin), "does not exist (the stitch mesh has " + std::to_string(n) + " faces)");
  for (int f : faces)
    if (f < 0 || f >= n) throw Error("", "face " + std::to_string(f), "does not exist");
  TileReport counts;
  StitchMesh out = mesh;
  // A pattern in colour brings its palette into the mesh's; stitches it does not reach keep theirs (the first
  // colour, where the mesh had none: the pattern's main colour).
  const std::vector<int> colour = merge_palette(out.palette, pattern.palette);
  if (!remeshes(pattern)) {
    // Plain stitches only: each chosen plain stitch takes the pattern's type at its row and column from the
    // origin, modulo the repeat, so the repeat may be cut anywhere.
    const StitchGrid grid = stitch_grid(mesh);
    const auto mod = [](long a, long m) { return ((a % m) + m) % m; };
    for (int f : faces) {
      auto& face = out.faces[f];
      if (!is_plain(face)) continue;
      const long r = mod(grid.level[f] - grid.level[origin], pattern.height());
      const long c = mod(grid.column[f] - grid.column[origin], static_cast<long>(pattern.rows[r].size()));
      face.type = pattern.rows[r][c];
      if (!colour.empty()) face.colour = colour[static_cast<size_t>(pattern.colours[r][c])];
      ++counts.stitches;
    }
  } else {
    // Increases, decreases, lace or cables re-mesh: whole repeats only, each over W x H chosen plain stitches,
    // on the lattice of repeats from the origin (found by walking W stitches along the row and H up the wale).
    if (!is_plain(mesh.faces[origin]))
      throw Error("", "face " + std::to_string(origin), "is not a plain stitch: a pattern that re-meshes its stitches starts on one");
    const int w = pattern.width(), h = pattern.height();
    const EdgeTable table = edge_table(mesh);
    const std::set<int> chosen(faces.begin(), faces.end());
    std::vector<char> used(mesh.faces.size(), 0);
    std::vector<std::vector<std::vector<int>>> repeats;
    std::set<int> visited{origin};
    std::vector<int> queue{origin};
    while (!queue.empty()) {
      const int corner = queue.back();
      queue.pop_back();
      const auto grid = repeat_grid(mesh, table, corner, w, h);
      bool fits = !grid.empty(), touches = false;
      for (const auto& row : grid)
        for (int f : row) {
          fits = fits && chosen.count(f) && !used[f];
          touches = touches || chosen.count(f);
        }
      if (fits) {
        for (const auto& row : grid)
          for (int f : row) used[f] = 1;
        repeats.push_back(grid);
      }
      if (!touches && corner != origin) continue;
      for (const auto& [s, k] : {std::pair{Step::Right, w}, std::pair{Step::Left, w}, std::pair{Step::Up, h}, std::pair{Step::Down, h}})
        if (const int next = steps(mesh, table, corner, s, k); next >= 0 && visited.insert(next).second) queue.push_back(next);
    }
    if (repeats.empty())
      throw Error("", "pattern " + pattern.name,
                  "re-meshes whole repeats of " + std::to_string(w) + " x " + std::to_string(h) + " plain stitches, and none fits among the chosen stitches from face " +
                      std::to_string(origin));
    out = replace_repeats(out, repeats, pattern, colour);
    counts.repeats = static_cast<int>(repeats.size());
    counts.stitches = counts.repeats * w * h;
    const StitchReport check = validate(out);
    if (!check.valid()) throw Error("", "pattern " + pattern.name, "tiling refused: it would leave " + check.summary(1));
  }
  if (report) *report = counts;
  return out;
}

void colour_woven_yarn(relax::YarnCurves& yarn, const Pattern& pattern, int across, int up) {
  if (pattern.palette.empty() || pattern.weft_colours.empty() || pattern.warp_colours.empty()) return;
  const int rows = up * pattern.height();
  if (yarn.curves() != rows + across * pattern.width()) throw Error("", "pattern " + pattern.name, "the yarn is not its woven yarn at this tiling");
  yarn.colours.clear();
  for (const auto& c : pattern.palette) yarn.colours.push_back({c.name, c.srgb});
  yarn.point_colour.assign(yarn.points.size(), 0);
  for (int c = 0; c < yarn.curves(); ++c) {
    const int colour = c < rows ? pattern.weft_colours[c % pattern.height()] : pattern.warp_colours[(c - rows) % pattern.width()];
    std::fill(yarn.point_colour.begin() + yarn.curve_start[c], yarn.point_colour.begin() + yarn.curve_start[c + 1], colour);
  }
}

relax::YarnCurves woven_yarn(const Pattern& pattern, int across, int up, double spacing, double radius) {
  if (pattern.format != PatternFormat::Woven) throw Error("", "pattern " + pattern.name, "is knitted: its yarn comes from its stitch mesh");
  if (across < 1 || up < 1 || across > 4096 || up > 4096)
    throw Error("", "tiling", "the repeat counts must be 1 to 4096, found " + std::to_string(across) + " x " + std::to_string(up));
  if (!(radius > 0) || !(spacing >= 2 * radius) || !std::isfinite(spacing))
    throw Error("", "weave", "the yarn radius must be positive and the spacing at least a yarn diameter");
  relax::YarnCurves yarn;
  yarn.radius = radius;
  yarn.type_names = {"weft", "warp"};
  const int rows = up * pattern.height(), cols = across * pattern.width();
  const auto over = [&](int i, int j) { return pattern.over[i % pattern.height()][j % pattern.width()] != 0; };
  const auto add = [&](const Eigen::Vector3d& p, int type) {
    yarn.points.push_back(p);
    yarn.point_face.push_back(-1);
    yarn.point_type.push_back(type);
  };
  const auto end_curve = [&] {
    yarn.curve_start.push_back(static_cast<int>(yarn.points.size()));
    yarn.closed.push_back(0);
  };
  // Each yarn runs half a spacing past the last yarn it crosses, in the plane, and touches every yarn it
  // crosses from above or below (centrelines a yarn diameter apart).
  for (int i = 0; i < rows; ++i) {
    add({-0.5 * spacing, i * spacing, 0}, 0);
    for (int j = 0; j < cols; ++j) add({j * spacing, i * spacing, over(i, j) ? radius : -radius}, 0);
    add({(cols - 0.5) * spacing, i * spacing, 0}, 0);
    end_curve();
  }
  for (int j = 0; j < cols; ++j) {
    add({j * spacing, -0.5 * spacing, 0}, 1);
    for (int i = 0; i < rows; ++i) add({j * spacing, i * spacing, over(i, j) ? -radius : radius}, 1);
    add({j * spacing, (rows - 0.5) * spacing, 0}, 1);
    end_curve();
  }
  return yarn;
}

}  // namespace skein::mesh
