#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace skein::mesh {

/// A stitch type's name and the face shape it fits: how many bottom and top course edges
/// (Yuksel 2012 Table 1, the twisted top connections k±1 p±1 y±1 and x, s, sk).
struct StitchType {
  std::string name;
  int bottom = 1;
  int top = 1;
};

/// Every stitch type a face may carry, in Table 1 order.
const std::vector<StitchType>& stitch_types();
/// The type named `name`, or nullptr.
const StitchType* find_stitch_type(std::string_view name);
/// The type a fresh face of this shape gets: k, kp, kpk, d12k, d123k, ys, y3y; "" when no type fits.
std::string default_stitch_type(int bottom, int top);

}  // namespace skein::mesh
