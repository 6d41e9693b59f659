#include "relax/yarn_relax.hpp"
#include "relax/lbfgs.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <cmath>
#include <functional>
#include <numeric>
#include <optional>

#include <spdlog/spdlog.h>

#include "common/cpu_threads.hpp"
#include "common/error.hpp"
#include "relax/period_search.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_checkpoint.hpp"
#include "relax/yarn_model.hpp"
#include "relax/yarn_segment.hpp"

namespace skein::relax {
namespace {

using V = model::Vec3<double>;
V vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d eig(const V& v) { return {v.x, v.y, v.z}; }

/// A sum that does not depend on the number of threads: fixed chunks, added in order.
template <class F>
double ordered_sum(long n, F term) {
  constexpr long kChunks = 64;
  double part[kChunks] = {};
#pragma omp parallel for schedule(static)
  for (long c = 0; c < kChunks; ++c)
    for (long i = n * c / kChunks; i < n * (c + 1) / kChunks; ++i) part[c] += term(i);
  double total = 0;
  for (double p : part) total += p;
  return total;
}

/// The share of |∇E|² that the largest 0.1 % of the points' forces carry (at least one point): near 0.001 when
/// the force is spread over the yarn, near 1 when a few spots dominate it.
double peak_share(const Eigen::Matrix3Xd& grad) {
  std::vector<double> squared(grad.cols());
  for (long p = 0; p < grad.cols(); ++p) squared[p] = grad.col(p).squaredNorm();
  const double total = std::accumulate(squared.begin(), squared.end(), 0.0);
  if (!(total > 0)) return 0;
  const long top = std::max<long>(1, grad.cols() / 1000);
  std::nth_element(squared.begin(), squared.begin() + top - 1, squared.end(), std::greater<>());
  return std::accumulate(squared.begin(), squared.begin() + top, 0.0) / total;
}

/// |∇E| with every point's force clipped to the largest force left when the largest 0.1 % are set aside.
double clipped_norm(const Eigen::Matrix3Xd& grad) {
  std::vector<double> squared(grad.cols());
  for (long p = 0; p < grad.cols(); ++p) squared[p] = grad.col(p).squaredNorm();
  if (squared.empty()) return 0;
  const long top = std::max<long>(1, grad.cols() / 1000);
  std::vector<double> sorted = squared;
  std::nth_element(sorted.begin(), sorted.begin() + top, sorted.end(), std::greater<>());
  const double cap = top < static_cast<long>(sorted.size()) ? sorted[top] : sorted.back();
  double sum = 0;
  for (double s : squared) sum += std::min(s, cap);
  return std::sqrt(sum);
}

void check_param(double v, const char* name, bool allow_zero = true) {
  if (!std::isfinite(v) || v < 0 || (!allow_zero && v == 0))
    throw Error("", "yarn model", std::string(name) + " must be " + (allow_zero ? "finite and not negative" : "positive") + ", found " + std::to_string(v));
}

}  // namespace

void YarnParams::validate() const {
  check_param(k_bend, "k_bend");
  check_param(k_stretch, "k_stretch");
  check_param(k_length, "k_length");
  check_param(k_contact, "k_contact", false);
  check_param(k_dt, "k_dt");
  check_param(k_dn, "k_dn");
  check_param(k_global, "k_global");
  check_param(density, "density", false);
  if (!(contact_soft > 0 && contact_soft < 1)) throw Error("", "yarn model", "contact_soft must be in (0, 1), found " + std::to_string(contact_soft));
}

RunControl::RunControl(const YarnRelaxOptions& options) : m_options(options) {}

double RunControl::seconds() const { return std::chrono::duration<double>(Clock::now() - m_started).count(); }

bool RunControl::out_of_time() const { return m_options.max_seconds > 0 && seconds() >= m_options.max_seconds; }

bool RunControl::interrupted() const { return m_options.interrupt && m_options.interrupt->load(); }

StopReason RunControl::stop(long step, bool converged, bool out_of_time, bool interrupted, bool jammed) const {
  if (converged) return StopReason::Converged;
  if (step >= m_options.max_steps) return StopReason::StepCap;
  if (out_of_time) return StopReason::TimeCap;
  if (interrupted) return StopReason::Interrupted;
  if (jammed) return StopReason::Jammed;
  return StopReason::None;
}

bool RunControl::checkpoint_due(long step) const {
  const bool by_steps = m_options.checkpoint_every > 0 && step % m_options.checkpoint_every == 0;
  const bool by_time = m_options.checkpoint_minutes > 0 && std::chrono::duration<double>(Clock::now() - m_last_checkpoint).count() >= 60 * m_options.checkpoint_minutes;
  return by_steps || by_time;
}

void RunControl::checkpoint_written() { m_last_checkpoint = Clock::now(); }

bool JamWatch::jammed(double energy, long held) {
  if (m_steps <= 0) return false;
  if (held == 0) {
    m_streak = 0;
    return false;
  }
  if (m_streak == 0) m_start = energy;
  m_held = held;
  if (++m_streak < m_steps) return false;
  m_fell = (m_start - energy) / std::abs(m_start);
  if (m_fell < m_drop) return true;
  m_streak = 0;
  return false;
}

std::string JamWatch::describe() const {
  return fmt::format("jammed: the guard held yarn against yarn on each of the last {} steps ({} points on the last) and the energy {} by "
                     "{:.4f} % over them; the run stops here, not converged (--jam-steps 0 goes on)",
                     m_steps, m_held, m_fell < 0 ? "rose" : "fell only", 100 * std::abs(m_fell));
}

void YarnRelaxOptions::validate() const {
  params.validate();
  guard.validate();
  shape.validate();
  check_param(contact_margin, "contact_margin", false);
  check_param(time_step, "time_step");
  check_param(fire_max_step, "fire_max_step", false);
  check_param(tolerance, "tolerance");
  check_param(stall, "stall");
  check_param(force_tolerance, "force_tolerance", false);
  check_param(energy_stall, "energy_stall");
  if (stall_window < 1) throw Error("", "yarn relaxation", "the energy's stall window must be at least 1 step, found " + std::to_string(stall_window));
  period.validate();
  if (period.free && period.method == PeriodOptions::Method::Bracket && stop_rule != StopRule::Force)
    throw Error("", "--period-method bracket",
                "judges each width by the force stop rule (--stop-rule force): Leaf's relative rule would judge later widths by the first one's forces");
  if (period.free && (checkpoint_every > 0 || checkpoint_minutes > 0))
    throw Error("", "yarn relaxation", "a free period is not checkpointed: relax a periodic patch without checkpoints");
  check_param(max_seconds, "max_seconds");
  check_param(checkpoint_minutes, "checkpoint_minutes");
  check_param(jam_drop, "jam_drop");
  if (jam_steps < 0) throw Error("", "yarn relaxation", "jam_steps must be 0 (never) or more, found " + std::to_string(jam_steps));
  if (active_set.enabled) active_set.validate();
  if (active_set.enabled && method == YarnMethod::Lbfgs)
    throw Error("", "--active-set", "works with fire or euler: L-BFGS moves every point along one direction");
  if (!(lbfgs_first_trust >= 1e-3 && lbfgs_first_trust <= 1))
    throw Error("", "yarn relaxation", "L-BFGS's first trust must be 0.001 to 1, found " + std::to_string(lbfgs_first_trust));
  if (lbfgs_memory < 1 || lbfgs_memory > 100)
    throw Error("", "yarn relaxation", "the L-BFGS memory must be 1 to 100 moves, found " + std::to_string(lbfgs_memory));
  sampling.validate();
  if (guard.max_move > 0.5 * contact_margin)
    throw Error("", "max_move", "the movement limit ε (" + std::to_string(guard.max_move) + " r) must be at most half the contact margin, contact_margin (" +
                                    std::to_string(contact_margin) + " r), or pairs could meet between contact updates");
  if (max_steps < 0) throw Error("", "yarn relaxation", "the step cap must not be negative");
  if (checkpoint_every < 0) throw Error("", "yarn relaxation", "the checkpoint interval must not be negative");
  if ((checkpoint_every > 0 || checkpoint_minutes > 0) && checkpoint.empty())
    throw Error("", "yarn relaxation", "a checkpoint interval needs a checkpoint file");
}

YarnParams radius_scaled(const YarnParams& params, double gamma) {
  if (!(gamma > 0) || !std::isfinite(gamma)) throw Error("", "gamma", "the radius scale must be positive, found " + std::to_string(gamma));
  YarnParams out = params;
  out.k_bend *= gamma;                        // l' = gamma l, kappa' = kappa / gamma in l k_bend int kappa^2
  out.k_contact /= gamma * gamma;             // the quadrature weights carry two rest lengths
  out.k_dt /= gamma * gamma * gamma * gamma;
  out.k_dn /= gamma * gamma * gamma * gamma;
  out.k_global /= gamma * gamma;
  return out;
}

YarnMethod parse_yarn_method(const std::string& name) {
  if (name == "euler") return YarnMethod::Euler;
  if (name == "fire") return YarnMethod::Fire;
  if (name == "lbfgs") return YarnMethod::Lbfgs;
  throw Error("", "--method", "expected euler, fire or lbfgs, found '" + name + "'");
}

std::string to_string(YarnMethod method) {
  switch (method) {
    case YarnMethod::Euler: return "euler";
    case YarnMethod::Fire: return "fire";
    case YarnMethod::Lbfgs: return "lbfgs";
  }
  return "fire";
}

StopRule parse_stop_rule(const std::string& name) {
  if (name == "force") return StopRule::Force;
  if (name == "leaf") return StopRule::Leaf;
  throw Error("", "--stop-rule", "expected force or leaf, found '" + name + "'");
}

std::string to_string(StopRule rule) { return rule == StopRule::Force ? "force" : "leaf"; }

std::string to_string(StopReason reason) {
  switch (reason) {
    case StopReason::None: return "";
    case StopReason::Converged: return "converged";
    case StopReason::StepCap: return "step cap";
    case StopReason::TimeCap: return "time cap";
    case StopReason::Interrupted: return "interrupted";
    case StopReason::Jammed: return "jammed";
    case StopReason::Diverged: return "diverged";
    case StopReason::NothingChanged: return "nothing changed";
    case StopReason::UnsafeSplice: return "unsafe splice";
    case StopReason::NoStressFreePeriod: return "no stress-free period";
  }
  return "";
}

double bending_force_scale(const YarnParams& params, double radius) { return params.k_bend / (radius * radius * radius); }

double largest_force_per_length(const YarnSystem& system, const Eigen::Matrix3Xd& gradient) {
  double largest = 0;
#pragma omp parallel for reduction(max : largest) schedule(static)
  for (int p = 0; p < system.num_points(); ++p) largest = std::max(largest, gradient.col(p).norm() / system.mass[p]);
  return largest;
}

Backend parse_backend(const std::string& name) {
  if (name == "auto") return Backend::Auto;
  if (name == "cpu") return Backend::Cpu;
  if (name == "cuda") return Backend::Cuda;
  throw Error("", "--backend", "expected auto, cpu or cuda, found '" + name + "'");
}

double yarn_energy(const YarnSystem& system, const YarnParams& params, const ContactPairs& pairs, const Eigen::Matrix3Xd& points,
                   Eigen::Matrix3Xd& gradient, const Eigen::Matrix3Xd* velocities, Eigen::Matrix3Xd* damping) {
  YarnForces forces(system, params);
  forces.set_pairs(pairs);
  return forces.evaluate(points, nullptr, gradient, velocities, damping);
}

YarnForces::YarnForces(const YarnSystem& system, const YarnParams& params)
    : m_system(system), m_params(params), m_new_partners(system.num_segments(), 1) {
  const int samples = system.sample_start.back() + system.contact_samples.back();
  m_pos.resize(samples);
  m_vel.resize(samples);
  m_weight.resize(samples);
  m_arc.resize(samples);
  m_grad.resize(system.num_segments());
  m_damp.resize(system.num_segments());
  m_energy.resize(system.num_segments());
}

void YarnForces::set_periodic(const PeriodicMap& map) {
  m_role.clear();
  m_valid = false;
  if (map.empty()) return;
  if (map.cells.size() != map.virtual_points.size()) throw Error("", "periodic patch", "the periodic map does not say each virtual point's repeat");
  std::vector<char> real(m_system.num_points(), 1);
  for (int p : map.virtual_points) real[p] = 0;
  for (int p : map.frozen) real[p] = 0;
  m_role = repeat_segments(m_system, map);  // one repeat's segments (yarn_cell.hpp)
  for (int s = 0; s < m_system.num_segments(); ++s) {
    const auto& sp = m_system.segment_points[s];
    if (m_role[s]) m_role[s] = 2;
    else if (real[sp[0]] || real[sp[1]] || real[sp[2]] || real[sp[3]]) m_role[s] = 1;
  }
}

void YarnForces::set_pairs(const ContactPairs& pairs) {
  m_pairs = &pairs;
  if (m_last_start.size() != pairs.start.size()) {
    m_valid = false;
  } else {
#pragma omp parallel for schedule(static)
    for (int s = 0; s < m_system.num_segments(); ++s)
      m_new_partners[s] |= !std::equal(pairs.partner.begin() + pairs.start[s], pairs.partner.begin() + pairs.start[s + 1],
                                       m_last_partner.begin() + m_last_start[s], m_last_partner.begin() + m_last_start[s + 1]);
  }
  m_last_start = pairs.start;
  m_last_partner = pairs.partner;
}

double YarnForces::evaluate(const Eigen::Matrix3Xd& points, const std::vector<char>* changed, Eigen::Matrix3Xd& gradient,
                            const Eigen::Matrix3Xd* velocities, Eigen::Matrix3Xd* damping) {
  if (!m_pairs) throw Error("", "yarn forces", "no contact pairs were set");
  const int segments = m_system.num_segments();
  const bool damped = velocities != nullptr;
  if (damped != m_damped) m_valid = false;
  m_damped = damped;
  const bool all = !m_valid || !changed;
  const model::IntrinsicParams<double> intrinsic{m_params.k_bend, m_params.k_stretch, m_params.k_length};
  const model::ContactParams<double> contact{m_params.k_contact, damped ? m_params.k_dt : 0.0, damped ? m_params.k_dn : 0.0, m_system.radius,
                                             m_params.contact_soft};
  const V zero{0, 0, 0};
  const auto view = segment_view(m_system);
  const auto point = [&](int p) { return vec(points.col(p)); };
  const auto velocity = [&](int p) { return damped ? vec(velocities->col(p)) : zero; };
  // Contact samples of every segment with a changed point (Leaf §3.1).
  std::vector<char> resampled(segments, 1);
  const model::SampleView<double> sample_view{m_pos.data(), m_vel.data(), m_weight.data(), m_arc.data()};
#pragma omp parallel for schedule(static)
  for (int s = 0; s < segments; ++s) {
    if (!all) {
      const auto& sp = m_system.segment_points[s];
      resampled[s] = (*changed)[sp[0]] || (*changed)[sp[1]] || (*changed)[sp[2]] || (*changed)[sp[3]];
    }
    if (resampled[s]) model::segment_samples(view, s, point, velocity, sample_view);
  }
  // Per segment the gradient on its four control points (and the contact damping force) where its samples,
  // a partner's samples or its partners changed; gathered per point afterwards (Leaf §3.2 stencils): no two
  // threads write the same place.
  const ContactPairs& pairs = *m_pairs;
  const model::PairView pair_view{pairs.start.data(), pairs.partner.data()};
  long computed = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : computed)
  for (int s = 0; s < segments; ++s) {
    const char role = m_role.empty() ? 2 : m_role[s];
    if (role == 0) {  // a periodic patch's segment with no real point: no force of it counts, ever
      if (all) m_energy[s] = 0, m_grad[s] = {zero, zero, zero, zero}, m_damp[s] = {zero, zero, zero, zero};
      continue;
    }
    bool stale = all || resampled[s] || m_new_partners[s];
    for (int k = pairs.start[s]; k < pairs.start[s + 1] && !stale; ++k) stale = resampled[pairs.partner[k]];
    if (!stale) continue;
    ++computed;
    V g[4] = {zero, zero, zero, zero}, d[4] = {zero, zero, zero, zero};
    const double energy = model::segment_forces(view, sample_view, pair_view, intrinsic, contact, s, point, g, d);
    m_energy[s] = role == 2 ? energy : 0.0;
    for (int k = 0; k < 4; ++k) {
      m_grad[s][k] = g[k];
      m_damp[s][k] = d[k];
    }
  }
  m_computed = computed;
  m_valid = true;
  std::fill(m_new_partners.begin(), m_new_partners.end(), 0);
  gradient.setZero(3, points.cols());
  if (damping) damping->setZero(3, points.cols());
#pragma omp parallel for schedule(static)
  for (int p = 0; p < m_system.num_points(); ++p) {
    V g = zero, d = zero;
    for (int i = m_system.point_segments_start[p]; i < m_system.point_segments_start[p + 1]; ++i) {
      const int code = m_system.point_segments[i];
      g += m_grad[code >> 2][code & 3];
      if (damped) d += m_damp[code >> 2][code & 3];
    }
    gradient.col(p) = eig(g);
    if (damping && damped)
      damping->col(p) = eig(d) - m_params.k_global * m_system.mass[p] * m_params.density * velocities->col(p);  // eq. 11, lumped
  }
  return ordered_sum(segments, [&](long s) { return m_energy[s]; });
}

