#include <cstdio>

#include "cuda/device.hpp"

namespace skein::cuda {
std::string describe(const DeviceQuery& query) {
  if (!query.available()) return "CUDA: no GPU answered (" + query.reason + "); using the CPU";
  std::string s = "CUDA:";
  for (const auto& d : query.devices) {
    char buf[256];
    std::snprintf(buf, sizeof buf, " [%d] %s (sm_%d%d, %.1f GiB, %d SMs)", d.index, d.name.c_str(), d.compute_major, d.compute_minor,
                  d.memory_gib, d.multiprocessors);
    s += buf;
  }
  return s;
}
}  // namespace skein::cuda
