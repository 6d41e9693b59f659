#pragma once
#include <vector>

#include <Eigen/Core>

#include "relax/yarn_contacts.hpp"
#include "relax/yarn_system.hpp"

namespace skein::relax {

/// When control points stop being integrated and when they start again (YarnRelaxOptions::active_set).
/// A point's level is the stop rule's share per point, ε1 |∇E_0| / √N: if every point stayed under it, the
/// whole residual would pass Leaf eq. 5's test.
struct ActiveSetOptions {
  bool enabled = false;
  double sleep_force = 0.5;  ///< a point falls asleep when its |∇E| is below this × its level ...
  double sleep_move = 0.01;  ///< ... and it moved less than this × r on each of the last `quiet_steps` steps
  int quiet_steps = 3;
  double wake_force = 2;     ///< a sleeping point wakes when its |∇E| grows past this × its level ...
  double wake_move = 0.05;   ///< ... or the points it shares a segment or a contact pair with moved this × r since it fell asleep
  void validate() const;     ///< throws skein::Error for values out of range
};

/// How often the active set acted over a run.
struct ActiveSetCounters {
  long point_steps = 0;      ///< control points integrated, summed over steps
  long sleeps = 0;           ///< points put to sleep
  long wakes_by_force = 0;   ///< sleeping points woken because their own force grew
  long wakes_by_move = 0;    ///< sleeping points woken because a neighbour moved
};

/// The active set (issue 10): control points whose neighbourhood has converged stop being integrated, and
/// wake when their force grows or a segment or contact neighbour moves. The forces on sleeping points are
/// still evaluated (YarnForces keeps what did not change), so the stop rule always sees the whole system.
class ActiveSet {
public:
  /// `never_sleep`: per point, set for points tied to others by a constraint (border loops, periodic copies).
  ActiveSet(const YarnSystem& system, const ActiveSetOptions& options, std::vector<char> never_sleep);

  /// Before a step: wakes sleeping points whose force grew past wake_force × `level` and puts quiet points
  /// under sleep_force × `level` to sleep. Returns the points awake.
  long choose(const Eigen::Matrix3Xd& gradient, double level);
  /// After the step moved the points by `delta`: counts quiet steps, and wakes sleeping points whose segment
  /// or contact neighbours (`pairs`) moved wake_move × r in all since they fell asleep.
  void moved(const Eigen::Matrix3Xd& delta, const ContactPairs& pairs);
  void wake_all();

  bool asleep(int p) const { return m_asleep[p] != 0; }
  const ActiveSetCounters& counters() const { return m_counters; }

private:
  const YarnSystem& m_system;
  ActiveSetOptions m_options;
  std::vector<char> m_never, m_asleep;
  std::vector<int> m_quiet;           ///< per point: steps in a row it moved less than sleep_move r
  std::vector<double> m_disturbance;  ///< per sleeping point: its neighbours' moves since it fell asleep [mm]
  ActiveSetCounters m_counters;
};

}  // namespace skein::relax
