// libFuzzer harness: knitting and weaving patterns as text (patterns/FORMAT.md).
#include "fuzz_support.hpp"
#include "stitchmesh/pattern.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  skein::fuzz::expect_clean([&] {
    const auto pattern = skein::mesh::parse_pattern(skein::fuzz::text(data, size), "fuzz.knit");
    // A pattern that reads must also make its stitch mesh or woven yarn, or say why.
    if (pattern.format == skein::mesh::PatternFormat::Woven) skein::mesh::woven_yarn(pattern, 1, 1, 6.0, 0.6);
    else skein::mesh::pattern_stitch_mesh(pattern, 1, 1);
  });
  return 0;
}