YarnState initial_state(const YarnSystem& system, const YarnRelaxOptions& options) {
  YarnState state;
  state.points = system.points;
  state.velocities.setZero(3, system.num_points());
  state.time_step = options.time_step > 0 ? options.time_step : options.method == YarnMethod::Euler ? 0.002 : 0.02;
  state.fire_alpha = 0.1;
  return state;
}

namespace {

class CpuYarnRelaxer final : public YarnRelaxer {
public:
  CpuYarnRelaxer(const YarnSystem& system, const ShapeTargets& targets, const YarnRelaxOptions& options)
      : m_system(system), m_targets(targets), m_options(options), m_auditor(system), m_forces(system, options.params),
        m_changed(system.num_points(), 1), m_lbfgs(options.lbfgs_memory), m_lbfgs_trust(options.lbfgs_first_trust), m_periodic(targets.periodic) {
    m_options.validate();
    m_forces.set_periodic(m_periodic);
    if (m_options.period.free && (m_periodic.virtual_points.empty() || m_periodic.cells.size() != m_periodic.virtual_points.size()))
      throw Error("", "--free-period", "needs a periodic patch (skein pattern --relax without --tiled)");
    std::vector<int> groups(system.num_points(), -1);
    for (int l = 0; l < static_cast<int>(targets.boundary_loops.size()); ++l)
      for (int p : targets.boundary_loops[l]) groups[p] = l;
    group_copies(targets.periodic, groups, static_cast<int>(targets.boundary_loops.size()));
    if (m_options.active_set.enabled) {
      // Points tied to others by a constraint move with them: they never sleep.
      std::vector<char> tied(system.num_points());
      for (int p = 0; p < system.num_points(); ++p) tied[p] = groups[p] >= 0;
      m_active.emplace(system, m_options.active_set, std::move(tied));
    }
    m_guard.emplace(system, m_options.guard, std::move(groups));
    if (!m_periodic.empty()) {
      // One copy of each pair is tested; the guard's groups carry its halvings to the other copies.
      auto tested = periodic_tested_segments(system, m_periodic);
      m_auditor.restrict_to(tested);
      m_guard->restrict_to(std::move(tested));
    }
    m_inv_mass.resize(system.num_points());
    for (int p = 0; p < system.num_points(); ++p) m_inv_mass[p] = 1.0 / (system.mass[p] * m_options.params.density);
  }

