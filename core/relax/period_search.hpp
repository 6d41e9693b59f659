#pragma once
// A free period found from outside (issue 24): the repeat relaxed at fixed widths, one after another, and the
// width where its stress is zero found by a bracketing root search. Under tension (take-up below 1) the width
// of a fabric is a soft mode: relaxed with the points (CellFrame) it creeps for tens of thousands of steps at
// stresses far above the period's tolerance, while a fixed width converges in a few thousand. The stress at a
// converged width is the energy's derivative there (cell_stress at equilibrium), so the search needs no mass
// for the period and ends with the stress-free width bracketed.
#include <memory>

#include "relax/shape_targets.hpp"
#include "relax/yarn_relax.hpp"

namespace skein::relax {

/// One relaxation at a fixed width, as the search saw it.
struct WidthTrial {
  double width = 0;   ///< the repeat's length along the free axis [mm]
  double stress = 0;  ///< the free axis's stress at the end, over B / r³ (positive: the repeat would narrow)
  double force_tolerance = 0;  ///< the force (× B / r³) it was relaxed to; 0: tightly enough to be believed
};

/// Where to relax next, from converged trials along one axis. Against the stress until a trial's stress
/// changes sign: 4 % of the start width first, then the secant of the last two trials, kept within half and
/// twice the last step and 15 % of the width. A bracket so found has the repeat pulled out (stress < 0) at its
/// narrow end and pushed in at its wide end: an energy minimum lies between. Inside it, regula falsi with the
/// Illinois halving of an end kept twice (Dowell and Jarratt 1971). Done when a trial's stress is at most
/// `tolerance` (a trial relaxed more loosely than trial_force_tolerance's floor is relaxed again at it first: its
/// stress may be noise), when the bracket is narrower than `bracket` of the width (converged either way: the stress at
/// the bracket's ends can then be several times the tolerance, or far more where it jumps, as at a rib's wall), or
/// when the width would leave a quarter to four times the start or a stress is not finite (not converged).
class WidthSearch {
public:
  WidthSearch(double start, double tolerance, double bracket) : m_start(start), m_tolerance(tolerance), m_bracket(bracket) {}
  /// The width to try after `trial`; 0 when the search is over.
  double next(const WidthTrial& trial);
  bool converged() const { return m_converged; }
  bool within() const { return m_within; }  ///< converged with a trial's stress within the tolerance (else by the bracket)
  /// The answer once the search is over: the trial within the tolerance, else the bracket's end with the smaller
  /// stress, else (not converged) the trial with the smallest stress. On a rib's plateau, where the stress
  /// stays small and nearly flat, the smallest stress can lie far outside the final bracket.
  const WidthTrial& result() const;
  int trials() const { return m_trials; }
  /// The force tolerance (× B / r³) for the next width's relaxation: `loosest` while every stress so far is large,
  /// tighter as the search nears the root, so that the noise a trial leaves in its stress (about a twentieth of
  /// its force tolerance, measured) stays below the stress it must read the sign of: ten times the smallest
  /// stress seen, never below twenty times the tolerance (where that noise is the tolerance itself), and that
  /// floor once the root is bracketed or a trial's stress is to be confirmed.
  double trial_force_tolerance(double loosest) const;

private:
  double m_start, m_tolerance, m_bracket;
  WidthTrial m_best, m_last, m_low, m_high;  // m_low: stress < 0, the narrow end; m_high: stress > 0
  bool m_low_set = false, m_high_set = false, m_converged = false, m_within = false, m_confirming = false;
  int m_trials = 0, m_kept_low = 0, m_kept_high = 0;
  double m_step = 0;
};

/// The relaxer of a free period by WidthSearch (PeriodOptions::Method::Bracket): one free length, no shear. Every
/// width is relaxed by the CPU relaxer with the period fixed, converged by the run's stop rule with the force
/// tolerance at most WidthSearch::trial_force_tolerance(PeriodOptions::trial_force_tolerance): a rib's stress
/// under tension is about a hundredth of B/r³ over a fifth of its width, and a trial leaves noise of about a
/// twentieth of its force tolerance in it: 0.02 B/r³ at the run's 0.5, and at 0.1 still 0.005, enough to stop two
/// starts of the 1x1 rib 16 % apart. Each trial
/// starts from the last one's points stretched to its width: an affine map of the whole patch, copies and frozen
/// points too, which moves no yarn through another. Ends with the result()'s points and period. Steps, the step
/// and time caps and interrupts count over all trials; the log and the report see one run. A run cut short (a
/// cap, an interrupt, a jam) ends at the search's best finished width, not the one it was relaxing.
std::unique_ptr<YarnRelaxer> make_period_search(const YarnSystem& system, const ShapeTargets& targets, const YarnRelaxOptions& options);

}  // namespace skein::relax
