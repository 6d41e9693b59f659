// libFuzzer harness: yarn relaxation checkpoints. The fingerprint and size are taken from the input's own
// header so that the fuzzer can reach past them; the checksum still guards the rest.
#include <cstring>

#include "fuzz_support.hpp"
#include "relax/yarn_checkpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::uint64_t fingerprint = 0;
  std::int64_t points = 0;
  if (size >= 28) {
    std::memcpy(&fingerprint, data + 12, 8);
    std::memcpy(&points, data + 20, 8);
  }
  if (points < 0 || points > (1 << 20)) points = 0;
  const auto path = skein::fuzz::as_file(data, size, ".ckp");
  skein::fuzz::expect_clean([&] { skein::relax::read_checkpoint(path, fingerprint, static_cast<int>(points)); });
  std::filesystem::remove(path);
  return 0;
}
