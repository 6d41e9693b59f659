#include "relax/period_search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "common/error.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_cell.hpp"

namespace skein::relax {

const WidthTrial& WidthSearch::result() const {
  if (m_within) return m_last;
  if (m_converged) return std::abs(m_low.stress) < std::abs(m_high.stress) ? m_low : m_high;
  return m_best;
}

double WidthSearch::trial_force_tolerance(double loosest) const {
  const double floor = 20 * m_tolerance;
  if (m_confirming || (m_low_set && m_high_set)) return std::min(loosest, floor);  // near the root: every sign counts
  if (m_best.width == 0) return loosest;
  return std::min(loosest, std::max(10 * std::abs(m_best.stress), floor));
}

double WidthSearch::next(const WidthTrial& trial) {
  if (!std::isfinite(trial.stress)) return 0;  // over, not converged: no trial to go on from
  ++m_trials;
  const bool within = std::abs(trial.stress) <= m_tolerance;
  m_confirming = within && trial.force_tolerance > 20 * m_tolerance * (1 + 1e-9);
  if (m_confirming) return trial.width;  // relaxed too loosely to tell the stress from noise: relax it again, tighter
  if (m_best.width == 0 || std::abs(trial.stress) < std::abs(m_best.stress)) m_best = trial;
  if (within) {
    m_converged = m_within = true;
    m_last = trial;
    return 0;
  }
  // The bracket's ends: the repeat pulled out (it would widen) at the narrow end, pushed in at the wide end.
  if (trial.stress < 0) {
    m_low = trial, m_low_set = true, m_kept_high = m_high_set ? m_kept_high + 1 : 0, m_kept_low = 0;
  } else {
    m_high = trial, m_high_set = true, m_kept_low = m_low_set ? m_kept_low + 1 : 0, m_kept_high = 0;
  }
  const bool bracketed = m_low_set && m_high_set && m_low.width < m_high.width;
  double next = 0;
  if (bracketed) {
    if (m_high.width - m_low.width <= m_bracket * trial.width) {
      m_converged = true;
      return 0;
    }
    // Regula falsi; an end kept twice in a row counts half (Illinois), so a curved stress does not stall it.
    const double s_low = m_low.stress * (m_kept_low >= 2 ? 0.5 : 1), s_high = m_high.stress * (m_kept_high >= 2 ? 0.5 : 1);
    next = m_low.width + (m_high.width - m_low.width) * (-s_low) / (s_high - s_low);
    // Not at an end: at least a tenth of the bracket in from each.
    const double margin = 0.1 * (m_high.width - m_low.width);
    next = std::clamp(next, m_low.width + margin, m_high.width - margin);
  } else {
    // Against the stress: the secant's step when the last trial is on the same side, within half to twice the last.
    const double direction = trial.stress > 0 ? -1 : 1;
    double step = m_step == 0 ? 0.04 * m_start : 2 * m_step;
    if (m_step > 0 && (m_last.stress > 0) == (trial.stress > 0) && m_last.stress != trial.stress) {
      const double secant = -trial.stress * (trial.width - m_last.width) / (trial.stress - m_last.stress);
      if (secant * direction > 0) step = std::clamp(std::abs(secant), 0.5 * m_step, 2 * m_step);
    }
    step = std::min(step, 0.15 * trial.width);
    m_step = step;
    next = trial.width + direction * step;
    if (next < 0.25 * m_start || next > 4 * m_start) return 0;  // no stress-free width in reach
  }
  m_last = trial;
  return next;
}

namespace {

class PeriodSearchRelaxer final : public YarnRelaxer {
public:
  PeriodSearchRelaxer(const YarnSystem& system, const ShapeTargets& targets, const YarnRelaxOptions& options)
      : m_system(system), m_targets(targets), m_options(options) {
    options.validate();  // one free length, no shear, the force stop rule (PeriodOptions, YarnRelaxOptions)
    if (!options.period.free || options.period.method != PeriodOptions::Method::Bracket)
      throw Error("", "--period-method bracket", "needs a free period");
    const auto& map = targets.periodic;
    if (map.virtual_points.empty() || map.cells.size() != map.virtual_points.size())
      throw Error("", "--free-period", "needs a periodic patch (skein pattern --relax without --tiled)");
    m_axis = options.period.free_x ? 0 : 1;
    m_inner = options;
    m_inner.period.free = false;
  }

