// libFuzzer harness: smocking patterns (docs/smocking.md).
#include "fuzz_support.hpp"
#include "smocking/smocking_embed.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  skein::fuzz::expect_clean([&] {
    const auto pattern = skein::smocking::parse_smocking_pattern(skein::fuzz::text(data, size), "fuzz.smock");
    // A pattern that reads must also gather, or say why (a few steps: the fuzzer looks for crashes, not pleats).
    skein::smocking::EmbedOptions options;
    options.max_iterations = 50;
    options.settle_iterations = 20;
    skein::smocking::embed(pattern, options);
  });
  return 0;
}
