// libFuzzer harness: smocking patterns (docs/smocking.md), as text or drawn as SVG (an input that starts with '<').
#include "fuzz_support.hpp"
#include "smocking/smocking_embed.hpp"
#include "smocking/smocking_svg.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  skein::fuzz::expect_clean([&] {
    const std::string text = skein::fuzz::text(data, size);
    const auto pattern = !text.empty() && text[0] == '<' ? skein::smocking::parse_smocking_svg(text, "fuzz.svg")
                                                         : skein::smocking::parse_smocking_pattern(text, "fuzz.smock");
    // A pattern that reads must also gather, or say why (a few steps on grids of up to 5,000 points: the fuzzer
    // looks for crashes, not pleats, and a 250,000-point grid is slow, not wrong).
    if (pattern.num_points() > 5000) return;
    skein::smocking::EmbedOptions options;
    options.max_iterations = 50;
    options.sweeps_per_step = 2;
    options.settle_iterations = 20;
    skein::smocking::embed(pattern, options);
  });
  return 0;
}
