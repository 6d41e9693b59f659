#include <spdlog/spdlog.h>

#include "common/error.hpp"
#include "cuda/device.hpp"
#include "cuda/yarn_relaxer.hpp"

namespace skein::cuda {

std::unique_ptr<relax::YarnRelaxer> make_yarn_relaxer(relax::Backend backend, const relax::YarnSystem& system, const relax::ShapeTargets& targets,
                                                      const relax::YarnRelaxOptions& options) {
  if (options.active_set.enabled) {
    if (backend == relax::Backend::Cuda) throw Error("", "--active-set", "the active set runs on the CPU only; use --backend cpu or auto");
    spdlog::info("active set: relaxing on the CPU (the CUDA relaxer integrates every point)");
    return relax::make_cpu_yarn_relaxer(system, targets, options);
  }
  if (options.clipped_scale) {
    if (backend == relax::Backend::Cuda) throw Error("", "--stop-scale clipped", "runs on the CPU only; use --backend cpu or auto");
    spdlog::info("clipped stop scale: relaxing on the CPU (the CUDA relaxer takes |∇E_0| whole)");
    return relax::make_cpu_yarn_relaxer(system, targets, options);
  }
  if (options.method == relax::YarnMethod::Lbfgs) {
    if (backend == relax::Backend::Cuda) throw Error("", "--method lbfgs", "runs on the CPU only; use --backend cpu or auto");
    spdlog::info("L-BFGS: relaxing on the CPU (the CUDA relaxer integrates with Euler or FIRE)");
    return relax::make_cpu_yarn_relaxer(system, targets, options);
  }
  if (options.stop_rule == relax::StopRule::Force) {
    if (backend == relax::Backend::Cuda) throw Error("", "--stop-rule force", "runs on the CPU only; use --backend cpu or auto");
    spdlog::info("force stop rule: relaxing on the CPU (the CUDA relaxer stops by Leaf's rule)");
    return relax::make_cpu_yarn_relaxer(system, targets, options);
  }
  if (backend == relax::Backend::Auto && !targets.periodic.empty()) {
    spdlog::info("periodic patch: relaxing on the CPU (the CUDA relaxer has no periodic boundary conditions yet)");
    return relax::make_cpu_yarn_relaxer(system, targets, options);
  }
  if (backend == relax::Backend::Cpu) {
    spdlog::info("backend cpu: relaxing on the CPU");
    return relax::make_cpu_yarn_relaxer(system, targets, options);
  }
  const auto query = query_devices();
  if (!query.available() && backend == relax::Backend::Cuda)
    throw Error("", "--backend cuda", "no CUDA GPU answered (" + query.reason + "); use --backend cpu or auto");
  spdlog::info("{}", describe(query));
  if (query.available()) return make_cuda_yarn_relaxer(system, targets, options);
  return relax::make_cpu_yarn_relaxer(system, targets, options);
}

}  // namespace skein::cuda