  YarnRelaxReport run(YarnState& state, const std::function<void(const YarnStepLog&)>& on_step) override {
    using Clock = std::chrono::steady_clock;
    const auto started = Clock::now();
    const auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - started).count(); };
    ShapeTargets targets = m_targets;  // its map follows the width tried
    auto& map = targets.periodic;
    if (!state.period.isZero()) {
      // A state that brings its period (the points already at it): the map's offsets follow.
      Eigen::Matrix3Xd none(3, 0);
      scale_period(map, none, state.period(0, 0) / map.period_x.x(), state.period(1, 1) / map.period_y.y());
    }
    const auto width_of = [&] { return m_axis == 0 ? map.period_x.x() : map.period_y.y(); };
    double width = width_of();
    const double start = width;
    WidthSearch search(width, m_options.period.tolerance, m_options.period.bracket);
    std::vector<std::pair<YarnState, YarnRelaxReport>> trials;  // per trial: its state and report
    YarnRelaxReport report;
    double first_peak = -1, first_trust = m_options.lbfgs_first_trust;
    for (;;) {
      auto inner = m_inner;
      inner.lbfgs_first_trust = first_trust;
      inner.force_tolerance = std::min(m_options.force_tolerance, search.trial_force_tolerance(m_options.period.trial_force_tolerance));
      if (m_options.max_seconds > 0) inner.max_seconds = std::max(1e-3, m_options.max_seconds - seconds());
      const auto trial_report = make_cpu_yarn_relaxer(m_system, targets, inner)->run(state, [&](const YarnStepLog& s) {
        if (!on_step) return;
        YarnStepLog log = s;
        log.period_x = map.period_x.x(), log.period_y = map.period_y.y();
        on_step(log);
      });
      if (search.trials() == 0) first_peak = trial_report.first_residual_peak;
      report = trial_report;
      if (trial_report.stopped_by != StopReason::Converged) break;  // a cap, an interrupt, a jam: the search ends with the run
      const WidthTrial trial{width, trial_report.period_stress[m_axis], inner.force_tolerance};
      const double next = search.next(trial);
      spdlog::info("free period by bracket: {} {:.4g} mm, stress {:+.3g} B/r³ after {} steps (relaxed to a force of {:g} B/r³)",
                   m_axis == 0 ? "width" : "height", width, trial.stress, trial_report.steps, inner.force_tolerance);
      trials.emplace_back(state, trial_report);
      if (next == 0) break;
      if (next != width) {  // else the same width relaxed again, tighter: nothing to stretch
        const double scale = next / width;
        const Eigen::Matrix3Xd before = state.points;
        scale_period(map, state.points, m_axis == 0 ? scale : 1, m_axis == 1 ? scale : 1);
        // An affine stretch moves no yarn through another; the auditor checks it as it checks every step.
        if (m_options.audit) state.pull_through_events += static_cast<long>(auditor().crossings(before, state.points).size());
      }
      state.velocities.setZero();
      first_trust = std::min(first_trust, 0.01);  // the state is tight now: L-BFGS starts with small moves
      width = width_of();  // next, as the map holds it
    }
    const char* axis = m_axis == 0 ? "width" : "height";
    const bool over = report.stopped_by == StopReason::Converged;  // else a cap, an interrupt, a jam cut a trial short
    if (!trials.empty()) {
      // The search's result so far (the run's counters kept): a trial cut short ends at no width of its own.
      const YarnState last = state;
      const YarnRelaxReport cut = report;
      // From the last back: a width relaxed again to confirm its stress is kept over its looser first relaxation.
      const auto& [result_state, result_report] = *std::min_element(trials.rbegin(), trials.rend(), [&](const auto& a, const auto& b) {
        return std::abs(a.second.period(m_axis, m_axis) - search.result().width) < std::abs(b.second.period(m_axis, m_axis) - search.result().width);
      });
      state = result_state;
      state.step = last.step, state.guard = last.guard, state.rollbacks = last.rollbacks;
      state.contact_rebuilds = last.contact_rebuilds, state.pull_through_events = last.pull_through_events;
      report = result_report;
      report.steps = cut.steps, report.guard = cut.guard, report.pull_through_events = cut.pull_through_events, report.rollbacks = cut.rollbacks;
      report.contact_rebuilds = cut.contact_rebuilds;
      report.converged = over && search.converged();
      report.stopped_by = !over ? cut.stopped_by : search.converged() ? StopReason::Converged : StopReason::NoStressFreePeriod;
    }
    if (over && search.converged())
      spdlog::info("free period by bracket: {} {:.4g} mm after {} {}s ({}), stress {:+.3g} B/r³", axis, search.result().width, search.trials(), axis,
                   search.within() ? "its stress within the tolerance" : "the bracket within " + fmt::format("{:g}", 100 * m_options.period.bracket) + " %",
                   search.result().stress);
    else if (over)
      spdlog::warn("free period by bracket: no stress-free {} from a quarter to four times {:.4g} mm; the least stress was {:+.3g} B/r³ at {:.4g} mm",
                   axis, start, search.result().stress, search.result().width);
    else if (!trials.empty())
      spdlog::warn("free period by bracket: {} during the {} {:.4g} mm; the {} kept is the search's best so far, {:.4g} mm (stress {:+.3g} B/r³), "
                   "not converged", to_string(report.stopped_by), axis, width, axis, search.result().width, search.result().stress);
    else
      spdlog::warn("free period by bracket: {} before the first {} ({:.4g} mm) was relaxed: no stress-free {} found", to_string(report.stopped_by), axis,
                   width, axis);
    report.period_trials = search.trials();
    state.period = report.period;
    report.free_period = true;
    for (int i = 0; i < 3; ++i)
      if (i != m_axis) report.period_stress[i] = 0;  // as a free period reports: its free components' stresses
    report.first_residual_peak = first_peak;
    report.wall_seconds = seconds();
    return report;
  }

private:
  const TopologyAuditor& auditor() {
    if (!m_auditor) {
      m_auditor.emplace(m_system);
      m_auditor->restrict_to(periodic_tested_segments(m_system, m_targets.periodic));
    }
    return *m_auditor;
  }

  const YarnSystem& m_system;
  const ShapeTargets& m_targets;
  YarnRelaxOptions m_options, m_inner;
  int m_axis = 0;
  std::optional<TopologyAuditor> m_auditor;  ///< built on the first stretch that is audited
};

}  // namespace

std::unique_ptr<YarnRelaxer> make_period_search(const YarnSystem& system, const ShapeTargets& targets, const YarnRelaxOptions& options) {
  return std::make_unique<PeriodSearchRelaxer>(system, targets, options);
}

}  // namespace skein::relax
