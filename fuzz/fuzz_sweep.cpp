// libFuzzer harness: sweep files for `skein sweep` and `skein-mpi sweep` (docs/sweeps.md), read as if in jobs/
// (so that the bundled patterns its seeds name are found).
#include "fuzz_support.hpp"
#include "skein/config.hpp"
#include "sweep.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  skein::fuzz::expect_clean([&] { skein::cli::parse_sweep(skein::fuzz::text(data, size), std::filesystem::path(SKEIN_SOURCE_DIR) / "jobs" / "fuzz.json"); });
  return 0;
}
