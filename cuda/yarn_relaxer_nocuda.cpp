#include "common/error.hpp"
#include "cuda/yarn_relaxer.hpp"

namespace skein::cuda {
// Built with SKEIN_CUDA=OFF or without nvcc: there is no CUDA relaxer to make.
std::unique_ptr<relax::YarnRelaxer> make_cuda_yarn_relaxer(const relax::YarnSystem&, const relax::ShapeTargets&, const relax::YarnRelaxOptions&) {
  throw Error("", "CUDA relaxer", "skein was built without CUDA (SKEIN_CUDA=OFF or no nvcc at configure time)");
}
}  // namespace skein::cuda