  YarnRelaxReport run(YarnState& state, const std::function<void(const YarnStepLog&)>& on_step) override {
    RunControl control(m_options);
    auto last_thread_count = std::chrono::steady_clock::now();
    const auto seconds_since = [](auto t) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count(); };
    refresh_thread_count();
    const double r = m_system.radius, limit = m_options.guard.max_move * r;
    JamWatch jam(m_options.jam_steps, m_options.jam_drop);
    bool jammed = false;
    const auto fingerprint = checkpoint_fingerprint(m_system, m_options.method);
    m_guard->set_counters(state.guard);
    refresh_contacts(state);
    m_forces.invalidate();
    if (m_active) m_active->wake_all();

    YarnRelaxReport report;
    const double force_scale = bending_force_scale(m_options.params, r);
    // A free period: L-BFGS takes it as three more variables (CellFrame), FIRE and Euler step it apart (Rprop).
    std::optional<PeriodRelaxer> cell;
    std::optional<CellFrame> frame;
    CellStress frame_stress;
    Eigen::Vector3d frame_stresses = Eigen::Vector3d::Constant(INFINITY);
    const Eigen::Vector3d free_components(m_options.period.free_x, m_options.period.free_y, m_options.period.shear);
    if (m_options.period.free) {
      if (state.period.isZero()) state.period << m_periodic.period_x, m_periodic.period_y;
      set_period(m_periodic, state.points, state.period.col(0), state.period.col(1));
      if (m_options.method == YarnMethod::Lbfgs)
        frame.emplace(m_options.period, state.period, m_periodic, state.points);
      else
        cell.emplace(m_options.period, state.period.col(0), state.period.col(1));
      report.free_period = true;
    }
    std::deque<double> energies;  // the force rule's window: the last stall_window + 1 energies
    Eigen::Matrix<double, 3, 2> good_period = state.period;
    Eigen::Matrix3Xd grad, frame_grad, damping, delta, good_points = state.points, good_velocities = state.velocities;
    double energy = 0, residual = 0, force = 0;
    for (;;) {
      energy = forces(state, grad, damping);
      if (!m_periodic.empty()) constrain_gradient(m_periodic, grad);
      residual = std::sqrt(ordered_sum(grad.cols(), [&](long p) { return grad.col(p).squaredNorm(); }));
      if (!std::isfinite(energy) || !std::isfinite(residual) || !state.points.allFinite()) {
        // Blow-up: back to the last good state with half the step (Leaf §3.1's step restriction failed).
        state.points = good_points;
        state.velocities = good_velocities;
        if (cell || frame) {
          state.period = good_period;
          set_period(m_periodic, state.points, state.period.col(0), state.period.col(1));
          if (frame) frame->accept(state.period);
        }
        state.time_step *= 0.5;
        ++state.rollbacks;
        forget_lbfgs(0.5);
        m_forces.invalidate();
        if (m_active) m_active->wake_all();
        spdlog::warn("step {}: the yarn state is not finite; back to the last good state, step {:.3g} s", state.step, state.time_step);
        if (!control.roll_back()) {
          report.stopped_by = StopReason::Diverged;
          break;
        }
        refresh_contacts(state);
        continue;
      }
      control.step_taken();
      if (frame) {
        frame_stress = cell_stress(m_system, m_options.params, m_pairs, m_periodic, state.points);
        frame_stresses = period_stresses(frame_stress, state.period).cwiseProduct(free_components);
        frame_grad = frame->gradient(grad, frame_stress, state.points);
      }
      // L-BFGS after a rollback: shorter moves, lengthening again step by step. No line search and no test of the
      // energy (as atomistic relaxers do; docs/yarn-relaxation.md).
      if (m_options.method == YarnMethod::Lbfgs) m_lbfgs_trust = std::min(1.0, m_lbfgs_trust * 1.1);
      good_points = state.points;
      good_velocities = state.velocities;
      good_period = state.period;
      if (state.residual0 == 0) {  // a state may bring its own scale (local relaxation)
        state.residual0 = m_options.clipped_scale ? clipped_norm(grad) : residual;
        report.first_residual_peak = peak_share(grad);
        if (m_options.clipped_scale)
          spdlog::info("stop rule's scale: |∇E_0| with the largest 0.1 % of the forces clipped, {:.3g} of its whole value", state.residual0 / residual);
        else if (m_options.stop_rule == StopRule::Leaf && report.first_residual_peak > 0.5) {  // the force rule's scale is absolute
          Eigen::Index largest;
          grad.colwise().squaredNorm().maxCoeff(&largest);
          const Eigen::Vector3d at = state.points.col(largest);
          spdlog::warn("the first residual is {:.0f} % from the largest 0.1 % of the control points' forces (the largest at point {}, "
                       "({:.1f}, {:.1f}, {:.1f}) mm): Leaf's relative stop rule may end this run early; relax the stitch mesh first or "
                       "lower the tolerance",
                       100 * report.first_residual_peak, largest, at.x(), at.y(), at.z());
        }
      }
      const double relative = residual / state.residual0;
      force = largest_force_per_length(m_system, grad) / force_scale;
      energies.push_back(energy);
      if (static_cast<long>(energies.size()) > m_options.stall_window + 1) energies.pop_front();
      const auto stopped = [&] {
        if (m_options.stop_rule == StopRule::Leaf)
          return model::converged(state.step, residual, state.residual0, state.residual_prev, m_options.tolerance, m_options.stall);
        const bool full = static_cast<long>(energies.size()) == m_options.stall_window + 1;
        return full && force <= m_options.force_tolerance && energies.front() - energy <= m_options.energy_stall * std::abs(energy);
      };
      const auto cell_converged = [&] {
        if (frame) return frame_stresses.cwiseAbs().maxCoeff() <= m_options.period.tolerance * force_scale;
        return !cell || cell->converged(m_options.period.tolerance * force_scale);
      };
      bool converged = stopped() && cell_converged();
      if (converged && m_active) {
        // The honest final check: the whole system's forces from scratch, none of them kept.
        m_forces.invalidate();
        energy = forces(state, grad, damping);
        if (!m_periodic.empty()) constrain_gradient(m_periodic, grad);
        residual = std::sqrt(ordered_sum(grad.cols(), [&](long p) { return grad.col(p).squaredNorm(); }));
        force = largest_force_per_length(m_system, grad) / force_scale;
        energies.back() = energy;
        converged = stopped() && cell_converged();
        if (!converged) {
          spdlog::warn("step {}: the active set's forces disagree with a fresh evaluation; every point wakes", state.step);
          m_active->wake_all();
        }
      }
      state.residual_prev = residual;
      report.stopped_by = control.stop(state.step, converged, control.out_of_time(), control.interrupted(), jammed);
      if (report.stopped_by != StopReason::None) {
        report.converged = converged;
        if (report.stopped_by == StopReason::Jammed) spdlog::warn("step {}: {}", state.step, jam.describe());
        break;
      }

      const GuardCounters before = m_guard->counters();
      const long awake = m_active ? m_active->choose(grad, m_options.tolerance * state.residual0 / std::sqrt(static_cast<double>(grad.cols())))
                                  : grad.cols();
      const double dt = propose(state, frame ? frame_grad : grad, damping, limit, delta, frame ? &*frame : nullptr);
      Eigen::Matrix<double, 3, 2> next_period = state.period;
      if (frame) {
        const Eigen::Matrix3Xd variables_move = delta;
        next_period = frame->split(variables_move, delta);
      }
      if (!m_targets.boundary_loops.empty()) project_boundary(m_targets, delta);
      if (!m_periodic.empty()) apply_periodic(m_periodic, delta, state.velocities);
      const double scale = m_guard->accept(state.points, delta);
      const long crossings = m_options.audit ? static_cast<long>(m_auditor.crossings(state.points, state.points + delta).size()) : 0;
      state.pull_through_events += crossings;
      state.points += delta;
      if (m_options.method == YarnMethod::Lbfgs) {
        // The move taken, after the guard: the secant pair's s (real points only, and a free period's frame).
        m_lbfgs_move = delta;
        if (!m_periodic.empty()) constrain_gradient(m_periodic, m_lbfgs_move);
        if (frame) {
          if (next_period != state.period) state.pull_through_events += frame_step(*frame, state, next_period, delta);
          m_lbfgs_move = frame->taken(m_lbfgs_move, next_period);
        }
        m_lbfgs_moved = true;
      } else if (scale < 1) {
        state.velocities = delta / dt;  // the velocity that matches the move the guard let through
      }
      if (cell) state.pull_through_events += period_step(*cell, state, limit / 1.25, delta);
      ++state.step;
      if (seconds_since(last_thread_count) >= 0.5) {  // issue 28: the cores other work left free, now
        refresh_thread_count();
        last_thread_count = std::chrono::steady_clock::now();
      }
      mark_changed(state, delta);
      if (m_active) m_active->moved(delta, m_pairs);
      const double moved = largest_sample_move(m_system, delta);
      m_moved_since_rebuild += moved;
      if (m_moved_since_rebuild >= 0.5 * m_options.contact_margin * r) refresh_contacts(state);
      state.guard = m_guard->counters();
      jammed = jam.jammed(energy, state.guard.held_points - before.held_points);

      if (on_step) {
        YarnStepLog log;
        log.step = state.step;
        log.energy = energy;
        log.residual = relative;
        log.time_step = dt * scale;
        log.moved = moved;
        log.contacts = m_pairs.pairs();
        log.guard_hits = state.guard.finest_hits - before.finest_hits;
        log.held_points = state.guard.held_points - before.held_points;
        log.crossings = crossings;
        log.awake = awake;
        log.force = force;
        if (cell || frame) log.period_x = state.period(0, 0), log.period_y = state.period(1, 1);
        on_step(log);
      }
      if (control.checkpoint_due(state.step)) {
        write_checkpoint(m_options.checkpoint, fingerprint, state);
        control.checkpoint_written();
        // A resumed run starts with fresh contacts and safe bounds, and L-BFGS with no memory (neither is in the
        // checkpoint); so does this one, so both go on alike.
        refresh_contacts(state);
        if (m_options.method == YarnMethod::Lbfgs) {
          forget_lbfgs(1);
          m_lbfgs_trust = 1;
        }
      }
    }
    // The last state too, so that a run stopped by a cap goes on from where it stopped.
    if (!m_options.checkpoint.empty() && report.stopped_by != StopReason::Diverged) write_checkpoint(m_options.checkpoint, fingerprint, state);
    report.steps = state.step;
    report.wall_seconds = control.seconds();
    report.residual = state.residual0 > 0 ? residual / state.residual0 : 0;
    report.force_residual = force;
    if (cell) {
      report.period = state.period;
      report.period_stress = cell->stress() / force_scale;
      report.repeat_energy = cell->energy();
      report.repeat_terms = cell->terms();
    } else if (frame) {
      report.period = state.period;
      report.period_stress = frame_stresses / force_scale;
      report.repeat_energy = frame_stress.energy;
      report.repeat_terms = frame_stress.terms;
    } else if (!m_periodic.virtual_points.empty() && m_periodic.cells.size() == m_periodic.virtual_points.size()) {
      // A fixed period's stress says how far it is from the repeat's stress-free one (and its sign, which way).
      report.period << m_periodic.period_x, m_periodic.period_y;
      const CellStress stress = cell_stress(m_system, m_options.params, m_pairs, m_periodic, state.points);
      report.period_stress = period_stresses(stress, report.period) / force_scale;
      report.repeat_energy = stress.energy;
      report.repeat_terms = stress.terms;
    }
    report.energy = energy;
    report.contacts = m_pairs.pairs();
    report.guard = m_guard->counters();
    report.pull_through_events = m_options.audit ? state.pull_through_events : -1;
    report.rollbacks = state.rollbacks;
    report.contact_rebuilds = state.contact_rebuilds;
    if (m_active) report.active = m_active->counters();
    return report;
  }

private:
  void refresh_contacts(YarnState& state) {
    m_pairs = find_contact_pairs(m_system, state.points, m_options.contact_margin * m_system.radius);
    ++state.contact_rebuilds;
    m_guard->reset(m_pairs);
    m_forces.set_pairs(m_pairs);
    m_moved_since_rebuild = 0;
  }

