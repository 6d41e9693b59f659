#include "workflow/garment_fabric.hpp"

#include <algorithm>

#include <spdlog/fmt/fmt.h>

#include "common/error.hpp"

namespace skein::workflow {

GarmentFabric garment_fabric(const std::string& weight, const mesh::StitchSize& size) {
  const auto& w = mesh::find_yarn_weight(weight);
  const double radius = w.diameter() / 2;
  return {w.name, radius, mesh::kYarnCompression * radius, mesh::gauge_of(size).loop_length()};
}

double garment_loop_length(const relax::YarnSystem& system, int stitches) {
  double yarn = 0;
  for (double l : system.rest_length) yarn += l;
  return yarn / std::max(stitches, 1);
}

double take_up_to_munden(double loop, double munden, const std::string& file, const std::string& option, const std::string& remedy) {
  const double take_up = munden / loop;
  if (!(take_up > 0.1 && take_up < 2))
    throw Error(file, option,
                fmt::format("the take-up to Munden's loop length ({:.3g} mm a stitch against the {:.3g} mm emitted) would be {:.3g}; {}", munden,
                            loop, take_up, remedy));
  return take_up;
}

}  // namespace skein::workflow
