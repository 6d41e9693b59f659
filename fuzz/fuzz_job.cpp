// libFuzzer harness: job files for `skein run` (docs/jobs.md).
#include "fuzz_support.hpp"
#include "job.hpp"
#include "skein/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  skein::fuzz::expect_clean([&] { skein::cli::parse_job(skein::fuzz::text(data, size), std::filesystem::path(SKEIN_SOURCE_DIR) / "jobs" / "fuzz.json"); });
  return 0;
}