  /// A free period's step (after the control points' one): the repeat's stress at the new positions, a move of
  /// the period (Rprop) that carries every virtual point with its cell, passed through the guard on its own and
  /// taken only whole (a virtual point must stay its real point plus its offset). The move is added to `delta`;
  /// returns the auditor's crossings in it.
  long period_step(PeriodRelaxer& cell, YarnState& state, double largest_move, Eigen::Matrix3Xd& delta) {
    const auto stress = cell_stress(m_system, m_options.params, m_pairs, m_periodic, state.points);
    const Eigen::Matrix<double, 3, 2> next = cell.propose(stress, m_periodic, largest_move), change = next - state.period;
    if (change.isZero()) return 0;
    Eigen::Matrix3Xd move = Eigen::Matrix3Xd::Zero(3, m_system.num_points());
    for (size_t i = 0; i < m_periodic.virtual_points.size(); ++i)
      move.col(m_periodic.virtual_points[i]) = change * m_periodic.cells[i].cast<double>();
    Eigen::Matrix3Xd guarded = move;
    GuardCounters counters = m_guard->counters();
    m_guard->accept(state.points, guarded);
    const long held = m_guard->counters().held_points - counters.held_points;
    counters = m_guard->counters();
    --counters.steps;  // one step, two passes
    m_guard->set_counters(counters);
    if (held > 0 || !(guarded - move).isZero()) {
      cell.reject();
      return 0;
    }
    const long crossings = m_options.audit ? static_cast<long>(m_auditor.crossings(state.points, state.points + move).size()) : 0;
    set_period(m_periodic, state.points, next.col(0), next.col(1));
    state.period = next;
    cell.accept(next);
    delta += move;
    return crossings;
  }

