#include "cuda/device.hpp"

namespace skein::cuda {
// Built with SKEIN_CUDA=OFF or without nvcc: there is never a device.
DeviceQuery query_devices() { return {{}, "skein was built without CUDA (SKEIN_CUDA=OFF or no nvcc at configure time)"}; }
}  // namespace skein::cuda
