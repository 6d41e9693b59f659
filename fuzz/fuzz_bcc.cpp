// libFuzzer harness: .bcc yarn files.
#include "fuzz_support.hpp"
#include "workflow/yarn_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = skein::fuzz::as_file(data, size, ".bcc");
  skein::fuzz::expect_clean([&] { skein::workflow::read_bcc(path); });
  std::filesystem::remove(path);
  return 0;
}