  /// L-BFGS's frame move (after the points' one): every point carried by the deformation to `next`, passed through
  /// the guard on its own and taken only whole, as period_step's; `next` becomes the period kept. The move is
  /// added to `delta`; returns the auditor's crossings in it.
  long frame_step(CellFrame& frame, YarnState& state, Eigen::Matrix<double, 3, 2>& next, Eigen::Matrix3Xd& delta) {
    const Eigen::Matrix3Xd move = frame.affine_move(next, state.points);
    Eigen::Matrix3Xd guarded = move;
    GuardCounters counters = m_guard->counters();
    m_guard->accept(state.points, guarded);
    const long held = m_guard->counters().held_points - counters.held_points;
    counters = m_guard->counters();
    --counters.steps;  // one step, two passes
    m_guard->set_counters(counters);
    if (held > 0 || !(guarded - move).isZero()) {
      next = state.period;
      return 0;
    }
    const long crossings = m_options.audit ? static_cast<long>(m_auditor.crossings(state.points, state.points + move).size()) : 0;
    state.points += move;
    set_period(m_periodic, state.points, next.col(0), next.col(1));
    state.period = next;
    frame.accept(next);
    delta += move;
    return crossings;
  }

  /// Which points the next evaluation must see as changed: those that moved, and for Euler's damping those
  /// whose velocity changed.
  void mark_changed(const YarnState& state, const Eigen::Matrix3Xd& delta) {
    const bool damped = m_options.method == YarnMethod::Euler;
#pragma omp parallel for schedule(static)
    for (int p = 0; p < m_system.num_points(); ++p)
      m_changed[p] = delta.col(p).squaredNorm() > 0 || (damped && state.velocities.col(p) != m_velocities.col(p));
  }

