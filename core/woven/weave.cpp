#include "woven/weave.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <sstream>

#include "common/error.hpp"
#include "workflow/yarn_io.hpp"

namespace skein::woven {

Weave make_weave(int warps, int wefts) {
  if (warps < 1 || wefts < 1) throw Error("", "weave", "needs at least one warp and one weft");
  return {warps, wefts, std::vector<char>(static_cast<size_t>(warps) * wefts, 0)};
}

Weave from_pattern(const mesh::Pattern& pattern) {
  if (pattern.format != mesh::PatternFormat::Woven) throw Error("", "pattern " + pattern.name, "is knitted, not woven");
  Weave w = make_weave(pattern.width(), pattern.height());
  for (int i = 0; i < w.wefts; ++i)
    for (int j = 0; j < w.warps; ++j) w.set(i, j, pattern.over[i][j] == 0);
  return w;
}

Weave tiled(const Weave& repeat, int warps, int wefts) {
  Weave w = make_weave(warps, wefts);
  for (int i = 0; i < wefts; ++i)
    for (int j = 0; j < warps; ++j) w.set(i, j, repeat.at(i % repeat.wefts, j % repeat.warps));
  return w;
}

std::string to_text(const Weave& weave) {
  std::string text;
  for (int i = weave.wefts - 1; i >= 0; --i) {
    for (int j = 0; j < weave.warps; ++j) text += weave.at(i, j) ? '#' : '.';
    text += '\n';
  }
  return text;
}

Weave from_text(const std::string& text, const std::string& source) {
  std::vector<std::string> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) rows.push_back(line);
  if (rows.empty()) throw Error(source, "weave", "holds no rows");
  Weave w = make_weave(static_cast<int>(rows[0].size()), static_cast<int>(rows.size()));
  for (size_t r = 0; r < rows.size(); ++r) {
    const std::string where = "weave row " + std::to_string(r + 1);
    if (static_cast<int>(rows[r].size()) != w.warps)
      throw Error(source, where, "has " + std::to_string(rows[r].size()) + " crossings, the first row " + std::to_string(w.warps));
    for (int j = 0; j < w.warps; ++j) {
      const char c = rows[r][j];
      if (c != '#' && c != '.') throw Error(source, where, std::string("holds '") + c + "': crossings are '#' (warp up) or '.' (weft up)");
      w.set(w.wefts - 1 - static_cast<int>(r), j, c == '#');
    }
  }
  return w;
}

Weave weave_from_labels(const std::vector<int>& labels, int width, int height, const std::vector<Weave>& weaves, const std::vector<int>& map) {
  if (static_cast<long>(labels.size()) != static_cast<long>(width) * height) throw Error("", "picture", "has the wrong number of pixels");
  Weave w = make_weave(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int label = labels[static_cast<size_t>(y) * width + x];
      if (label < 0 || label >= static_cast<int>(map.size()))
        throw Error("", "picture pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")", "has a colour with no weave");
      const int v = map[label];
      if (v < 0 || v >= static_cast<int>(weaves.size())) throw Error("", "colour " + std::to_string(label), "maps to no elementary weave");
      const Weave& e = weaves[v];
      const int weft = height - 1 - y;
      w.set(weft, x, e.at(weft % e.wefts, x % e.warps));
    }
  return w;
}

namespace {

/// Where the projections onto z = 0 of two polylines first cross: the heights of both there.
std::optional<std::pair<double, double>> crossing_heights(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  for (size_t s = 0; s + 1 < a.size(); ++s)
    for (size_t t = 0; t + 1 < b.size(); ++t) {
      const Eigen::Vector2d p = a[s].head<2>(), r = a[s + 1].head<2>() - p, q = b[t].head<2>(), d = b[t + 1].head<2>() - q;
      const double den = r.x() * d.y() - r.y() * d.x();
      if (std::abs(den) < 1e-15) continue;
      const Eigen::Vector2d pq = q - p;
      const double u = (pq.x() * d.y() - pq.y() * d.x()) / den, v = (pq.x() * r.y() - pq.y() * r.x()) / den;
      if (u < 0 || u > 1 || v < 0 || v > 1) continue;
      return std::pair{a[s].z() + u * (a[s + 1].z() - a[s].z()), b[t].z() + v * (b[t + 1].z() - b[t].z())};
    }
  return std::nullopt;
}

}  // namespace

Weave detect_weave(const relax::YarnCurves& yarn, const std::vector<int>& warp_curves, const std::vector<int>& weft_curves) {
  const auto samples = workflow::sample_curves(yarn, 8);
  Weave w = make_weave(static_cast<int>(warp_curves.size()), static_cast<int>(weft_curves.size()));
  for (int i = 0; i < w.wefts; ++i)
    for (int j = 0; j < w.warps; ++j) {
      const auto heights = crossing_heights(samples[warp_curves[j]], samples[weft_curves[i]]);
      if (!heights)
        throw Error("", "yarn", "warp " + std::to_string(j) + " (curve " + std::to_string(warp_curves[j]) + ") and weft " + std::to_string(i) +
                                    " do not cross");
      w.set(i, j, heights->first > heights->second);
    }
  return w;
}

std::vector<int> picture_labels(const render::Image& image, int& colours) {
  std::map<std::array<std::uint8_t, 3>, int> index;
  std::vector<int> labels(static_cast<size_t>(image.width) * image.height);
  for (size_t k = 0; k < labels.size(); ++k) {
    const std::array<std::uint8_t, 3> c{image.rgb[3 * k], image.rgb[3 * k + 1], image.rgb[3 * k + 2]};
    labels[k] = index.emplace(c, static_cast<int>(index.size())).first->second;
  }
  colours = static_cast<int>(index.size());
  return labels;
}

}  // namespace skein::woven
