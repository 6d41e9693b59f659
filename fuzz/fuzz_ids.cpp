// libFuzzer harness: stitch ids side files (read_point_ids) for a yarn of two curves of 5 and 4 points, as
// fuzz/seeds/ids/ holds one.
#include "fuzz_support.hpp"
#include "workflow/yarn_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const skein::relax::YarnCurves yarn = [] {
    skein::relax::YarnCurves y;
    for (int p = 0; p < 9; ++p) y.points.emplace_back(p, 0, 0);
    y.curve_start = {0, 5, 9};
    y.closed = {0, 0};
    y.radius = 0.5;
    return y;
  }();
  const auto path = skein::fuzz::as_file(data, size, ".csv");
  skein::fuzz::expect_clean([&] { skein::workflow::read_point_ids(path, yarn); });
  std::filesystem::remove(path);
  return 0;
}