  /// Energy and its gradient (yarn model and patch tracking) at `state`, and for Euler the damping forces
  /// (FIRE steers its own velocities and takes none).
  double forces(const YarnState& state, Eigen::Matrix3Xd& grad, Eigen::Matrix3Xd& damping) {
    const bool damped = m_options.method == YarnMethod::Euler;
    double energy = m_forces.evaluate(state.points, &m_changed, grad, damped ? &state.velocities : nullptr, damped ? &damping : nullptr);
    if (damped) m_velocities = state.velocities;
    if (!m_targets.patches.empty()) energy += patch_energy(m_targets, m_options.shape, m_system.radius, state.points, grad);
    return energy;
  }

  /// The integrator's proposed move into `delta`; returns the time step it used.
  /// With a free period's frame, L-BFGS moves its variables (`grad` and `delta` have the frame's column).
  double propose(YarnState& state, const Eigen::Matrix3Xd& grad, const Eigen::Matrix3Xd& damping, double limit, Eigen::Matrix3Xd& delta,
                 const CellFrame* frame) {
    const int n = m_system.num_points();
    const auto asleep = [&](int p) { return m_active && m_active->asleep(p); };
    Eigen::Matrix3Xd accel(3, n);
    // Sleeping points neither move nor carry velocity.
#pragma omp parallel for schedule(static)
    for (int p = 0; p < n; ++p)
      if (asleep(p)) state.velocities.col(p).setZero();
    if (m_options.method == YarnMethod::Euler) {
#pragma omp parallel for schedule(static)
      for (int p = 0; p < n; ++p) accel.col(p) = asleep(p) ? Eigen::Vector3d::Zero() : Eigen::Vector3d((damping.col(p) - grad.col(p)) * m_inv_mass[p]);
      // Leaf eq. 2: the largest step after which no contact sample moves more than ε r.
      double dt = state.time_step;
#pragma omp parallel for schedule(static) reduction(min : dt)
      for (int s = 0; s < m_system.num_segments(); ++s)
        for (int i = 0, ns = m_system.contact_samples[s]; i < ns; ++i) {
          double w[4];
          model::basis(static_cast<double>(i) / (ns - 1), w);
          Eigen::Vector3d u = Eigen::Vector3d::Zero(), a = Eigen::Vector3d::Zero();
          for (int k = 0; k < 4; ++k) {
            u += w[k] * state.velocities.col(m_system.segment_points[s][k]);
            a += w[k] * accel.col(m_system.segment_points[s][k]);
          }
          dt = std::min(dt, model::step_bound(u.norm(), a.norm(), limit));
        }
      state.velocities += dt * accel;
      delta = dt * state.velocities;
      return dt;
    }
    if (m_options.method == YarnMethod::Lbfgs) {
      if (m_lbfgs_moved) m_lbfgs.remember(m_lbfgs_move, grad - m_lbfgs_grad);
      m_lbfgs_grad = grad;
      delta = m_lbfgs.direction(grad);
      // The whole move scaled (its direction kept) so that no point goes further than the trusted share of ε r / 1.25.
      double largest = 0;
      if (frame)
        largest = frame->largest_move(delta, state.points);
      else
        for (int p = 0; p < n; ++p) largest = std::max(largest, delta.col(p).norm());
      const double clamp = m_lbfgs_trust * limit / 1.25;
      if (largest > 0 && (largest > clamp || m_lbfgs.empty())) delta *= clamp / largest;
      state.velocities.setZero();
      return 1.0;
    }
    // FIRE (Bitzek et al. 2006) on the forces, semi-implicit.
    Eigen::Matrix3Xd force = -grad;
#pragma omp parallel for schedule(static)
    for (int p = 0; p < n; ++p) {
      if (asleep(p)) force.col(p).setZero();
      accel.col(p) = force.col(p) * m_inv_mass[p];
    }
    const double power = ordered_sum(n, [&](long p) { return force.col(p).dot(state.velocities.col(p)); });
    const double vnorm = std::sqrt(ordered_sum(n, [&](long p) { return state.velocities.col(p).squaredNorm(); }));
    const double fnorm = std::sqrt(ordered_sum(n, [&](long p) { return force.col(p).squaredNorm(); }));
    model::FireControl<double> control{state.time_step, state.fire_alpha, state.fire_positive};
    double keep, mix;
    model::fire_control(power, vnorm, fnorm, m_options.fire_max_step, control, keep, mix);
    state.time_step = control.time_step;
    state.fire_alpha = control.alpha;
    state.fire_positive = control.positive;
    state.velocities = keep * state.velocities + mix * force;
    const double dt = state.time_step;
    state.velocities += dt * accel;
    delta = dt * state.velocities;
    // Every point at most ε r / 1.25, so no sample moves more than ε r (Catmull-Rom: sum |b| <= 1.25).
    const double clamp = limit / 1.25;
#pragma omp parallel for schedule(static)
    for (int p = 0; p < n; ++p) {
      const double m = delta.col(p).norm();
      if (m > clamp) {
        delta.col(p) *= clamp / m;
        state.velocities.col(p) = delta.col(p) / dt;
      }
    }
    return dt;
  }

