#pragma once
#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string>

#include <Eigen/Core>

#include "relax/pull_through_guard.hpp"
#include "relax/shape_targets.hpp"
#include "relax/yarn_active.hpp"
#include "relax/yarn_cell.hpp"
#include "relax/yarn_contacts.hpp"
#include "relax/yarn_segment.hpp"
#include "relax/yarn_system.hpp"

namespace skein::relax {

/// Stiffnesses and damping of the yarn model (Leaf 2018 §3.1 and Appendix B; units mm, g, s). Only their
/// ratios shape the relaxed yarn; the defaults suit the bundled stitch library at r = 0.6 mm.
struct YarnParams {
  double k_bend = 0.1;      ///< eq. 7
  double k_stretch = 20;    ///< eq. 8
  double k_length = 200;    ///< eq. 1
  double k_contact = 50;    ///< eq. 9
  double contact_soft = 0.5;  ///< distance / 2r below which the contact kernel continues linearly
  double k_dt = 0.05;       ///< eq. 12, tangential contact damping
  double k_dn = 0.2;        ///< eq. 12, normal contact damping
  double k_global = 20;     ///< eq. 11, mass-proportional damping [1/s] (Euler)
  double density = 1;       ///< mass per rest length [g/mm]
  void validate() const;
};

/// The stiffnesses that simulate yarn of radius r at radius gamma r (Leaf 2018 §6.2, eq. 4, for this model's
/// energies): bending x gamma, contact x gamma^-2, contact damping x gamma^-4, global damping x gamma^-2,
/// stretch and length unchanged. Relaxed at gamma r and scaled by 1/gamma, the yarn is that of the physical
/// model with 1/gamma of the yarn length: a knob for take-up that keeps the spline segments.
YarnParams radius_scaled(const YarnParams& params, double gamma);
/// The radius scales `skein pattern --gamma` and a sweep's `gamma` take: a quarter to four times the yarn's length.
inline constexpr double kMinGamma = 0.25, kMaxGamma = 4.0;

/// The energy of the yarn at `points` (intrinsic terms of every segment and contact between the given
/// pairs) with its gradient; with `velocities`, also the damping forces (eqs. 11–12) into `damping`.
double yarn_energy(const YarnSystem& system, const YarnParams& params, const ContactPairs& pairs, const Eigen::Matrix3Xd& points,
                   Eigen::Matrix3Xd& gradient, const Eigen::Matrix3Xd* velocities = nullptr, Eigen::Matrix3Xd* damping = nullptr);

/// yarn_energy kept per segment between evaluations: a segment's share is computed again only when one of
/// its control points, a point of a contact partner or its list of partners changed since the last
/// evaluation. The sums run over every segment in a fixed order, so the numbers are those of yarn_energy
/// bit for bit; what a step costs falls with the points that stay put (the active set).
class YarnForces {
public:
  YarnForces(const YarnSystem& system, const YarnParams& params);
  /// The contact pairs of the evaluations to come; segments whose partners differ from the last set's are
  /// computed again. `pairs` must live until the next call.
  void set_pairs(const ContactPairs& pairs);
  /// Everything is computed at the next evaluation (after a jump of the state: a rollback, a new run).
  void invalidate() { m_valid = false; }
  /// yarn_energy at `points` (with `velocities`: also the damping). `changed`: per control point, whether its
  /// position (or, with velocities, its velocity) may differ from the last evaluation's; null: every point.
  double evaluate(const Eigen::Matrix3Xd& points, const std::vector<char>* changed, Eigen::Matrix3Xd& gradient,
                  const Eigen::Matrix3Xd* velocities = nullptr, Eigen::Matrix3Xd* damping = nullptr);
  /// Segments whose share the last evaluation computed (the others were kept).
  long computed_segments() const { return m_computed; }
  /// A periodic patch (Leaf §5): only the real points' forces count (the virtual ones copy them), so only the
  /// segments that hold a real point are computed, and the energy is one repeat's (repeat_segments: each piece
  /// of the repeat's yarn once, its contacts halved as everywhere), the energy cell_stress gives and the one
  /// the real points' forces descend. An empty map: every segment, the whole yarn's energy.
  void set_periodic(const PeriodicMap& map);

private:
  using V = model::Vec3<double>;
  const YarnSystem& m_system;
  YarnParams m_params;
  const ContactPairs* m_pairs = nullptr;
  std::vector<int> m_last_start, m_last_partner;  ///< the pairs the kept shares were computed with
  std::vector<char> m_new_partners;               ///< per segment: its partners changed since
  std::vector<V> m_pos, m_vel;                    ///< contact samples (yarn_segment.hpp SampleView)
  std::vector<double> m_weight, m_arc;
  std::vector<std::array<V, 4>> m_grad, m_damp;   ///< per segment: gradient and damping on its four points
  std::vector<double> m_energy;                   ///< per segment
  std::vector<char> m_role;                       ///< per segment of a periodic patch: 0 skipped, 1 computed, 2 computed and counted; empty: all counted
  bool m_valid = false, m_damped = false;
  long m_computed = 0;
};

/// When a run has converged.
enum class StopRule {
  /// The honest rule (issue 24): the largest force per unit yarn length at most `force_tolerance` times the yarn's
  /// own bending force per length, B / r³ (B = k_bend, the bending stiffness: the force per length that holds the
  /// yarn bent to a radius of r), and the energy stalled: it fell by less than `energy_stall` of itself over the
  /// last `stall_window` steps. Absolute: the first step's forces do not set it.
  Force,
  Leaf,  ///< Leaf 2018 eq. 5: the residual against the first step's (`tolerance`, `stall`)
};
StopRule parse_stop_rule(const std::string& name);  ///< "force" or "leaf"; throws skein::Error otherwise
std::string to_string(StopRule rule);

/// The yarn's bending force per length B / r³ [energy / mm²]: the scale of the force stop rule and of a free
/// period's stress.
double bending_force_scale(const YarnParams& params, double radius);

/// The largest force per unit yarn length of `gradient` (per point: |∇E_p| over its share of the rest length).
double largest_force_per_length(const YarnSystem& system, const Eigen::Matrix3Xd& gradient);

enum class YarnMethod {
  Euler,  ///< semi-implicit Euler with the per-sample step bound of Leaf eq. 2 (Leaf Algorithm 1)
  Fire,   ///< FIRE (Bitzek et al. 2006), a quasi-static descent with inertia; every point clamped to ε r
  /// L-BFGS (Liu and Nocedal 1989): a quasi-Newton descent from the last `lbfgs_memory` moves and force changes,
  /// the whole move scaled down until no point goes further than ε r / 1.25; CPU only
  Lbfgs,
};
YarnMethod parse_yarn_method(const std::string& name);  ///< "euler", "fire" or "lbfgs"; throws skein::Error otherwise
std::string to_string(YarnMethod method);

/// Where a run's steps are computed. Auto: CUDA when skein was built with it and a GPU answers, else the
/// CPU; the choice is logged (skein::cuda::make_yarn_relaxer).
enum class Backend { Auto, Cpu, Cuda };
Backend parse_backend(const std::string& name);  ///< "auto", "cpu" or "cuda"; throws skein::Error otherwise

struct YarnRelaxOptions {
  YarnMethod method = YarnMethod::Fire;
  YarnParams params;
  GuardOptions guard;
  ShapeOptions shape;
  double contact_margin = 1.0;  ///< [r]: pairs this far beyond touching are cached; rebuilt after half of it is used
  double time_step = 0;         ///< [s] Euler's step and FIRE's first step; 0: 0.002 for Euler, 0.02 for FIRE
  double fire_max_step = 0.2;   ///< [s] FIRE's largest step
  int lbfgs_memory = 8;         ///< L-BFGS: the moves and force changes it remembers
  /// L-BFGS: the share of the movement limit its first moves may use, growing by a tenth a step to the whole.
  /// Below 1 for a state already tight: a first move of the whole limit along the bare gradient can press yarn
  /// deep into yarn (a free period's trial widths, period_search.hpp).
  double lbfgs_first_trust = 1;
  StopRule stop_rule = StopRule::Leaf;
  double force_tolerance = 0.5;  ///< StopRule::Force: the largest force per length / (B / r³)
  long stall_window = 200;      ///< StopRule::Force: steps over which the energy must have stalled
  double energy_stall = 1e-4;   ///< StopRule::Force: the energy's fall over the window, a share of itself
  double tolerance = 0.01;      ///< Leaf eq. 5, ε1: |∇E| / |∇E_0|
  double stall = 0.05;          ///< Leaf eq. 5, ε2: | |∇E_i| / |∇E_i-1| - 1 |
  PeriodOptions period;         ///< a periodic patch's free period (variable-cell relaxation; CPU)
  /// Leaf eq. 5's scale |∇E_0| with every point's force clipped to the largest of all but the largest 0.1 %, so
  /// that a few kinks of the emitted yarn do not set it (YarnRelaxReport::first_residual_peak); CPU only.
  bool clipped_scale = false;
  long max_steps = 20000;
  double max_seconds = 0;       ///< wall-time cap, 0 for none
  /// A jam (JamWatch): the run stops, not converged, when for `jam_steps` steps in a row the guard held points
  /// on every step and the energy fell by less than `jam_drop` of itself over them. 0 steps: never.
  long jam_steps = 100;
  double jam_drop = 1e-4;
  bool audit = true;            ///< run the topology auditor on every step (pull_through_events)
  ActiveSetOptions active_set;  ///< converged points stop being integrated (CPU only)
  ContactSampling sampling;     ///< contact samples per segment, for the systems the callers build (make_yarn_system)
  std::filesystem::path checkpoint;  ///< written atomically every checkpoint_every steps / minutes
  long checkpoint_every = 0;
  double checkpoint_minutes = 0;
  /// When set and it turns true, the run stops after the step in progress (stopped_by "interrupted"); the
  /// state is then whole and a later run() goes on from it (pause and stop in the app).
  const std::atomic<bool>* interrupt = nullptr;
  void validate() const;
};

/// Everything a run needs to go on: what a checkpoint holds.
struct YarnState {
  Eigen::Matrix3Xd points, velocities;  ///< [mm], [mm/s]
  long step = 0;
  double time_step = 0;       ///< the integrator's current step
  double fire_alpha = 0;      ///< FIRE's mixing factor
  long fire_positive = 0;     ///< FIRE's steps downhill in a row
  double residual0 = 0, residual_prev = 0;  ///< |∇E| at the first step (or the scale set before it) and the previous step
  GuardCounters guard;
  long rollbacks = 0, contact_rebuilds = 0, pull_through_events = 0;
  /// With a free period: the repeat's period (period_x, period_y) [mm]; zero until a run sets it (the map's own).
  Eigen::Matrix<double, 3, 2> period = Eigen::Matrix<double, 3, 2>::Zero();
};
YarnState initial_state(const YarnSystem& system, const YarnRelaxOptions& options);

struct YarnStepLog {
  long step = 0;
  double energy = 0, residual = 0;  ///< residual: |∇E| / |∇E_0|
  double time_step = 0, moved = 0;  ///< moved: the largest distance a point of the yarn moved [mm]
  long contacts = 0, guard_hits = 0, held_points = 0;
  long crossings = 0;  ///< centreline crossings the auditor found in this step
  long awake = 0;      ///< control points integrated in this step (all of them without the active set)
  double force = 0;    ///< the largest force per unit yarn length over B / r³ (StopRule::Force)
  double period_x = 0, period_y = 0;  ///< with a free period: the repeat's L_x and L_y [mm]
};

/// Outcome of a run; not converging is a result, not an exception.
/// Why a run ended (a yarn relaxation, a local re-relaxation); logs, reports and JSON keep to_string's words.
enum class StopReason {
  None,            ///< not run yet
  Converged,       ///< the stop rule held
  StepCap,         ///< max_steps reached
  TimeCap,         ///< max_seconds reached
  Interrupted,     ///< a signal (Ctrl-C) or the app's Stop
  Jammed,          ///< yarn pulled against yarn it may not pass: the same points held step after step (JamWatch)
  Diverged,        ///< the energy became NaN or infinite
  NothingChanged,  ///< a local re-relaxation with no changed stitch
  UnsafeSplice,    ///< a local re-relaxation whose splice would cross yarn: nothing relaxed
  NoStressFreePeriod,  ///< a free period's bracket search found no stress-free length within reach
};
std::string to_string(StopReason reason);  ///< "converged", "step cap", "time cap", ... ("" for None)
inline std::ostream& operator<<(std::ostream& out, StopReason reason) { return out << to_string(reason); }

struct YarnRelaxReport {
  bool converged = false;
  StopReason stopped_by = StopReason::None;
  long steps = 0;
  double wall_seconds = 0, residual = 0, energy = 0;
  double force_residual = 0;  ///< the largest force per unit yarn length at the end, over B / r³ (StopRule::Force)
  /// A periodic patch's period (period_x, period_y) [mm] at the end (relaxed with a free period, else the one it
  /// was given; zero for yarn that is not a periodic patch) and its stresses there (dE/dL_x / L_y, dE/dL_y / L_x,
  /// dE/ds / L_x; a fixed period's shear too, a free one's only when it may shear) over B / r³.
  bool free_period = false;
  Eigen::Matrix<double, 3, 2> period = Eigen::Matrix<double, 3, 2>::Zero();
  Eigen::Vector3d period_stress = Eigen::Vector3d::Zero();
  double repeat_energy = 0;  ///< one repeat's energy at the end (cell_stress), with a period
  CellStress::Terms repeat_terms;  ///< the same by term
  int period_trials = 0;     ///< a free period by bracket (PeriodOptions::Method::Bracket): the widths relaxed to the end
  long contacts = 0;          ///< contact pairs at the end
  GuardCounters guard;
  long pull_through_events = -1;  ///< centreline crossings found by the auditor; -1 when it did not run
  /// The share of |∇E₀|² from the largest 0.1 % of the points' forces; above 0.5 a few spots (kinks in the
  /// emitted yarn, yarn nearly touching yarn) set the scale of Leaf's relative stop rule, and the log warns
  /// that the run may stop early.
  /// -1 when the state brought its own scale (a resumed or local run), and on the GPU (not measured there).
  double first_residual_peak = -1;
  long rollbacks = 0, contact_rebuilds = 0;
  ActiveSetCounters active;     ///< with the active set: what it did
  std::string backend = "cpu";  ///< "cpu", or "cuda: " and the device's name
};

/// Tells a run that is jammed from one that still relaxes. Where emitted yarn lies pulled against yarn it may
/// not pass (a jam), the guard holds the same points step after step, their forces keep Leaf's residual above
/// its tolerance, and the energy creeps: such a run would go on to its step cap without converging. Fed every
/// step's energy (before the step) and the points the guard held in it, it says jammed when for `steps` steps
/// in a row some points were held and the energy fell by less than `drop` of itself over them; a window that
/// fell more starts the next.
class JamWatch {
public:
  JamWatch(long steps, double drop) : m_steps(steps), m_drop(drop) {}
  bool jammed(double energy, long held);
  /// What a jammed run says of itself, for the log.
  std::string describe() const;

private:
  long m_steps;
  double m_drop;
  long m_streak = 0, m_held = 0;
  double m_start = 0, m_fell = 0;
};

/// The run loop's policy, the same on every back-end (issue 23): which stop reason wins when several hold, how
/// many rollbacks in a row a run may take, and when a checkpoint is due. Each back-end keeps its own steps (the
/// CPU's loop, the GPU's batches of kernels) and asks this between them; the guard's round policy is shared the
/// same way (model::guard_round).
class RunControl {
public:
  explicit RunControl(const YarnRelaxOptions& options);
  double seconds() const;    ///< since the run started
  bool out_of_time() const;  ///< the time cap (max_seconds) has passed
  bool interrupted() const;  ///< the caller has asked the run to stop
  /// Why a run that has reached `step` stops, in this order: converged, the step cap, the time cap, an interrupt,
  /// a jam; StopReason::None to go on.
  StopReason stop(long step, bool converged, bool out_of_time, bool interrupted, bool jammed) const;
  /// After a step that was not finite (the state goes back to the last good one): false once more than
  /// kMaxRollbacks have come in a row, and the run has diverged.
  bool roll_back() { return ++m_rollbacks <= kMaxRollbacks; }
  void step_taken() { m_rollbacks = 0; }  ///< a finite step ends a run of rollbacks
  /// Whether a checkpoint is due now that `step` steps are done: at every checkpoint_every steps, or when
  /// checkpoint_minutes have passed since the last one.
  bool checkpoint_due(long step) const;
  void checkpoint_written();  ///< restarts the clock of checkpoint_minutes
  static constexpr int kMaxRollbacks = 20;

private:
  using Clock = std::chrono::steady_clock;
  const YarnRelaxOptions& m_options;
  Clock::time_point m_started = Clock::now(), m_last_checkpoint = m_started;
  int m_rollbacks = 0;
};

/// Relaxes yarn control points toward equilibrium (Yuksel 2012 §6.3, Leaf 2018 §3); never lets two yarns
/// pass through each other. One interface for every backend.
class YarnRelaxer {
public:
  virtual ~YarnRelaxer() = default;
  /// Steps `state` until converged or capped; `on_step` sees every step's figures.
  virtual YarnRelaxReport run(YarnState& state, const std::function<void(const YarnStepLog&)>& on_step = {}) = 0;
};

/// The CPU relaxer (OpenMP), the reference for every other backend. `targets` may be empty (bare yarn).
std::unique_ptr<YarnRelaxer> make_cpu_yarn_relaxer(const YarnSystem& system, const ShapeTargets& targets, const YarnRelaxOptions& options);

/// The energy the CPU relaxer measures at `points` (its first evaluation: no step, audit or checkpoint), with the
/// same terms, contacts and shape targets as a relaxation: what a preview or a stand-in is worth against one.
double relaxer_energy(const YarnSystem& system, const ShapeTargets& targets, const YarnRelaxOptions& options, const Eigen::Matrix3Xd& points);

}  // namespace skein::relax
