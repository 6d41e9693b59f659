#include "relax/yarn_active.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"

namespace skein::relax {

void ActiveSetOptions::validate() const {
  const auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw Error("", "active set", std::string(name) + " must be positive, found " + std::to_string(v));
  };
  positive(sleep_force, "the sleep force");
  positive(sleep_move, "the sleep move");
  positive(wake_move, "the wake move");
  if (!(wake_force > sleep_force) || !std::isfinite(wake_force))
    throw Error("", "active set", "the wake force must be finite and above the sleep force (" + std::to_string(sleep_force) + "), found " + std::to_string(wake_force));
  if (quiet_steps < 1) throw Error("", "active set", "the quiet steps must be at least 1, found " + std::to_string(quiet_steps));
}

ActiveSet::ActiveSet(const YarnSystem& system, const ActiveSetOptions& options, std::vector<char> never_sleep)
    : m_system(system), m_options(options), m_never(std::move(never_sleep)), m_asleep(system.num_points(), 0), m_quiet(system.num_points(), 0),
      m_disturbance(system.num_points(), 0.0) {
  m_options.validate();
  if (m_never.empty()) m_never.assign(system.num_points(), 0);
}

long ActiveSet::choose(const Eigen::Matrix3Xd& gradient, double level) {
  const double sleep = m_options.sleep_force * level, wake = m_options.wake_force * level;
  long awake = 0, sleeps = 0, wakes = 0;
#pragma omp parallel for schedule(static) reduction(+ : awake, sleeps, wakes)
  for (int p = 0; p < m_system.num_points(); ++p) {
    const double force = gradient.col(p).norm();
    if (m_asleep[p] && force > wake) {
      m_asleep[p] = 0;
      m_quiet[p] = 0;
      ++wakes;
    } else if (!m_asleep[p] && !m_never[p] && force < sleep && m_quiet[p] >= m_options.quiet_steps) {
      m_asleep[p] = 1;
      m_disturbance[p] = 0;
      ++sleeps;
    }
    awake += !m_asleep[p];
  }
  m_counters.sleeps += sleeps;
  m_counters.wakes_by_force += wakes;
  m_counters.point_steps += awake;
  return awake;
}

void ActiveSet::moved(const Eigen::Matrix3Xd& delta, const ContactPairs& pairs) {
  const int points = m_system.num_points(), segments = m_system.num_segments();
  // Per segment the largest move of its points, then the largest over it and its contact partners.
  std::vector<double> own(segments), near(segments);
#pragma omp parallel for schedule(static)
  for (int s = 0; s < segments; ++s) {
    double m = 0;
    for (int p : m_system.segment_points[s]) m = std::max(m, delta.col(p).norm());
    own[s] = m;
  }
#pragma omp parallel for schedule(static)
  for (int s = 0; s < segments; ++s) {
    double m = own[s];
    for (int k = pairs.start[s]; k < pairs.start[s + 1]; ++k) m = std::max(m, own[pairs.partner[k]]);
    near[s] = m;
  }
  const double quiet = m_options.sleep_move * m_system.radius, wake = m_options.wake_move * m_system.radius;
  long wakes = 0;
#pragma omp parallel for schedule(static) reduction(+ : wakes)
  for (int p = 0; p < points; ++p) {
    m_quiet[p] = delta.col(p).norm() < quiet ? m_quiet[p] + 1 : 0;
    if (!m_asleep[p]) continue;
    double m = 0;
    for (int i = m_system.point_segments_start[p]; i < m_system.point_segments_start[p + 1]; ++i) m = std::max(m, near[m_system.point_segments[i] >> 2]);
    m_disturbance[p] += m;
    if (m_disturbance[p] >= wake) {
      m_asleep[p] = 0;
      m_quiet[p] = 0;
      ++wakes;
    }
  }
  m_counters.wakes_by_move += wakes;
}

void ActiveSet::wake_all() {
  std::fill(m_asleep.begin(), m_asleep.end(), 0);
  std::fill(m_quiet.begin(), m_quiet.end(), 0);
}

}  // namespace skein::relax