  const YarnSystem& m_system;
  const ShapeTargets& m_targets;
  YarnRelaxOptions m_options;
  TopologyAuditor m_auditor;
  std::optional<PullThroughGuard> m_guard;
  Eigen::VectorXd m_inv_mass;
  ContactPairs m_pairs;
  YarnForces m_forces;
  std::vector<char> m_changed;   ///< per point: moved (or for Euler its velocity changed) since the last evaluation
  LbfgsMemory m_lbfgs;           ///< L-BFGS: the remembered moves and gradient changes
  Eigen::Matrix3Xd m_lbfgs_grad, m_lbfgs_move;  ///< L-BFGS: the last step's gradient and the move it took
  bool m_lbfgs_moved = false;    ///< L-BFGS: a move was taken since the memory was last forgotten
  double m_lbfgs_trust;          ///< L-BFGS: the share of the movement limit a move may use

  void forget_lbfgs(double shrink) {
    m_lbfgs.forget();
    m_lbfgs_moved = false;
    m_lbfgs_trust = std::max(1e-3, m_lbfgs_trust * shrink);
  }
  Eigen::Matrix3Xd m_velocities;  ///< Euler: the velocities of the last evaluation
  std::optional<ActiveSet> m_active;
  double m_moved_since_rebuild = 0;
  PeriodicMap m_periodic;  ///< the periodic patch's map, its offsets those of the current period
};

}  // namespace

std::unique_ptr<YarnRelaxer> make_cpu_yarn_relaxer(const YarnSystem& system, const ShapeTargets& targets, const YarnRelaxOptions& options) {
  if (options.period.free && options.period.method == PeriodOptions::Method::Bracket) return make_period_search(system, targets, options);
  return std::make_unique<CpuYarnRelaxer>(system, targets, options);
}

double relaxer_energy(const YarnSystem& system, const ShapeTargets& targets, const YarnRelaxOptions& options, const Eigen::Matrix3Xd& points) {
  auto probe = options;
  probe.max_steps = 0;
  probe.audit = false;
  probe.checkpoint.clear();
  probe.checkpoint_every = 0;
  probe.checkpoint_minutes = 0;
  auto state = initial_state(system, probe);
  state.points = points;
  return make_cpu_yarn_relaxer(system, targets, probe)->run(state).energy;
}

}  // namespace skein::relax
