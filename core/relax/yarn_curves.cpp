#include "relax/yarn_curves.hpp"

#include <algorithm>

namespace skein::relax {

int YarnCurves::yarn_of(int point) const {
  return static_cast<int>(std::upper_bound(curve_start.begin(), curve_start.end(), point) - curve_start.begin()) - 1;
}

int YarnCurves::segment_owner(int p) const {
  const int c = yarn_of(p);
  return p + 1 < curve_start[c + 1] ? p + 1 : p;
}

}  // namespace skein::relax
