#include "cuda/check.cuh"
#include "cuda/device.hpp"

namespace skein::cuda {

namespace {
/// Writes one index per thread: proves that a kernel ran on the device and came back.
__global__ void iota_kernel(int* out, int n) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) out[i] = i;
}

/// Launches a tiny kernel and reads it back; a device that lists itself but cannot run code is no device.
bool runs_a_kernel(int device, std::string& why) {
  try {
    SKEIN_CUDA_CHECK(cudaSetDevice(device));
    constexpr int n = 256;
    int* d = nullptr;
    SKEIN_CUDA_CHECK(cudaMalloc(&d, n * sizeof(int)));
    iota_kernel<<<1, n>>>(d, n);
    SKEIN_CUDA_CHECK(cudaGetLastError());
    int h[n];
    const cudaError_t copied = cudaMemcpy(h, d, sizeof h, cudaMemcpyDeviceToHost);
    cudaFree(d);
    SKEIN_CUDA_CHECK(copied);
    for (int i = 0; i < n; ++i)
      if (h[i] != i) {
        why = "a test kernel returned wrong values";
        return false;
      }
    return true;
  } catch (const skein::Error& e) {
    why = e.what();
    return false;
  }
}
}  // namespace

DeviceQuery query_devices() {
  DeviceQuery q;
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  // Without a driver this is cudaErrorInsufficientDriver (35), not cudaErrorNoDevice: any error means no GPU.
  if (status != cudaSuccess) {
    q.reason = std::string(cudaGetErrorName(status)) + ": " + cudaGetErrorString(status);
    return q;
  }
  if (count == 0) {
    q.reason = "the CUDA runtime lists no device";
    return q;
  }
  for (int i = 0; i < count; ++i) {
    cudaDeviceProp prop{};
    if (cudaGetDeviceProperties(&prop, i) != cudaSuccess) continue;
    std::string why;
    if (!runs_a_kernel(i, why)) {
      q.reason = "device " + std::to_string(i) + " (" + prop.name + ") cannot run kernels: " + why;
      continue;
    }
    q.devices.push_back({i, prop.name, prop.major, prop.minor, prop.totalGlobalMem / double(1ull << 30), prop.multiProcessorCount});
  }
  if (!q.devices.empty()) q.reason.clear();
  return q;
}

}  // namespace skein::cuda
