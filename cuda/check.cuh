#pragma once
// Error checking for every CUDA runtime call and kernel launch. Device code never includes this.
#include <cuda_runtime.h>

#include <string>

#include "common/error.hpp"

namespace skein::cuda::detail {
inline void check(cudaError_t status, const char* call, const char* file, int line) {
  if (status != cudaSuccess)
    throw skein::Error(std::string(file) + ":" + std::to_string(line), call,
                       std::string(cudaGetErrorName(status)) + ": " + cudaGetErrorString(status));
}
}  // namespace skein::cuda::detail

#define SKEIN_CUDA_CHECK(call) ::skein::cuda::detail::check((call), #call, __FILE__, __LINE__)
#ifdef NDEBUG
#define SKEIN_CUDA_CHECK_LAUNCH() SKEIN_CUDA_CHECK(cudaGetLastError())
#else  // debug builds wait for each kernel so that a fault names its launch
#define SKEIN_CUDA_CHECK_LAUNCH() (SKEIN_CUDA_CHECK(cudaGetLastError()), SKEIN_CUDA_CHECK(cudaDeviceSynchronize()))
#endif
