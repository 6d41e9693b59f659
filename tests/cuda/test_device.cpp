#include <gtest/gtest.h>

#include "cuda/device.hpp"

using namespace skein;

TEST(CudaDevice, QueryAnswersWithDevicesOrAReason) {
  const auto q = cuda::query_devices();
  const std::string line = cuda::describe(q);
  if (!q.available()) {
    EXPECT_FALSE(q.reason.empty());
    EXPECT_NE(line.find("no GPU answered"), std::string::npos) << line;
    GTEST_SKIP() << "no CUDA device: " << q.reason;
  }
  for (const auto& d : q.devices) {
    EXPECT_FALSE(d.name.empty());
    EXPECT_GE(d.compute_major, 7);
    EXPECT_GT(d.memory_gib, 1.0);
  }
  EXPECT_NE(line.find(q.devices[0].name), std::string::npos) << line;
}
