#include "woven/synthesis.hpp"

#include <algorithm>
#include <array>
#include <random>
#include <unordered_map>

#include "common/error.hpp"

namespace skein::woven {

namespace {

constexpr std::array<std::array<int, 2>, 4> kSteps{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};  // (d_weft, d_warp)

/// A crossing's weave neighbourhood: its own value and, per step, 0 (absent), 1 (weft up) or 2 (warp up).
int neighbourhood(const Weave& w, int i, int j) {
  int key = w.at(i, j) ? 1 : 0;
  for (const auto& [di, dj] : kSteps) {
    const int a = i + di, b = j + dj;
    key = key * 3 + (a < 0 || b < 0 || a >= w.wefts || b >= w.warps ? 0 : w.at(a, b) ? 2 : 1);
  }
  return key;
}

/// The blocks of every exemplar that are correct for the target's crossing (weft i, warp j) and match the most
/// of its neighbours (principles 1 and 2); `best` is that number.
std::vector<Block> best_blocks(const Weave& target, int i, int j, const std::vector<Weave>& exemplars, int& best) {
  std::vector<Block> out;
  best = -1;
  for (int u = 0; u < static_cast<int>(exemplars.size()); ++u)
    for (int y = 0; y < exemplars[u].wefts; ++y)
      for (int x = 0; x < exemplars[u].warps; ++x) {
        if (exemplars[u].at(y, x) != target.at(i, j)) continue;
        const int m = neighbour_matches(target, i, j, exemplars[u], x, y);
        if (m > best) best = m, out.clear();
        if (m == best) out.push_back({u, x, y});
      }
  return out;
}

}  // namespace

int neighbour_matches(const Weave& target, int weft, int warp, const Weave& exemplar, int x, int y) {
  int m = 0;
  for (const auto& [di, dj] : kSteps) {
    const int a = weft + di, b = warp + dj;
    if (a < 0 || b < 0 || a >= target.wefts || b >= target.warps) continue;
    const int ey = y + di, ex = x + dj;
    if (ey < 0 || ex < 0 || ey >= exemplar.wefts || ex >= exemplar.warps) continue;
    m += exemplar.at(ey, ex) == target.at(a, b);
  }
  return m;
}

bool continuous(const Block& a, const Block& b, int d_weft, int d_warp) {
  return a.exemplar >= 0 && a.exemplar == b.exemplar && b.x - a.x == d_warp && b.y - a.y == d_weft;
}

Assignment synthesize(const Weave& target, const std::vector<Weave>& exemplars, const SynthesisOptions& options) {
  if (exemplars.empty()) throw Error("", "synthesis", "needs at least one exemplar");
  if (options.group < 1) throw Error("", "synthesis", "the randomization's group must be at least one crossing");
  int largest = 0;
  for (const auto& e : exemplars) largest = std::max({largest, e.warps, e.wefts});
  // Candidates depend only on the crossing's neighbourhood (and, at the fabric's edges, on which neighbours
  // exist, which the key holds): solve each neighbourhood once.
  std::unordered_map<int, std::vector<Block>> candidates;
  std::vector<int> key(static_cast<size_t>(target.warps) * target.wefts);
  for (int i = 0; i < target.wefts; ++i)
    for (int j = 0; j < target.warps; ++j) {
      const int k = key[static_cast<size_t>(i) * target.warps + j] = neighbourhood(target, i, j);
      if (candidates.count(k)) continue;
      int best = 0;
      auto blocks = best_blocks(target, i, j, exemplars, best);
      if (blocks.empty())
        throw Error("", "synthesis", std::string("no exemplar has a crossing with the ") + (target.at(i, j) ? "warp" : "weft") +
                                         " on top (weft " + std::to_string(i) + ", warp " + std::to_string(j) + " needs one)");
      candidates.emplace(k, std::move(blocks));
    }
  const auto code = [&](const Block& b) { return (static_cast<long>(b.exemplar) * largest + b.x) * largest + b.y; };
  Assignment out{target.warps, target.wefts, std::vector<Block>(key.size())};
  // Eq. 1, column by column: f(i, t) = max_t' f(i - 1, t') + gain(t', t), gain 1 when t' is the block below t.
  std::vector<std::vector<double>> f(target.wefts);
  std::vector<std::vector<int>> from(target.wefts);
  for (int j = 0; j < target.warps; ++j) {
    std::unordered_map<long, int> previous;  // block code -> index in row i - 1's candidates
    for (int i = 0; i < target.wefts; ++i) {
      const auto& c = candidates.at(key[static_cast<size_t>(i) * target.warps + j]);
      f[i].assign(c.size(), 0.0);
      from[i].assign(c.size(), -1);
      int best_prev = -1;
      if (i > 0)
        for (int t = 0; t < static_cast<int>(f[i - 1].size()); ++t)
          if (best_prev < 0 || f[i - 1][t] > f[i - 1][best_prev]) best_prev = t;
      std::unordered_map<long, int> here;
      for (int t = 0; t < static_cast<int>(c.size()); ++t) {
        double value = 0;
        if (i > 0) {
          value = f[i - 1][best_prev], from[i][t] = best_prev;
          const auto below = previous.find(code({c[t].exemplar, c[t].x, c[t].y - 1}));
          if (below != previous.end() && f[i - 1][below->second] + 1 > value) value = f[i - 1][below->second] + 1, from[i][t] = below->second;
        }
        if (options.horizontal && j > 0 && continuous(out.at(i, j - 1), c[t], 0, 1)) value += 1;
        f[i][t] = value;
        here.emplace(code(c[t]), t);
      }
      previous = std::move(here);
    }
    int t = 0;
    for (int s = 1; s < static_cast<int>(f[target.wefts - 1].size()); ++s)
      if (f[target.wefts - 1][s] > f[target.wefts - 1][t]) t = s;
    for (int i = target.wefts - 1; i >= 0; --i) {
      out.at(i, j) = candidates.at(key[static_cast<size_t>(i) * target.warps + j])[t];
      t = from[i][t];
    }
  }
  if (!options.randomize) return out;
  // Randomization: one shift per group of blocks, kept only where every block of the group lands on a block of
  // its exemplar with the same neighbourhood (so correctness, consistency and the group's continuity stay);
  // up to 32 random shifts are tried per group, and a group that none fits keeps its blocks.
  std::mt19937_64 random(options.seed);
  std::vector<std::array<int, 2>> shifts;
  for (int dy = -largest + 1; dy < largest; ++dy)
    for (int dx = -largest + 1; dx < largest; ++dx)
      if (dx != 0 || dy != 0) shifts.push_back({dx, dy});
  for (int gi = 0; gi < target.wefts; gi += options.group)
    for (int gj = 0; gj < target.warps; gj += options.group) {
      std::shuffle(shifts.begin(), shifts.end(), random);
      for (int tries = 0; tries < std::min<int>(32, shifts.size()); ++tries) {
        const auto [dx, dy] = shifts[tries];
        bool fits = true;
        for (int i = gi; fits && i < std::min(gi + options.group, target.wefts); ++i)
          for (int j = gj; fits && j < std::min(gj + options.group, target.warps); ++j) {
            const Block& b = out.at(i, j);
            const Weave& e = exemplars[b.exemplar];
            const int x = b.x + dx, y = b.y + dy;
            fits = x >= 0 && y >= 0 && x < e.warps && y < e.wefts && neighbourhood(e, y, x) == neighbourhood(e, b.y, b.x);
          }
        if (!fits) continue;
        for (int i = gi; i < std::min(gi + options.group, target.wefts); ++i)
          for (int j = gj; j < std::min(gj + options.group, target.warps); ++j) out.at(i, j).x += dx, out.at(i, j).y += dy;
        break;
      }
    }
  return out;
}

SynthesisScore score(const Weave& target, const std::vector<Weave>& exemplars, const Assignment& a) {
  SynthesisScore s;
  std::unordered_map<int, int> best;
  for (int i = 0; i < target.wefts; ++i)
    for (int j = 0; j < target.warps; ++j) {
      ++s.crossings;
      const Block& b = a.at(i, j);
      const Weave& e = exemplars.at(b.exemplar);
      s.correct += e.at(b.y, b.x) == target.at(i, j);
      const int m = neighbour_matches(target, i, j, e, b.x, b.y);
      s.matches += m;
      int present = 0;
      for (const auto& [di, dj] : kSteps) present += i + di >= 0 && j + dj >= 0 && i + di < target.wefts && j + dj < target.warps;
      s.consistent += m == present;
      const int k = neighbourhood(target, i, j);
      if (!best.count(k)) best_blocks(target, i, j, exemplars, best[k]);
      s.best_matches += best[k];
      if (i + 1 < target.wefts) s.continuity += continuous(b, a.at(i + 1, j), 1, 0);
      if (j + 1 < target.warps) s.continuity += continuous(b, a.at(i, j + 1), 0, 1);
    }
  return s;
}

}  // namespace skein::woven
