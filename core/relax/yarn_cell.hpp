#pragma once
// Variable-cell relaxation of a periodic patch (issue 24; Leaf 2018 §7 fixes the period by hand): the repeat's
// period is a degree of freedom beside the control points. The derivative of one repeat's energy with respect
// to its period is the patch's mean stress; relaxing it to zero finds the stress-free repeat, so a rib narrows
// and a garter shortens by themselves and a pattern reports its own gauge.
#include <Eigen/Core>

#include "relax/periodic_map.hpp"
#include "relax/yarn_contacts.hpp"
#include "relax/yarn_system.hpp"

namespace skein::relax {

struct YarnParams;

/// One repeat's energy and its derivative with respect to the period at fixed real points (virtual point v
/// sits at its real point + a_v period_x + b_v period_y). The repeat's energy is the share of the real
/// segments (those that start at a real point: one of every periodic copy): their intrinsic terms and half of
/// each contact they take part in, as the relaxer counts it. A contact between samples at lattice coordinates
/// c_a and c_b (their basis-weighted cells) adds ½ ∂C/∂y_a (c_a − c_b)ᵀ: only differences of cells count,
/// so the result does not depend on which copy is called real.
struct CellStress {
  double energy = 0;                                             ///< one repeat's energy
  /// The same energy by term: bending (Leaf eq. 7), internal stretch (eq. 8), length (eq. 1) and contact (eq. 9).
  /// Which term holds a relaxed fabric: eq. 8 only keeps the spline's parameter speed even, yet in the model's
  /// relaxed stockinette it is 96 % of the energy and bending 4 % (docs/BENCHMARKS.md, "What the energy is made of").
  struct Terms {
    double bending = 0, stretch = 0, length = 0, contact = 0;
  } terms;
  Eigen::Matrix<double, 3, 2> gradient = Eigen::Matrix<double, 3, 2>::Zero();  ///< dE / d[period_x period_y]
  double area = 0;                                               ///< |period_x × period_y| [mm²]
  /// The mean stress σ = (1/A) Σ_k dE/dP_k P_kᵀ over the two periods (the energy's derivative per unit strain
  /// of the repeat, per area), in the plane of the fabric: xx across the course, yy along the wale.
  Eigen::Matrix2d mean_stress(const Eigen::Vector3d& period_x, const Eigen::Vector3d& period_y) const;
};

/// Which segments of a periodic patch make up one repeat: one of each piece of yarn (its span and the two points
/// either side, by their real points and repeats), of those that reach a real point. A yarn can cross the
/// repeat's edge in both directions (a loop's head in the row above, its legs in this one), so a piece that has
/// a real point at both of its ends' copies can be there twice: counting segments by their first real point
/// alone counted such pieces twice, in the energy and the stress.
std::vector<char> repeat_segments(const YarnSystem& system, const PeriodicMap& map);

/// The segments a periodic patch's pull-through guard and auditor test pairs from: one repeat's (repeat_segments)
/// and those that copy none of them (next to a frozen point, or at a yarn end where the patch's curves are cut). Every other segment is a translated copy of a
/// repeat segment that moves as it does (apply_periodic), and the rings are at least two stitches wide, so each
/// pair that can meet in a step (within the movement limit) has a copy whose one segment is a repeat segment and
/// whose other is in the patch: testing that copy tests them all. The guard's groups (a real point with its
/// copies) carry a halving or hold to every copy.
std::vector<char> periodic_tested_segments(const YarnSystem& system, const PeriodicMap& map);

/// The stress at `points` with contact between the given pairs; the map must say each virtual point's cell.
CellStress cell_stress(const YarnSystem& system, const YarnParams& params, const ContactPairs& pairs, const PeriodicMap& map,
                       const Eigen::Matrix3Xd& points);

/// The period's three stresses from its derivative: dE/dL_x / L_y, dE/dL_y / L_x and dE/ds / L_x (each per
/// length of the cut it acts across; s is period_y's x component, the shear).
Eigen::Vector3d period_stresses(const CellStress& stress, const Eigen::Matrix<double, 3, 2>& period);

/// What a free period may do (relax-yarn --free-period, skein pattern --relax --free-period).
struct PeriodOptions {
  bool free = false;        ///< relax the period too (periodic patches only; CPU)
  /// With free: the repeat may shear too (period_y's x component), as a diagonal pattern does. Off by default: the
  /// model's stockinette lowers its energy by under 1 % by shearing a third of a stitch (a soft mode that friction,
  /// which the model lacks, holds in real fabric).
  bool shear = false;
  /// With free: which of the two lengths relax; a length held stays at its given value (`--free-period x` finds
  /// the stress-free width of a rib at the row height a gauge sets).
  bool free_x = true, free_y = true;
  /// Converged when every free component's stress (dE/dL per length of the cut it acts across) is at most
  /// this times the yarn's bending force per length B / r³ (the stop rule's scale, StopRule).
  double tolerance = 1e-3;
  /// How the free length relaxes. Frame: with the points, as L-BFGS's variables (CellFrame; Rprop beside FIRE and
  /// Euler). Bracket: the repeat relaxed at one fixed width after another until the width where its stress is
  /// zero is found (period_search.hpp): one free length, no shear; under tension, where the width is a soft mode
  /// that the frame creeps along, it converges.
  enum class Method { Frame, Bracket } method = Method::Frame;
  /// Bracket: converged too when the stress-free length is bracketed within this share of it.
  double bracket = 5e-3;
  /// Bracket: the loosest force tolerance (× B / r³) a width is relaxed to when the run's is looser; trials
  /// near the stress-free width are relaxed tighter (WidthSearch::trial_force_tolerance says why).
  double trial_force_tolerance = 0.1;
  void validate() const;    ///< throws skein::Error for a tolerance that is not positive or no length free
};

/// The period's degrees of freedom: L_x = period_x.x, L_y = period_y.y and, with shear, s = period_y.x (period_x
/// stays on the x axis and both in the plane). Each step moves them by resilient propagation (Rprop, Riedmiller and
/// Braun 1993: per component a step that grows while the stress keeps its sign and halves when it flips), which
/// needs no mass for the cell and copes with the noise of the control points relaxing at the same time; no move
/// takes a virtual point further than `largest_move`.
class PeriodRelaxer {
public:
  PeriodRelaxer(const PeriodOptions& options, const Eigen::Vector3d& period_x, const Eigen::Vector3d& period_y);
  /// The next period from the stress (the step's size limited so that no virtual point of `map` moves more than
  /// `largest_move` [mm]); it is only proposed: accept() or reject() it.
  Eigen::Matrix<double, 3, 2> propose(const CellStress& stress, const PeriodicMap& map, double largest_move);
  void accept(const Eigen::Matrix<double, 3, 2>& period) { m_period = period; }
  void reject();  ///< the guard would have changed the move: every step halves
  const Eigen::Matrix<double, 3, 2>& period() const { return m_period; }
  /// The free components' stresses (dE/dL_x / L_y, dE/dL_y / L_x, dE/ds / L_x) from the last propose.
  const Eigen::Vector3d& stress() const { return m_stress; }
  double energy() const { return m_energy; }  ///< one repeat's energy at the last propose
  const CellStress::Terms& terms() const { return m_terms; }  ///< the same by term
  /// Every free component's stress at most `limit` [energy / mm²].
  bool converged(double limit) const;

private:
  PeriodOptions m_options;
  Eigen::Matrix<double, 3, 2> m_period;
  Eigen::Vector3d m_step, m_last = Eigen::Vector3d::Zero(), m_stress = Eigen::Vector3d::Constant(INFINITY);
  double m_energy = 0;
  CellStress::Terms m_terms;
};

/// The repeat's deformation as variables of the control points' L-BFGS (variable-cell relaxation as atomistic
/// relaxers do it: Tadmor et al. 1999's fractional coordinates, ASE's cell filters). The period is P = F P0 for
/// an in-plane deformation F (upper triangular: period_x stays on the x axis), and every real point is
/// x = c + F (X − c) for reference coordinates X about the real points' centre c. A move of F deforms the whole
/// patch at once, real points with their copies, where the staggered Rprop step (PeriodRelaxer) moves only the
/// virtual copies and leaves the real points to follow a strain that starts at the repeat's edge: the width of
/// a rib is a soft mode of a whole repeat (docs/yarn-relaxation.md, "The free period"), which the staggered
/// step took 80,000 steps to drift along. The variables are the points' X (columns 0 to n − 1 of the L-BFGS
/// vector, virtual and frozen ones zero) and one more column: L × (F00, F11, F01), L the longer period, so
/// that a unit step moves the repeat's far side about a millimetre, as a point's does.
class CellFrame {
public:
  CellFrame(const PeriodOptions& options, const Eigen::Matrix<double, 3, 2>& period, const PeriodicMap& map, const Eigen::Matrix3Xd& points);
  /// dE/d(variables) from the points' gradient (virtual and frozen columns zero) and the repeat's stress at
  /// the same state: Fᵀ g for each point (in the plane) and, for the frame, (Σ g (X − c)ᵀ + ∂E/∂P P0ᵀ) / L
  /// in its free components.
  Eigen::Matrix3Xd gradient(const Eigen::Matrix3Xd& grad, const CellStress& stress, const Eigen::Matrix3Xd& points) const;
  /// A move of the variables as the two moves the relaxer takes one after the other: the points' own
  /// (F ΔX, into `points_move`) and the frame's (the next period; the points then follow it by affine_move).
  Eigen::Matrix<double, 3, 2> split(const Eigen::Matrix3Xd& move, Eigen::Matrix3Xd& points_move) const;
  /// The move of every point that is not frozen (copies included) by the deformation from the current period to `next`.
  Eigen::Matrix3Xd affine_move(const Eigen::Matrix<double, 3, 2>& next, const Eigen::Matrix3Xd& points) const;
  /// The largest distance a point travels under a move of the variables [mm] (both parts, copies included).
  double largest_move(const Eigen::Matrix3Xd& move, const Eigen::Matrix3Xd& points) const;
  /// The variables' move that a taken points' move and period correspond to (the L-BFGS secant pair's s).
  Eigen::Matrix3Xd taken(const Eigen::Matrix3Xd& points_move, const Eigen::Matrix<double, 3, 2>& next) const;
  void accept(const Eigen::Matrix<double, 3, 2>& next);  ///< the period the patch now has
  const Eigen::Matrix<double, 3, 2>& period() const { return m_period; }

private:
  Eigen::Matrix2d deformation() const;  ///< F, in the plane
  Eigen::Vector3d m_free;               ///< per frame variable (F00, F11, F01): 1 when free
  Eigen::Matrix<double, 3, 2> m_period0, m_period;
  const PeriodicMap& m_map;
  std::vector<char> m_frozen;
  Eigen::Vector2d m_centre;
  double m_length = 1;
};

}  // namespace skein::relax
