// skein-stitches: writes the stitch library (stitches/*.stitch) from a few parametric builders.
// Canonical face: u across the course (0 left .. 1 right), v along the wale (0 bottom .. 1 top), h along the
// surface normal in yarn radii (+ = front, the knit side). A face holds the head of each loop from the row
// below (entering and leaving through its bottom edge) and the lower half of each new loop (the row's yarn
// entering at the left wale edge, rising through the top edges and leaving at the right wale edge), Yuksel
// 2012 §4.1 and Fig. 3. Threading is encoded in the offsets: a knit loop's legs pass behind the head's sides
// and in front of its top, so it is pulled through from back to front; purl is the mirror image.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "stitchmesh/stitch_model.hpp"

using namespace skein::mesh;

namespace {

constexpr double kSinker = 0.28;  // v of the row yarn between loops
constexpr double kHead = 0.62;    // v where the legs pass the heads from below
constexpr double kUpper = 0.84;   // v of the legs' last point before the top edge
constexpr double kSide = 0.12;    // u of the heads' sides (and 1 - kSide)

ModelPoint at(double u, double v, double h) { return {Eigen::Vector3d(u, v, h), std::nullopt}; }
ModelPoint cross(Crossing::Side side, int edge = 0, int slot = 0) { return {Eigen::Vector3d::Zero(), Crossing{side, edge, slot}}; }
ModelPoint left() { return cross(Crossing::Side::Left); }
ModelPoint right() { return cross(Crossing::Side::Right); }
ModelPoint bottom(int e, int slot) { return cross(Crossing::Side::Bottom, e, slot); }
ModelPoint top(int e, int slot) { return cross(Crossing::Side::Top, e, slot); }

/// How a new loop takes the head(s) below: knit pulls through from the back, purl from the front, a yarn-over
/// does not pass through at all (it stays behind the head).
enum class Action { Knit, Purl, YarnOver };
double leg_at_head(Action a) { return a == Action::Knit ? 1 : -1; }   // leg offset where it passes the head top
double leg_at_sinker(Action a) { return a == Action::Purl ? 1 : -1; }  // leg bottom and sinker offset

struct Loop {
  Action action = Action::Knit;
  int twist = 0;        ///< ±1: the legs cross above the heads (twisted top connection, Yuksel §4.2)
  bool crossed = false; ///< the legs cross below the heads (x)
};

/// u of a loop's legs where they pass the heads. Several loops share the middle 60% of the face, leaving
/// lanes at the sides for the sinker and the heads' sides.
double leg_u(int j, int loops, bool right_leg) {
  const double spread = loops == 1 ? 1.0 : 0.6 / 0.76;
  return 0.5 + spread * ((j + (right_leg ? 0.64 : 0.36)) / loops - 0.5);
}

/// The row's yarn through a face: nt + 1 pieces, L → loop 0 → loop 1 … → R.
std::vector<YarnPiece> row_yarn(const std::vector<Loop>& loops) {
  const int nt = static_cast<int>(loops.size());
  std::vector<YarnPiece> pieces;
  // Rising leg of loop j from its bottom to the top edge, and the falling leg the other way.
  const auto rise = [&](YarnPiece& p, int j) {
    const Loop& l = loops[j];
    const double lam = leg_at_head(l.action), beta = leg_at_sinker(l.action);
    const double uL = leg_u(j, nt, false), uR = leg_u(j, nt, true);
    if (l.crossed) {  // the left leg crosses in front to the right before reaching the heads
      p.points.push_back(at(uL, kSinker, beta));
      p.points.push_back(at(0.5 * (uL + uR), 0.45, beta + 1));
      p.points.push_back(at(uR, kHead, lam));
    } else {
      p.points.push_back(at(uL, kSinker, beta));
      p.points.push_back(at(uL, kHead, lam));
    }
    const bool lands_right = (l.twist != 0) != l.crossed;
    if (l.twist != 0) p.points.push_back(at((j + 0.5) / nt, kUpper, lam + l.twist));
    else p.points.push_back(at((j + (lands_right ? 0.69 : 0.31)) / nt, kUpper, 0.5 * lam));
    p.points.push_back(top(j, lands_right ? 1 : 0));
  };
  const auto fall = [&](YarnPiece& p, int j) {
    const Loop& l = loops[j];
    const double lam = leg_at_head(l.action), beta = leg_at_sinker(l.action);
    const double uL = leg_u(j, nt, false), uR = leg_u(j, nt, true);
    const bool starts_left = (l.twist != 0) != l.crossed;
    p.points.push_back(top(j, starts_left ? 0 : 1));
    if (l.twist != 0) p.points.push_back(at((j + 0.5) / nt, kUpper, lam - l.twist));
    else p.points.push_back(at((j + (starts_left ? 0.31 : 0.69)) / nt, kUpper, 0.5 * lam));
    if (l.crossed) {
      p.points.push_back(at(uL, kHead, lam));
      p.points.push_back(at(0.5 * (uL + uR), 0.45, beta - 1));
      p.points.push_back(at(uR, kSinker, beta));
    } else {
      p.points.push_back(at(uR, kHead, lam));
      p.points.push_back(at(uR, kSinker, beta));
    }
  };
  YarnPiece first;
  first.points = {left(), at(kSide, kSinker, leg_at_sinker(loops[0].action))};
  rise(first, 0);
  pieces.push_back(first);
  for (int j = 1; j < nt; ++j) {
    YarnPiece between;
    fall(between, j - 1);
    rise(between, j);
    pieces.push_back(between);
  }
  YarnPiece last;
  fall(last, nt - 1);
  last.points.push_back(at(1 - kSide, kSinker, leg_at_sinker(loops[nt - 1].action)));
  last.points.push_back(right());
  pieces.push_back(last);
  return pieces;
}

/// Heads of the loops from below, stacked in `order` (order[0] nearest the new legs). Each head enters at
/// its bottom edge, runs up the left side in front of the sinker, across the top behind the knit legs (in
/// front of purl legs), down the right side and back to its bottom edge. Layers stay 2 radii apart.
std::vector<YarnPiece> heads(int nb, const std::vector<int>& order, const std::vector<Loop>& loops) {
  const int nt = static_cast<int>(loops.size());
  std::vector<YarnPiece> pieces;
  const double side_left = -leg_at_sinker(loops.front().action), side_right = -leg_at_sinker(loops.back().action);
  for (int q = 0; q < nb; ++q) {
    const int i = order[q];
    const double deeper = 2.0 * (nb - 1 - q);  // layers beyond the first, away from the legs
    const double sl = side_left + (side_left > 0 ? deeper : -deeper), sr = side_right + (side_right > 0 ? deeper : -deeper);
    // From each foot the head rises to its layer at once, then runs sideways at a height of its own, so that
    // where the heads of a decrease cross each other they are already 2 radii apart.
    const double foot_a = (i + 0.3) / nb, foot_b = (i + 0.7) / nb, run = 0.08 + 0.05 * q;
    YarnPiece p;
    p.points.push_back(bottom(i, 0));
    p.points.push_back(at(foot_a, 0.04, sl));
    p.points.push_back(at(foot_a, run, sl));
    p.points.push_back(at(kSide, run, sl));
    p.points.push_back(at(kSide, kSinker, sl));
    // Where a head turns from its side to its top, its depth is the mean of the two, so layers stay 2 apart.
    // Over knit and purl legs layer 0 lies nearest the legs; in front of a yarn-over's legs the layers keep
    // the order they have at the sides (layer 0 in front), so that heads passing from a yarn-over to a knit
    // loop (lace) never cross each other.
    const auto top_depth = [&](int j) {
      return loops[j].action == Action::YarnOver ? 1 + 2.0 * (nb - 1 - q) : -leg_at_head(loops[j].action) * (1 + 2.0 * q);
    };
    p.points.push_back(at(kSide + 0.03, 0.5, 0.5 * (sl + top_depth(0))));
    for (int j = 0; j < nt; ++j) {
      p.points.push_back(at(leg_u(j, nt, false), kHead, top_depth(j)));
      p.points.push_back(at(leg_u(j, nt, true), kHead, top_depth(j)));
    }
    p.points.push_back(at(1 - kSide - 0.03, 0.5, 0.5 * (sr + top_depth(nt - 1))));
    p.points.push_back(at(1 - kSide, kSinker, sr));
    p.points.push_back(at(1 - kSide, run, sr));
    p.points.push_back(at(foot_b, run, sr));
    p.points.push_back(at(foot_b, 0.04, sr));
    p.points.push_back(bottom(i, 1));
    pieces.push_back(p);
  }
  return pieces;
}

StitchModel stitch(const std::string& name, const std::string& note, int nb, const std::vector<Loop>& loops, std::vector<int> order = {}) {
  StitchModel m;
  m.name = name;
  m.note = note;
  m.bottom = nb;
  m.top = static_cast<int>(loops.size());
  if (order.empty())
    for (int i = 0; i < nb; ++i) order.push_back(i);
  m.pieces = row_yarn(loops);
  const auto h = heads(nb, order, loops);
  m.pieces.insert(m.pieces.end(), h.begin(), h.end());
  return m;
}

Action action_of(char c) { return c == 'k' ? Action::Knit : c == 'p' ? Action::Purl : Action::YarnOver; }

StitchModel slip(const std::string& name, const std::string& note, double float_side) {
  StitchModel m;
  m.name = name;
  m.note = note;
  YarnPiece a, b, row;
  a.points = {bottom(0, 0), at(0.3, 0.5, 0), top(0, 0)};
  b.points = {bottom(0, 1), at(0.7, 0.5, 0), top(0, 1)};
  row.points = {left(), at(0.15, kWaleCrossing, 2 * float_side), at(0.85, kWaleCrossing, 2 * float_side), right()};
  m.pieces = {row, a, b};
  return m;
}

/// A cable face (Yuksel §4.5): `a` loops move right over (order +1) or under (-1) the next `b` loops.
StitchModel cable(int a, int b) {
  StitchModel m;
  m.name = "cable" + std::to_string(a) + "x" + std::to_string(b);
  m.note = "cable face: the first " + std::to_string(a) + " loops cross to the right in front of the next " + std::to_string(b) +
           " (Yuksel 2012 §4.5); emitted behind them when the cable's order is -1";
  const int n = a + b;
  m.bottom = m.top = n;
  m.wale_edges = false;
  for (int i = 0; i < n; ++i) {
    const int to = i < a ? i + b : i - a;
    const double h = i < a ? 2.0 : -2.0;
    for (int slot = 0; slot < 2; ++slot) {
      YarnPiece p;
      const double u0 = (i + kCourseSlots[slot]) / n, u1 = (to + kCourseSlots[slot]) / n;
      // Each strand leaves its crossing and reaches the next straight along the wale, on the surface, where
      // the stitches' heads beside the crossing stay clear of it.
      p.points = {bottom(i, slot), at(u0, 0.15, 0), at(u0 + 0.25 * (u1 - u0), 0.3, 0.6 * h), at(0.5 * (u0 + u1), 0.5, h),
                  at(u0 + 0.75 * (u1 - u0), 0.7, 0.6 * h), at(u1, 0.85, 0), top(to, slot)};
      m.pieces.push_back(p);
    }
  }
  return m;
}

StitchModel bind_off() {
  StitchModel m;
  m.name = "bind-off";
  m.note = "bind-off: closes each loop of the last row over its top edge (Yuksel 2012 §4.3, Fig. 6); drawn in a\n"
           "half-stitch band above the border edge";
  m.bottom = 1;
  m.top = 0;
  m.wale_edges = false;
  YarnPiece p;
  p.points = {bottom(0, 0), at(0.26, 0.45, 0.3), at(0.5, 0.75, 0), at(0.74, 0.45, -0.3), bottom(0, 1)};
  m.pieces = {p};
  return m;
}

/// `model` mirrored through the fabric's plane (h to -h) under a new name: a knit becomes a purl, a yarn-over
/// stays one, the stacking and the crossings stay where they are.
StitchModel mirrored(StitchModel model, const std::string& name, const std::string& note) {
  model.name = name;
  model.note = note;
  for (auto& piece : model.pieces)
    for (auto& point : piece.points)
      if (!point.crossing) point.uvh.z() = -point.uvh.z();
  return model;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 2 || (argc == 2 && argv[1][0] == '-')) {
    std::fprintf(stderr, "usage: skein-stitches [FOLDER]   (writes the stitch library, stitches/*.stitch, into FOLDER; default ./stitches)\n");
    return argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") ? 0 : 2;
  }
  const std::filesystem::path out = argc > 1 ? argv[1] : "stitches";
  std::vector<StitchModel> models;
  const std::string table1 = "(Yuksel 2012 §4.2, Table 1)";
  models.push_back(stitch("k", "knit: the new loop is pulled through the loop below from back to front " + table1, 1, {{Action::Knit}}));
  models.push_back(stitch("p", "purl: the new loop is pulled through the loop below from front to back " + table1, 1, {{Action::Purl}}));
  models.push_back(stitch("y", "yarn-over: a new loop that does not pass through the loop below " + table1, 1, {{Action::YarnOver}}));
  for (const char c : {'k', 'p', 'y'})
    for (const int t : {1, -1}) {
      const std::string name = std::string(1, c) + (t > 0 ? "+1" : "-1");
      models.push_back(stitch(name,
                              std::string(c == 'k' ? "knit" : c == 'p' ? "purl" : "yarn-over") + " with its top connection twisted " +
                                  (t > 0 ? "clockwise (left leg in front)" : "counter-clockwise (left leg behind)") +
                                  " (Yuksel 2012 §4.2); y±1 also serves as the cast-on stitch (§4.3)",
                              1, {{action_of(c), t, false}}));
    }
  models.push_back(stitch("x", "crossed knit: the legs cross below the loop they pass through (knit through the back loop)", 1,
                          {{Action::Knit, 0, true}}));
  models.push_back(slip("s", "slip: the loop below passes to the next row unworked, the yarn floats behind it", -1));
  models.push_back(slip("sk", "slip with the yarn in front: the loop below passes unworked, the yarn floats in front", 1));
  models.push_back(stitch("q", "crossed purl: a purl whose legs cross below the loop they pass through (purl through the back loop), "
                          "crossed as x is", 1, {{Action::Purl, 0, true}}));
  for (const char* inc : {"kp", "pk", "ky", "yk", "py", "yp", "kpk", "kyk", "yky", "kpy", "ykp", "pkp", "pyp", "ypy", "pky", "ypk"}) {
    std::vector<Loop> loops;
    for (const char* c = inc; *c; ++c) loops.push_back({action_of(*c)});
    models.push_back(stitch(inc, std::string("increase: ") + inc + " worked into one loop below, left to right " + table1, 1, loops));
  }
  // kfb and pfb: into the loop's front leg, then into its back leg, the second loop crossed (x or q). Seen from the
  // front, worked right to left on a right-side row and left to right on a wrong-side one: kfb is xk (RS) or pq (WS),
  // pfb qp (RS) or kx (WS).
  const std::vector<std::pair<const char*, const char*>> front_and_back = {
      {"xk", "kfb on a right-side row"}, {"kx", "pfb on a wrong-side row"}, {"qp", "pfb on a right-side row"}, {"pq", "kfb on a wrong-side row"}};
  for (const auto& [inc, written] : front_and_back) {
    std::vector<Loop> loops;
    for (const char* c = inc; *c; ++c) loops.push_back({action_of(*c == 'x' ? 'k' : *c == 'q' ? 'p' : *c), 0, *c == 'x' || *c == 'q'});
    models.push_back(stitch(inc, std::string("increase: ") + inc + " worked into one loop below, left to right, x and q crossed (" + written + ") " + table1, 1, loops));
  }
  for (const std::string order : {"12", "21", "123", "132", "213", "231", "312", "321"})
    for (const char c : {'k', 'p'}) {
      std::vector<int> stack;
      for (const char d : order) stack.push_back(d - '1');
      const std::string name = "d" + order + c;
      models.push_back(stitch(name,
                              "decrease: one " + std::string(c == 'k' ? "knit" : "purl") + " loop through " + std::to_string(order.size()) +
                                  " loops below, stacked " + order + " (loop " + order.substr(0, 1) + " nearest the new loop) " + table1,
                              static_cast<int>(order.size()), {{action_of(c)}}, stack));
    }
  // Leaf 2018 Table 2's lace tiles: a yarn-over beside a decrease, as many loops made as taken.
  const std::string leaf = " (Leaf 2018 Table 2)";
  models.push_back(stitch("ys", "lace: a yarn-over, then a knit loop through both loops below, stacked 21 (ssk)" + leaf, 2,
                          {{Action::YarnOver}, {Action::Knit}}, {1, 0}));
  models.push_back(stitch("2u", "lace: a knit loop through both loops below, stacked 12 (k2tog), then a yarn-over" + leaf, 2,
                          {{Action::Knit}, {Action::YarnOver}}, {0, 1}));
  // The same with a purl through the two loops (garter lace: "yo, k2tog" from the wrong side): the knit tiles
  // mirrored through the fabric's plane, which turns each knit into a purl and keeps the stacking, so that the heads
  // keep their layers past the yarn-over.
  const StitchModel ys = models[models.size() - 2], two_u = models.back();
  models.push_back(mirrored(ys, "ysp", "lace: a yarn-over, then a purl loop through both loops below, stacked 21 (ys mirrored through the "
                                       "fabric: yo, ssk worked from the wrong side)"));
  models.push_back(mirrored(two_u, "2up", "lace: a purl loop through both loops below, stacked 12, then a yarn-over (2u mirrored through the "
                                          "fabric: k2tog, yo worked from the wrong side)"));
  models.push_back(stitch("y3y", "lace: a yarn-over, a knit loop through the three loops below, stacked 213 (sk2p), a yarn-over" + leaf, 3,
                          {{Action::YarnOver}, {Action::Knit}, {Action::YarnOver}}, {1, 0, 2}));
  for (int a = 1; a <= 3; ++a)
    for (int b = 1; b <= 3; ++b) models.push_back(cable(a, b));
  models.push_back(bind_off());

  try {
    for (const auto& m : models) {
      const std::string text = format_stitch_model(m);
      parse_stitch_model(text, m.name + ".stitch");  // every model written must read back valid
      const auto path = out / (m.name + ".stitch");
      std::ofstream(path, std::ios::binary) << text;
    }
  } catch (const skein::Error& e) {
    std::fprintf(stderr, "skein-stitches: %s\n", e.what());
    return 1;
  }
  std::printf("wrote %zu stitch models to %s\n", models.size(), out.c_str());
}
