#include "stitchmesh/pattern.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/error.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/stitch_types.hpp"

namespace skein::mesh {
namespace {

/// Leaf 2018 Table 2's tiles that have a stitch-mesh face: knit, purl, and the slipped front and back stitches.
struct Tile {
  const char* code;
  const char* type;
};
constexpr Tile kTiles[] = {{"K", "k"}, {"P", "p"}, {"F", "sk"}, {"B", "s"}};
/// Leaf's lace tiles: a yarn-over and a decrease across two or three loops, which no single stitch-mesh face
/// shape holds (faces take one loop to several or several to one).
constexpr const char* kLaceTiles[] = {"YS", "2U", "Y3Y"};

struct Token {
  std::string text;
  int column;  // 1-based
};
struct Row {
  std::vector<Token> tokens;
  int line;
};

std::vector<Token> split(const std::string& line) {
  std::vector<Token> out;
  for (size_t i = 0; i < line.size();) {
    if (std::isspace(static_cast<unsigned char>(line[i]))) {
      ++i;
      continue;
    }
    const size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    out.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return out;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

std::string known_types() {
  std::string names;
  for (const auto& t : stitch_types()) names += (names.empty() ? "" : " ") + t.name;
  return names;
}

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

}  // namespace

int Pattern::width() const {
  if (format == PatternFormat::Woven) return over.empty() ? 0 : static_cast<int>(over[0].size());
  return rows.empty() ? 0 : loops_taken(rows[0]);
}
int Pattern::height() const { return static_cast<int>(format == PatternFormat::Woven ? over.size() : rows.size()); }

Pattern parse_pattern(const std::string& text, const std::string& source) {
  Pattern p;
  p.name = std::filesystem::path(source).stem().string();
  std::istringstream in(text);
  std::string raw;
  int line_no = 0;
  bool have_format = false;
  std::vector<Row> lines;  // top line first, as written
  const auto at = [&](int line, int column) { return "line " + std::to_string(line) + (column > 0 ? ", column " + std::to_string(column) : ""); };
  while (std::getline(in, raw)) {
    ++line_no;
    std::string line = raw;
    if (const auto hash = line.find('#'); hash != std::string::npos) {
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
      else throw Error(source, at(line_no, tokens[0].column), "expected the format first: 'format knit', 'format tiles' or 'format woven'");
      have_format = true;
      continue;
    }
    lines.push_back({tokens, line_no});
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
      for (const char* lace : kLaceTiles)
        if (t.text == lace)
          throw Error(source, at(it->line, t.column),
                      "tile " + t.text + " (a yarn-over with a decrease across several loops) has no stitch-mesh face yet: write it in 'format knit' with an "
                      "increase and a decrease (e.g. kyk and d123k)");
      throw Error(source, at(it->line, t.column), "unknown tile '" + t.text + "'; the tiles are K P F B (Leaf 2018 Table 2), separated by spaces");
    }
    p.rows.push_back(std::move(row));
    row_line.push_back(it->line);
  }
  // Every row takes the loops the row below it made; the first row takes the last row's, so the repeat stacks.
  const int n = static_cast<int>(p.rows.size());
  for (int r = 0; r < n; ++r) {
    const int above = (r + 1) % n, made = loops_made(p.rows[r]), taken = loops_taken(p.rows[above]);
    if (made == taken) continue;
    if (above == 0)
      throw Error(source, at(row_line[0], 0), "the first row takes " + std::to_string(taken) + " loops but the last row (line " +
                                                  std::to_string(row_line[r]) + ") makes " + std::to_string(made) + ", so the repeat cannot stack");
    throw Error(source, at(row_line[above], 0), "this row takes " + std::to_string(taken) + " loops but the row below it (line " +
                                                    std::to_string(row_line[r]) + ") makes " + std::to_string(made));
  }
  return p;
}

Pattern read_pattern(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string(), "", "cannot be opened for reading");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_pattern(text.str(), file.string());
}

StitchMesh pattern_stitch_mesh(const Pattern& pattern, int across, int up, const StitchSize& size) {
  size.validate();
  if (pattern.format == PatternFormat::Woven) throw Error("", "pattern " + pattern.name, "is woven: it has no stitch mesh (use woven_yarn)");
  if (across < 1 || up < 1 || across > 4096 || up > 4096)
    throw Error("", "tiling", "the repeat counts must be 1 to 4096, found " + std::to_string(across) + " x " + std::to_string(up));
  StitchMesh mesh;
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
    const double y = (r + 1) * size.height, loop = width / (across * loops_made(row));
    std::vector<int> top{vertex(0, y)};
    size_t a = 0;
    for (int copy = 0; copy < across; ++copy)
      for (const auto& name : row) {
        const StitchType& type = *find_stitch_type(name);
        const size_t c = top.size() - 1;
        for (int j = 1; j <= type.top; ++j) top.push_back(vertex(static_cast<double>(c + j) * loop, y));
        StitchFace face;
        face.bottom = type.bottom;
        face.row = r;
        face.type = type.name;
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

StitchMesh tile_pattern(const StitchMesh& mesh, const std::vector<int>& faces, const Pattern& pattern, int origin) {
  if (pattern.format == PatternFormat::Woven) throw Error("", "pattern " + pattern.name, "is woven: it cannot be tiled onto a stitch mesh");
  for (const auto& row : pattern.rows)
    for (const auto& name : row)
      if (const auto* t = find_stitch_type(name); t->bottom != 1 || t->top != 1)
        throw Error("", "pattern " + pattern.name,
                    "has the " + name + " stitch (" + std::to_string(t->bottom) + " loops below, " + std::to_string(t->top) +
                        " above): only patterns of plain stitches tile onto a stitch mesh so far, since others would re-mesh the region");
  const int n = static_cast<int>(mesh.faces.size());
  if (origin < 0 || origin >= n) throw Error("", "face " + std::to_string(origin), "does not exist (the stitch mesh has " + std::to_string(n) + " faces)");
  for (int f : faces)
    if (f < 0 || f >= n) throw Error("", "face " + std::to_string(f), "does not exist");
  const StitchGrid grid = stitch_grid(mesh);
  const auto mod = [](long a, long m) { return ((a % m) + m) % m; };
  StitchMesh out = mesh;
  for (int f : faces) {
    auto& face = out.faces[f];
    if (face.bottom != 1 || face.top() != 1) continue;
    const auto& row = pattern.rows[mod(grid.level[f] - grid.level[origin], pattern.height())];
    face.type = row[mod(grid.column[f] - grid.column[origin], static_cast<long>(row.size()))];
  }
  return out;
}

YarnCurves woven_yarn(const Pattern& pattern, int across, int up, double spacing, double radius) {
  if (pattern.format != PatternFormat::Woven) throw Error("", "pattern " + pattern.name, "is knitted: its yarn comes from its stitch mesh");
  if (across < 1 || up < 1 || across > 4096 || up > 4096)
    throw Error("", "tiling", "the repeat counts must be 1 to 4096, found " + std::to_string(across) + " x " + std::to_string(up));
  if (!(radius > 0) || !(spacing >= 2 * radius) || !std::isfinite(spacing))
    throw Error("", "weave", "the yarn radius must be positive and the spacing at least a yarn diameter");
  YarnCurves yarn;
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
