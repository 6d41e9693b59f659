#include "stitchmesh/stitch_types.hpp"

#include <algorithm>

namespace skein::mesh {

const std::vector<StitchType>& stitch_types() {
  static const std::vector<StitchType> types = [] {
    std::vector<StitchType> t;
    const auto add = [&](std::initializer_list<const char*> names, int bottom, int top) {
      for (const char* n : names) t.push_back({n, bottom, top});
    };
    add({"k", "p", "y", "k+1", "k-1", "p+1", "p-1", "y+1", "y-1", "x", "q", "s", "sk"}, 1, 1);
    add({"kp", "pk", "ky", "yk", "py", "yp", "xk", "kx", "qp", "pq"}, 1, 2);
    add({"kpk", "kyk", "yky", "kpy", "ykp", "pkp", "pyp", "ypy", "pky", "ypk"}, 1, 3);
    add({"d12k", "d21k", "d12p", "d21p"}, 2, 1);
    add({"d123k", "d132k", "d213k", "d231k", "d312k", "d321k", "d123p", "d132p", "d213p", "d231p", "d312p", "d321p"}, 3, 1);
    add({"ys", "2u", "ysp", "2up"}, 2, 2);  // Leaf 2018 Table 2's lace tiles: a yarn-over beside a decrease (and their purls)
    add({"y3y"}, 3, 3);
    return t;
  }();
  return types;
}

const StitchType* find_stitch_type(std::string_view name) {
  const auto& t = stitch_types();
  const auto it = std::find_if(t.begin(), t.end(), [&](const StitchType& s) { return s.name == name; });
  return it == t.end() ? nullptr : &*it;
}

std::string default_stitch_type(int bottom, int top) {
  if (bottom == 1 && top == 1) return "k";
  if (bottom == 1 && top == 2) return "kp";
  if (bottom == 1 && top == 3) return "kpk";
  if (bottom == 2 && top == 1) return "d12k";
  if (bottom == 3 && top == 1) return "d123k";
  if (bottom == 2 && top == 2) return "ys";
  if (bottom == 3 && top == 3) return "y3y";
  return "";
}

}  // namespace skein::mesh
