#pragma once
// The GPU side of the CUDA relaxer: the yarn system, its state and the step loop in device memory. A plain
// C++ interface (no CUDA types), so that the host loop (yarn_relaxer.cpp) builds without nvcc.
#include <memory>
#include <vector>

#include "relax/yarn_relax.hpp"

namespace skein::cuda {

/// Why the device stopped stepping.
enum class Halt {
  None,       ///< still running: the batch ended first
  Converged,  ///< Leaf eq. 5 holds at the current state
  StopAt,     ///< the step the host asked to stop at (a cap, a checkpoint, an audit)
  NotFinite,  ///< the forces at the current state are not finite
  Rebuild,    ///< the yarn moved half the contact margin: the contact pairs must be rebuilt
};

/// What the host reads back after a batch of steps.
struct DeviceStatus {
  Halt halt = Halt::None;
  long step = 0;
  double energy = 0;    ///< at the current state
  double residual = 0;  ///< |grad E| / |grad E_0| at the current state
};

class DeviceYarn {
public:
  /// Uploads the system, the shape targets and the options; throws skein::Error on a CUDA failure.
  DeviceYarn(const relax::YarnSystem& system, const relax::ShapeTargets& targets, const relax::YarnRelaxOptions& options);
  ~DeviceYarn();
  DeviceYarn(const DeviceYarn&) = delete;
  DeviceYarn& operator=(const DeviceYarn&) = delete;

  /// Positions, velocities and the controller (step, time step, FIRE state, residuals, guard counters).
  void set_state(const relax::YarnState& state);
  /// The same back into `state` (its counters of rollbacks, rebuilds and audit events are the host's).
  void get_state(relax::YarnState& state) const;
  /// The control points only [mm].
  void get_points(Eigen::Matrix3Xd& points) const;

  /// Contact pairs from a sorted uniform grid over the segment spheres, and the guard's pair list with
  /// fresh safe bounds; returns the number of unordered contact pairs.
  long rebuild_contacts();
  /// The contact pairs of the last rebuild, read back (for tests against the CPU's).
  relax::ContactPairs contact_pairs() const;
  /// Steps until the step count reaches `stop_at`, or the device halts, at most `batch` steps, one CUDA
  /// graph launch per step and one read-back at the end. The steps' logs go to `logs`.
  DeviceStatus run(long stop_at, int batch, std::vector<relax::YarnStepLog>& logs);
  /// Back to the state before the last step whose forces were finite, with half the time step.
  void roll_back();

private:
  struct Impl;
  std::unique_ptr<Impl> m;
};

}  // namespace skein::cuda
