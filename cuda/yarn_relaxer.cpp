// The CUDA relaxer's host loop: the CPU reference's run loop (yarn_relax.cpp) with the steps on the GPU.
// The device runs batches of steps and stops by itself where the host must act; the host reads back once a
// batch, rebuilds contacts, rolls back, checkpoints, audits and reports.
#include "cuda/yarn_relaxer.hpp"


#include <spdlog/spdlog.h>

#include "common/error.hpp"
#include "cuda/device.hpp"
#include "cuda/yarn_device.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_checkpoint.hpp"

namespace skein::cuda {
namespace {

constexpr int kBatch = 32;  ///< steps per read-back when nothing else sets the stop

class CudaYarnRelaxer final : public relax::YarnRelaxer {
public:
  CudaYarnRelaxer(const relax::YarnSystem& system, const relax::ShapeTargets& targets, const relax::YarnRelaxOptions& options, std::string device)
      : m_system(system), m_options(options), m_device(system, targets, options), m_auditor(system), m_name(std::move(device)) {}

  relax::YarnRelaxReport run(relax::YarnState& state, const std::function<void(const relax::YarnStepLog&)>& on_step) override {
    relax::RunControl control(m_options);  // the stop order, rollbacks and checkpoints of the CPU relaxer
    const auto fingerprint = relax::checkpoint_fingerprint(m_system, m_options.method);
    m_device.set_state(state);
    long contacts = rebuild(state);

    relax::YarnRelaxReport report;
    report.backend = "cuda: " + m_name;
    std::vector<relax::YarnStepLog> logs;
    Eigen::Matrix3Xd before, after;
    DeviceStatus status;
    long step = state.step;
    relax::JamWatch jam(m_options.jam_steps, m_options.jam_drop);
    for (;;) {
      // Where this batch must stop: the step cap, the next checkpoint step, the time cap (at once); with the
      // audit, after every step (the auditor compares consecutive states on the CPU).
      long stop_at = m_options.max_steps;
      if (m_options.checkpoint_every > 0) stop_at = std::min(stop_at, (step / m_options.checkpoint_every + 1) * m_options.checkpoint_every);
      const bool out_of_time = control.out_of_time(), interrupted = control.interrupted();
      if (out_of_time || interrupted) stop_at = step;  // evaluate the current state once more, for the report
      if (m_options.audit) m_device.get_points(before);
      status = m_device.run(stop_at, m_options.audit ? 1 : kBatch, logs);
      if (m_options.audit && !logs.empty()) {
        m_device.get_points(after);
        logs.back().crossings = static_cast<long>(m_auditor.crossings(before, after).size());
        state.pull_through_events += logs.back().crossings;
      }
      bool jammed = false;
      for (const auto& log : logs) {
        if (on_step) on_step(log);
        jammed = jammed || jam.jammed(log.energy, log.held_points);
      }
      step = status.step;
      if (!logs.empty()) control.step_taken();
      if (status.halt == Halt::NotFinite) {
        // Blow-up: back to the last good state with half the step (Leaf §3.1's step restriction failed).
        m_device.roll_back();
        ++state.rollbacks;
        spdlog::warn("step {}: the yarn state is not finite; back to the last good state with half the step", step);
        if (!control.roll_back()) {
          report.stopped_by = relax::StopReason::Diverged;
          break;
        }
        contacts = rebuild(state);
        continue;
      }
      // The time cap and an interrupt were read before the batch, which then only evaluated the state once more.
      const bool halted = status.halt == Halt::StopAt;
      report.stopped_by = control.stop(step, status.halt == Halt::Converged, halted && out_of_time, halted && interrupted, jammed);
      if (report.stopped_by != relax::StopReason::None) {
        report.converged = report.stopped_by == relax::StopReason::Converged;
        if (report.stopped_by == relax::StopReason::Jammed) spdlog::warn("step {}: {}", step, jam.describe());
        break;
      }
      if (status.halt == Halt::Rebuild) contacts = rebuild(state);
      if (control.checkpoint_due(step)) {
        checkpoint(state, fingerprint);
        control.checkpoint_written();
        // A resumed run starts with fresh contacts and safe bounds; so does this one, so both go on alike.
        contacts = rebuild(state);
      }
    }
    if (!m_options.checkpoint.empty() && report.stopped_by != relax::StopReason::Diverged) checkpoint(state, fingerprint);
    const long pull_through = state.pull_through_events, rollbacks = state.rollbacks, rebuilds = state.contact_rebuilds;
    m_device.get_state(state);
    state.pull_through_events = pull_through;
    state.rollbacks = rollbacks;
    state.contact_rebuilds = rebuilds;
    report.steps = state.step;
    report.wall_seconds = control.seconds();
    report.residual = status.residual;
    report.energy = status.energy;
    report.contacts = contacts;
    report.guard = state.guard;
    report.pull_through_events = m_options.audit ? state.pull_through_events : -1;
    report.rollbacks = state.rollbacks;
    report.contact_rebuilds = state.contact_rebuilds;
    return report;
  }

private:
  long rebuild(relax::YarnState& state) {
    ++state.contact_rebuilds;
    return m_device.rebuild_contacts();
  }

  void checkpoint(relax::YarnState& state, std::uint64_t fingerprint) {
    relax::YarnState saved = state;  // the host's counters, with the device's state
    m_device.get_state(saved);
    relax::write_checkpoint(m_options.checkpoint, fingerprint, saved);
  }

  const relax::YarnSystem& m_system;
  relax::YarnRelaxOptions m_options;
  DeviceYarn m_device;
  relax::TopologyAuditor m_auditor;
  std::string m_name;
};

}  // namespace

std::unique_ptr<relax::YarnRelaxer> make_cuda_yarn_relaxer(const relax::YarnSystem& system, const relax::ShapeTargets& targets,
                                                           const relax::YarnRelaxOptions& options) {
  options.validate();
  if (!targets.periodic.empty()) throw Error("", "CUDA relaxer", "has no periodic boundary conditions yet: relax periodic patches with --backend cpu");
  const auto query = query_devices();
  if (!query.available()) throw Error("", "CUDA relaxer", "no CUDA GPU answered (" + query.reason + ")");
  return std::make_unique<CudaYarnRelaxer>(system, targets, options, query.devices.front().name);
}

}  // namespace skein::cuda
