#pragma once
// Where the stitched fabric goes when its threads are pulled: the constrained 2-D projection of a coarse
// mass-spring system (Zhou, Ren and Sorkine-Hornung 2024, §4.1, Algorithm 1), and the 3-D positional
// constraints lifted from it (§4.2, eqs. 6-8).
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "smocking/smocking_pattern.hpp"

namespace skein::smocking {

/// Algorithm 1's settings; the defaults are the paper's (§5.6, and the hyper-parameters of Algorithm 1).
struct EmbedOptions {
  double gamma = 0.3;          ///< stop when the threads are this fraction of their sewn length (eq. 1c)
  double thickness = -1;       ///< fabric thickness τ [mm]; below 0: 1 % of the grid's longer side (the paper's 0.01 at 1 m)
  Eigen::Vector2d pull{1, 0};  ///< the pulling direction (eq. 5 measures stitches across it); the paper's is horizontal
  bool pull_along_stitches = false;  ///< each stitch pulled along itself (its target τ), as the paper's CURVE pattern
  double time_step = 0.1, damping = 0.9;  ///< Δt and α of Algorithm 1
  double k_fabric = 1, k_stitch = 5;      ///< spring stiffnesses
  int max_iterations = 200'000;
  int stall_window = 2'000;        ///< stalled: the threads shortened by less than stall_tolerance of D(X̄) over this many iterations
  double stall_tolerance = 1e-5;
  std::vector<double> snapshots;   ///< keep the embedding when the threads first reach each of these fractions (Zhou Fig. 6, 18)
  int history_every = 10;          ///< record D(X)/D(X̄) every this many iterations (Zhou Fig. 17)
  /// Project the fabric back inside eq. 1b after every step (a Gauss-Seidel sweep over the fabric springs), and
  /// after the last until it holds to `settle_tolerance`. Ours, not the paper's: its explicit steps alone let the
  /// threads reach γ with the fabric stretched by up to 90 % (Canadian knots close in 5 steps), where Appendix A
  /// says eq. 1b holds throughout. Off: Algorithm 1 as printed.
  bool settle = true;
  double settle_tolerance = 1e-3;  ///< the largest stretch or squeeze allowed, over the spring's rest length or τ
  int sweeps_per_step = 10;        ///< sweeps after each step at most
  int settle_iterations = 2'000;   ///< sweeps after the last step at most (the bundled patterns need up to 45)

  /// Throws skein::Error naming the option and the rule broken.
  void validate() const;
};

struct Spring {
  int a = 0, b = 0;   ///< grid point indices
  double rest = 0;    ///< length in the flat fabric [mm]
};

/// A stitching spring (Zhou §3): one stitch of a thread.
struct Stitch : Spring {
  int thread = 0;
  bool front = true;
  double bead = 0;  ///< the diameter of a bead on it [mm]: its target never below that (§5.2)
};

enum class EmbedStop { Reached, Stalled, IterationCap };
const char* stop_name(EmbedStop stop);

struct Embedding {
  Eigen::Matrix2Xd rest, positions;  ///< every grid point, flat and embedded [mm]
  std::vector<Spring> fabric;        ///< between grid neighbours (eq. 1b)
  std::vector<Stitch> stitches;      ///< along the threads (eq. 1c)
  double thickness = 0;              ///< τ used [mm]
  double threads_rest = 0, threads = 0;  ///< D(X̄) and D(X) (eq. 2) [mm]
  int iterations = 0;                ///< Algorithm 1's steps (also those after settling, when it went on)
  int settle_iterations = 0;         ///< sweeps of the settling passes
  double stretch_before_settling = 0;  ///< the largest violation of eq. 1b where Algorithm 1 first stopped
  double shrinkage_before_settling = 1;  ///< D(X)/D(X̄) where Algorithm 1 first stopped
  EmbedStop stopped = EmbedStop::Reached;
  double largest_stretch = 0;        ///< max over fabric springs of length / rest - 1 (eq. 1b's upper bound: 0)
  double shortest_fabric = 0;        ///< min over fabric springs of length / τ (eq. 1b's lower bound: 1)
  std::vector<std::pair<double, Eigen::Matrix2Xd>> snapshots;  ///< (fraction reached, positions)
  std::vector<Eigen::Vector2d> history;  ///< (iteration, D(X)/D(X̄)) every EmbedOptions::history_every iterations, from 0 to the last

  double shrinkage() const { return threads_rest > 0 ? threads / threads_rest : 1; }
  /// Eq. 1c's lower bound over D(X̄): the threads pulled taut, every stitch τ long (or its bead's diameter).
  double taut() const {
    double d = 0;
    for (const auto& s : stitches) d += std::max(thickness, s.bead);
    return threads_rest > 0 ? d / threads_rest : 0;
  }
};

/// The mass-spring system of `pattern` (grid springs and stitching springs, Zhou §3).
Embedding make_mass_spring_system(const SmockingPattern& pattern, double thickness);

/// Algorithm 1: from the flat fabric, springs whose targets follow eqs. 4 and 5 (Canadian: stitches target 0,
/// §5.4), damped explicit steps (each followed by EmbedOptions::settle's projection), until D(X) <= γ D(X̄)
/// (eq. 1c), a stall, or the iteration cap.
Embedding embed(const SmockingPattern& pattern, const EmbedOptions& options);

/// §4.2's positional constraints in 3-D [mm], z towards the front: each stitching point at z = 0 (eq. 6), each
/// stitch's midpoint between its ends at -h (front stitch) or +h (back stitch), h from eq. 8.
struct Lift {
  std::vector<int> points;        ///< the stitching points (grid indices), each once
  Eigen::Matrix3Xd point_positions;
  Eigen::Matrix3Xd midpoints;     ///< one per Embedding::stitches entry
};
Lift lift(const Embedding& embedding);

}  // namespace skein::smocking
