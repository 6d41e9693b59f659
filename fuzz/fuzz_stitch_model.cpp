// libFuzzer harness: stitch models (stitches/FORMAT.md).
#include <optional>

#include "fuzz_support.hpp"
#include "stitchmesh/stitch_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::optional<skein::mesh::StitchModel> model;
  skein::fuzz::expect_clean([&] { model = skein::mesh::parse_stitch_model(skein::fuzz::text(data, size), "fuzz.stitch"); });
  // A model that reads writes back to text that reads again (an error here escapes: a bug).
  if (model) skein::mesh::parse_stitch_model(skein::mesh::format_stitch_model(*model), "again.stitch");
  return 0;
}
