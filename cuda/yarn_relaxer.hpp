#pragma once
#include <memory>

#include "relax/yarn_relax.hpp"

namespace skein::cuda {

/// The CUDA yarn relaxer (Leaf 2018 §3.2): the CPU reference's model, integrators and pull-through guard in
/// float on the GPU, the step loop captured as a CUDA graph and the host reading back every few steps.
/// Throws skein::Error naming the reason when skein was built without CUDA or no GPU answers.
std::unique_ptr<relax::YarnRelaxer> make_cuda_yarn_relaxer(const relax::YarnSystem& system, const relax::ShapeTargets& targets,
                                                           const relax::YarnRelaxOptions& options);

/// The relaxer for `backend`: Cpu, Cuda (an error without a GPU) or Auto (CUDA when a GPU answers, else
/// the CPU). Logs the choice.
std::unique_ptr<relax::YarnRelaxer> make_yarn_relaxer(relax::Backend backend, const relax::YarnSystem& system, const relax::ShapeTargets& targets,
                                                      const relax::YarnRelaxOptions& options);

}  // namespace skein::cuda
