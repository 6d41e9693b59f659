#pragma once
#include <string>
#include <vector>

namespace skein::cuda {

/// A CUDA device that answered.
struct DeviceInfo {
  int index = 0;
  std::string name;
  int compute_major = 0, compute_minor = 0;
  double memory_gib = 0;
  int multiprocessors = 0;
};

/// What the CUDA runtime says: the devices that answer, or why none does ("no CUDA device", "driver
/// missing", "built without CUDA"). Never throws: no GPU is a normal answer and the CPU path is used.
struct DeviceQuery {
  std::vector<DeviceInfo> devices;
  std::string reason;  ///< empty when at least one device answered
  bool available() const { return !devices.empty(); }
};
DeviceQuery query_devices();

/// One line for the log: "CUDA: NVIDIA H100 (sm_90, 79.1 GiB)" or "CUDA: no GPU answered (...); using the CPU".
std::string describe(const DeviceQuery& query);

}  // namespace skein::cuda
