// The CUDA relaxer's device side (Leaf 2018 §3.2): float structure-of-arrays buffers, one thread per
// segment, point, patch or pair, the per-term math shared with the CPU reference (yarn_segment.hpp,
// guard_model.hpp, yarn_model.hpp), forces gathered per control point (no atomics on floats), sums in a
// fixed order (a run gives the same bits every time), and one step as a CUDA graph. Every kernel of a step
// reads the device's halt flag first, so a batch of graph launches stops cleanly wherever the step loop
// must hand back to the host (convergence, a stop step, a contact rebuild, a state that is not finite).
#include "cuda/yarn_device.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>

#include "cuda/check.cuh"
#include "relax/guard_model.hpp"
#include "relax/yarn_segment.hpp"

namespace skein::cuda {
namespace {

namespace model = relax::model;
using V = model::Vec3<float>;

constexpr int kThreads = 256;
constexpr int kReduceBlocks = 256;  ///< fixed, so that every sum adds the same partials in the same order
constexpr int kMaxBatch = 64;       ///< steps between read-backs, at most

int blocks_for(long n) { return static_cast<int>(std::max<long>(1, (n + kThreads - 1) / kThreads)); }

/// Device memory of n values; move-only.
template <class T>
class Buffer {
public:
  Buffer() = default;
  ~Buffer() {
    if (m_ptr) cudaFree(m_ptr);
  }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  void resize(size_t n) {
    if (n == m_size) return;
    if (m_ptr) cudaFree(m_ptr);
    m_ptr = nullptr;
    m_size = n;
    if (n > 0) SKEIN_CUDA_CHECK(cudaMalloc(&m_ptr, n * sizeof(T)));
  }
  void upload(const std::vector<T>& host) {
    resize(host.size());
    if (!host.empty()) SKEIN_CUDA_CHECK(cudaMemcpy(m_ptr, host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice));
  }
  std::vector<T> download(size_t n) const {
    std::vector<T> host(n);
    if (n > 0) SKEIN_CUDA_CHECK(cudaMemcpy(host.data(), m_ptr, n * sizeof(T), cudaMemcpyDeviceToHost));
    return host;
  }
  T* get() const { return m_ptr; }
  size_t size() const { return m_size; }

private:
  T* m_ptr = nullptr;
  size_t m_size = 0;
};

/// Three float arrays: x, y and z of every control point.
struct Soa {
  float *x, *y, *z;
  __device__ V operator()(int i) const { return {x[i], y[i], z[i]}; }
  __device__ void store(int i, const V& v) const {
    x[i] = v.x;
    y[i] = v.y;
    z[i] = v.z;
  }
};
struct SoaBuffer {
  Buffer<float> x, y, z;
  void resize(size_t n) {
    x.resize(n);
    y.resize(n);
    z.resize(n);
  }
  Soa view() const { return {x.get(), y.get(), z.get()}; }
  void upload(const Eigen::Matrix3Xd& m) {
    std::vector<float> h[3];
    for (int c = 0; c < 3; ++c) {
      h[c].resize(m.cols());
      for (Eigen::Index i = 0; i < m.cols(); ++i) h[c][i] = static_cast<float>(m(c, i));
    }
    x.upload(h[0]);
    y.upload(h[1]);
    z.upload(h[2]);
  }
  void download(Eigen::Matrix3Xd& m, size_t n) const {
    const std::vector<float> h[3] = {x.download(n), y.download(n), z.download(n)};
    m.resize(3, static_cast<Eigen::Index>(n));
    for (int c = 0; c < 3; ++c)
      for (size_t i = 0; i < n; ++i) m(c, static_cast<Eigen::Index>(i)) = h[c][i];
  }
  void copy_from(const SoaBuffer& o, size_t n) {
    SKEIN_CUDA_CHECK(cudaMemcpy(x.get(), o.x.get(), n * sizeof(float), cudaMemcpyDeviceToDevice));
    SKEIN_CUDA_CHECK(cudaMemcpy(y.get(), o.y.get(), n * sizeof(float), cudaMemcpyDeviceToDevice));
    SKEIN_CUDA_CHECK(cudaMemcpy(z.get(), o.z.get(), n * sizeof(float), cudaMemcpyDeviceToDevice));
  }
};

/// Velocities for Euler's contact damping; FIRE takes none (CPU: yarn_energy without velocities).
struct MaybeVelocity {
  Soa v;
  bool on;
  __device__ V operator()(int i) const { return on ? v(i) : V{0, 0, 0}; }
};

enum GuardMode : int { kNone = 0, kHalve = 1, kHold = 2 };
/// GuardCounters, in its order.
enum Counter : int { kSteps, kRateLimited, kPairsTested, kPairsSkipped, kSphereTests, kFinestHits, kHalvings, kHeldPoints, kCounters };
/// Partial sums: one slot of kReduceBlocks values per quantity.
enum Slot : int { kGrad2, kPower, kVel2, kSegEnergy, kPatchEnergy, kRateMove, kEulerBound, kMoved, kSphereRadius, kSlots };

/// The controller and the step's scalars, in device memory.
struct Scalars {
  long long step, stop_at, log_base;
  double time_step, alpha;
  long positive;
  double residual0, residual_prev, residual, energy;
  double keep, mix, dt, scale, moved_since_rebuild;
  double least;  ///< the smallest factor the guard's halvings left on a point's move in this step
  int halt;  ///< Halt
  int guard_done, guard_mode, hits, hold_all;
  int guard_pairs;
  long long contacts;
  unsigned long long counters[kCounters];
  unsigned long long finest_before, held_before;
};

/// Every device pointer and constant a step needs, passed by value to every kernel.
struct Dev {
  model::SegmentView<float> seg;
  model::SampleView<float> samples;
  model::PairView pairs;
  model::IntrinsicParams<float> intrinsic;
  model::ContactParams<float> contact;
  int num_points, num_segments, num_patches, num_loops, num_groups;
  bool euler;
  Soa x, v, grad, damp, delta, accel, good_x, good_v;
  const float *inv_mass, *damp_coeff;  ///< 1 / m, and k_global m (eq. 11, lumped)
  const int *point_segments_start, *point_segments;
  V *seg_grad, *seg_damp;  ///< 4 per segment
  float* seg_energy;
  // Patch tracking (Yuksel eqs. 6–7): patches as CSR over points, and points as CSR over patches.
  const int *patch_start, *patch_points;
  const float* patch_weights;
  const V *patch_normal, *patch_start_sum;
  const float* patch_weight_sum;
  const int *point_patch_start, *point_patch;
  const float* point_patch_weight;
  V* patch_slope;
  float* patch_energy;
  float k_normal, k_far, threshold, k_tangent;
  // Border loops (eq. 5) and the guard's groups.
  const int *loop_start, *loop_points, *group;
  int *hold, *hold_group;  ///< per point and per group: the last guard round that marked it (round + 1), 0 for none
  // The guard's pairs.
  const int *pair_a, *pair_b;
  float *budget, *new_budget;
  double *pair_travel, *travel;  ///< 8 per pair; per point
  char *hit, *retest;
  bool guard_enabled, safe_bounds;
  int max_depth, max_halvings;
  float limit;  ///< ε r [mm]
  double fire_max_step, tolerance, stall, rebuild_after;
  double* partial;
  Scalars* sc;
  relax::YarnStepLog* logs;
};

/// The sum (or, for moves, which are never negative, the largest) of a slot's partials, in a fixed order.
__device__ double finish(const Dev& d, int slot, bool max) {
  double acc = 0;
  const double* p = d.partial + slot * kReduceBlocks;
  for (int b = 0; b < kReduceBlocks; ++b) acc = max ? fmax(acc, p[b]) : acc + p[b];
  return acc;
}
__device__ double finish_min(const Dev& d, int slot) {
  double acc = INFINITY;
  const double* p = d.partial + slot * kReduceBlocks;
  for (int b = 0; b < kReduceBlocks; ++b) acc = fmin(acc, p[b]);
  return acc;
}

enum class Op { Sum, Max, Min };

/// A fixed grid of kReduceBlocks blocks folds term(i, acc) over [0, n) into N slots of partials.
template <int N, Op op, class Term>
__global__ void k_reduce(Dev d, int n, int slot, Term term) {
  if (d.sc->halt) return;
  const double identity = op == Op::Min ? INFINITY : 0.0;
  double acc[N];
  for (int k = 0; k < N; ++k) acc[k] = identity;
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x) term(d, i, acc);
  __shared__ double shared[kThreads];
  for (int k = 0; k < N; ++k) {
    shared[threadIdx.x] = acc[k];
    __syncthreads();
    for (int s = kThreads / 2; s > 0; s >>= 1) {
      if (threadIdx.x < s) {
        const double a = shared[threadIdx.x], b = shared[threadIdx.x + s];
        shared[threadIdx.x] = op == Op::Sum ? a + b : op == Op::Max ? fmax(a, b) : fmin(a, b);
      }
      __syncthreads();
    }
    if (threadIdx.x == 0) d.partial[(slot + k) * kReduceBlocks + blockIdx.x] = shared[0];
    __syncthreads();
  }
}

struct PointSums {  // |grad|^2, F.v with F = -grad, |v|^2
  __device__ void operator()(const Dev& d, int p, double* acc) const {
    const V g = d.grad(p), v = d.v(p);
    acc[0] += model::dot(g, g);
    acc[1] -= model::dot(g, v);
    acc[2] += model::dot(v, v);
  }
};
struct SegmentEnergy {
  __device__ void operator()(const Dev& d, int s, double* acc) const { acc[0] += d.seg_energy[s]; }
};
struct PatchEnergy {
  __device__ void operator()(const Dev& d, int k, double* acc) const { acc[0] += d.patch_energy[k]; }
};
struct DeltaMove {  // the largest distance a point of the yarn moves with this step's delta
  __device__ void operator()(const Dev& d, int s, double* acc) const {
    acc[0] = fmax(acc[0], static_cast<double>(model::segment_largest_move<float>(d.seg.segment_points, s, d.delta)));
  }
};
struct EulerBound {  // Leaf eq. 2 over the segment's contact samples
  __device__ void operator()(const Dev& d, int s, double* acc) const {
    const int* sp = d.seg.segment_points + 4 * s;
    const int n = d.seg.contact_samples[s];
    for (int i = 0; i < n; ++i) {
      float w[4];
      model::basis(float(i) / float(n - 1), w);
      V u{0, 0, 0}, a{0, 0, 0};
      for (int k = 0; k < 4; ++k) {
        u += d.v(sp[k]) * w[k];
        a += d.accel(sp[k]) * w[k];
      }
      acc[0] = fmin(acc[0], static_cast<double>(model::step_bound(model::norm(u), model::norm(a), d.limit)));
    }
  }
};

#define SKEIN_INDEX(n)                                   \
  const int i = blockIdx.x * blockDim.x + threadIdx.x; \
  if (i >= (n) || d.sc->halt) return;

// ---- forces ----

__global__ void k_samples(Dev d) {
  SKEIN_INDEX(d.num_segments);
  model::segment_samples(d.seg, i, d.x, MaybeVelocity{d.v, d.euler}, d.samples);
}

__global__ void k_segment_forces(Dev d) {
  SKEIN_INDEX(d.num_segments);
  V g[4] = {}, damp[4] = {};
  d.seg_energy[i] = model::segment_forces(d.seg, d.samples, d.pairs, d.intrinsic, d.contact, i, d.x, g, damp);
  for (int k = 0; k < 4; ++k) {
    d.seg_grad[4 * i + k] = g[k];
    d.seg_damp[4 * i + k] = damp[k];
  }
}

__global__ void k_patches(Dev d) {
  SKEIN_INDEX(d.num_patches);
  V sum{0, 0, 0};
  for (int k = d.patch_start[i]; k < d.patch_start[i + 1]; ++k) sum += d.x(d.patch_points[k]) * d.patch_weights[k];
  const V drift = (sum - d.patch_start_sum[i]) * (1.0f / d.patch_weight_sum[i]);  // eq. 7 over the weight sum
  V slope;
  d.patch_energy[i] = model::patch_tracking(drift, d.patch_normal[i], d.patch_weight_sum[i], d.k_normal, d.k_far, d.threshold, d.k_tangent, slope);
  d.patch_slope[i] = slope;
}

/// Per point: the gradient (and Euler's damping) gathered from its segments and patches (Leaf §3.2 stencils).
__global__ void k_gather(Dev d) {
  SKEIN_INDEX(d.num_points);
  V g{0, 0, 0}, damp{0, 0, 0};
  for (int k = d.point_segments_start[i]; k < d.point_segments_start[i + 1]; ++k) {
    const int code = d.point_segments[k];
    g += d.seg_grad[code];  // code = 4 segment + slot
    damp += d.seg_damp[code];
  }
  if (d.num_patches > 0)
    for (int k = d.point_patch_start[i]; k < d.point_patch_start[i + 1]; ++k) g += d.patch_slope[d.point_patch[k]] * d.point_patch_weight[k];
  d.grad.store(i, g);
  if (d.euler) d.damp.store(i, damp - d.v(i) * d.damp_coeff[i]);
}

/// The controller: energy and residual of the current state, rollback, Leaf eq. 5, the stop step, FIRE.
__global__ void k_decide(Dev d) {
  Scalars& sc = *d.sc;
  if (sc.halt) return;
  const double g2 = finish(d, kGrad2, false), power = finish(d, kPower, false), v2 = finish(d, kVel2, false);
  sc.energy = finish(d, kSegEnergy, false) + (d.num_patches > 0 ? finish(d, kPatchEnergy, false) : 0.0);
  const double residual = sqrt(g2);
  if (!isfinite(sc.energy) || !isfinite(residual)) {
    sc.halt = static_cast<int>(Halt::NotFinite);
    return;
  }
  if (sc.residual0 == 0) sc.residual0 = residual;  // a state may bring its own scale
  sc.residual = residual;
  if (model::converged<double>(sc.step, residual, sc.residual0, sc.residual_prev, d.tolerance, d.stall)) {
    sc.halt = static_cast<int>(Halt::Converged);
    return;
  }
  if (sc.step >= sc.stop_at) {
    sc.halt = static_cast<int>(Halt::StopAt);
    return;
  }
  sc.residual_prev = residual;
  if (d.euler) return;  // k_euler_step sets the step
  model::FireControl<double> control{sc.time_step, sc.alpha, sc.positive};
  model::fire_control(power, sqrt(v2), residual, d.fire_max_step, control, sc.keep, sc.mix);
  sc.time_step = control.time_step;
  sc.alpha = control.alpha;
  sc.positive = control.positive;
  sc.dt = sc.time_step;
}

/// The last state whose forces were finite, for a rollback.
__global__ void k_save_good(Dev d) {
  SKEIN_INDEX(d.num_points);
  d.good_x.store(i, d.x(i));
  d.good_v.store(i, d.v(i));
}

__global__ void k_euler_accel(Dev d) {
  SKEIN_INDEX(d.num_points);
  d.accel.store(i, (d.damp(i) - d.grad(i)) * d.inv_mass[i]);
}

__global__ void k_euler_step(Dev d) {
  Scalars& sc = *d.sc;
  if (sc.halt) return;
  sc.dt = fmin(sc.time_step, finish_min(d, kEulerBound));  // Leaf eq. 2
}

/// The integrator's proposed move: semi-implicit Euler, or FIRE with every point clamped to ε r / 1.25.
__global__ void k_integrate(Dev d) {
  SKEIN_INDEX(d.num_points);
  const float dt = static_cast<float>(d.sc->dt);
  V v = d.v(i);
  if (d.euler) {
    v += d.accel(i) * dt;
    d.delta.store(i, v * dt);
    d.v.store(i, v);
    return;
  }
  const V force = d.grad(i) * -1.0f;
  v = v * static_cast<float>(d.sc->keep) + force * static_cast<float>(d.sc->mix);
  v += force * (dt * d.inv_mass[i]);
  V delta = v * dt;
  // Catmull-Rom: sum |b| <= 1.25, so no sample moves more than ε r.
  const float clamp = d.limit / 1.25f, m = model::norm(delta);
  if (m > clamp) {
    delta = delta * (clamp / m);
    v = delta * (1.0f / dt);
  }
  d.delta.store(i, delta);
  d.v.store(i, v);
}

/// Eq. 5 as a projection: each border loop's mean displacement is removed.
__global__ void k_boundary(Dev d) {
  SKEIN_INDEX(d.num_loops);
  V mean{0, 0, 0};
  const int begin = d.loop_start[i], end = d.loop_start[i + 1];
  for (int k = begin; k < end; ++k) mean += d.delta(d.loop_points[k]);
  mean = mean * (1.0f / static_cast<float>(end - begin));
  for (int k = begin; k < end; ++k) d.delta.store(d.loop_points[k], d.delta(d.loop_points[k]) - mean);
}

// ---- the pull-through guard (PullThroughGuard::accept, step for step) ----

__global__ void k_guard_begin(Dev d) {
  Scalars& sc = *d.sc;
  if (sc.halt) return;
  ++sc.counters[kSteps];
  const double largest = finish(d, kRateMove, true);
  sc.scale = 1;
  sc.least = 1;
  if (largest > d.limit) {
    ++sc.counters[kRateLimited];
    sc.scale = d.limit / largest;
  }
  sc.guard_done = d.guard_enabled ? 0 : 1;
  sc.guard_mode = kNone;
  sc.hits = 0;
  sc.hold_all = 0;
  sc.finest_before = sc.counters[kFinestHits];
  sc.held_before = sc.counters[kHeldPoints];
}

/// The movement limit applied, holds cleared; every pair to be tested.
__global__ void k_guard_prepare(Dev d, int capacity) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (d.sc->halt) return;
  if (i < d.num_points) {
    if (d.sc->scale < 1) d.delta.store(i, d.delta(i) * static_cast<float>(d.sc->scale));
    d.hold[i] = 0;
  }
  if (i < d.num_groups) d.hold_group[i] = 0;
  if (i < capacity && i < d.sc->guard_pairs) {
    d.retest[i] = 1;
    d.hit[i] = 0;
    d.new_budget[i] = -1;
  }
}

__device__ void pair_points(const Dev& d, int i, int out[8]) {
  for (int k = 0; k < 4; ++k) {
    out[k] = d.seg.segment_points[4 * d.pair_a[i] + k];
    out[4 + k] = d.seg.segment_points[4 * d.pair_b[i] + k];
  }
}

/// One round: the hierarchical swept-sphere test of every pair still to be tested.
__global__ void k_guard_test(Dev d) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  Scalars& sc = *d.sc;
  if (sc.halt || sc.guard_done || i >= sc.guard_pairs || !d.retest[i]) return;
  d.hit[i] = 0;
  d.new_budget[i] = -1;
  int p[8];
  pair_points(d, i, p);
  float move[8];
  bool still = true;
  for (int k = 0; k < 8; ++k) {
    move[k] = model::norm(d.delta(p[k]));
    still = still && move[k] == 0;
  }
  if (still) return;  // neither segment moves: they cannot pass through each other
  if (d.safe_bounds && d.budget[i] >= 0) {
    bool inside = true;
    for (int k = 0; k < 8 && inside; ++k) inside = d.travel[p[k]] + move[k] - d.pair_travel[8 * i + k] < d.budget[i];
    if (inside) {
      atomicAdd(&sc.counters[kPairsSkipped], 1ull);
      return;
    }
  }
  atomicAdd(&sc.counters[kPairsTested], 1ull);
  // About one of the pair's points, so that float keeps its precision for the small distances that matter.
  const V origin = d.x(p[1]);
  V a0[4], a1[4], b0[4], b1[4];
  for (int k = 0; k < 4; ++k) {
    a0[k] = d.x(p[k]) - origin;
    a1[k] = a0[k] + d.delta(p[k]);
    b0[k] = d.x(p[4 + k]) - origin;
    b1[k] = b0[k] + d.delta(p[4 + k]);
  }
  float gap;
  long tests = 0;
  const bool meet = model::pieces_meet(a0, a1, b0, b1, d.max_depth, gap, tests);
  atomicAdd(&sc.counters[kSphereTests], static_cast<unsigned long long>(tests));
  if (meet) {
    d.hit[i] = 1;
    atomicAdd(&sc.hits, 1);
  } else if (gap > 0 && isfinite(gap)) {
    d.new_budget[i] = gap / 8;  // Yuksel eq. 9, d_i = d/8
  }
}

/// After a round: done, or halve the moves of the points of the pairs still hit, or hold those points, or (out of
/// rounds) hold all.
__global__ void k_guard_decide(Dev d, int round) {
  Scalars& sc = *d.sc;
  if (sc.halt || sc.guard_done) return;
  sc.guard_mode = kNone;
  const model::GuardRound action = model::guard_round(round, sc.hits, d.max_halvings);  // the CPU guard's policy
  if (action == model::GuardRound::Done) {
    sc.guard_done = 1;
    return;
  }
  sc.counters[kFinestHits] += sc.hits;
  sc.hits = 0;
  if (action == model::GuardRound::Halve) {
    ++sc.counters[kHalvings];
    sc.least *= 0.5;
    sc.guard_mode = kHalve;
  } else if (action == model::GuardRound::Hold) {
    sc.guard_mode = kHold;
  } else {
    sc.hold_all = 1;  // k_commit holds every point for this step
    sc.guard_done = 1;
  }
}

/// The points of the pairs still hit, and their groups, marked with the round's stamp (round + 1): only their
/// moves change in this round.
__global__ void k_guard_mark(Dev d, int capacity, int round) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  const Scalars& sc = *d.sc;
  if (sc.halt || sc.guard_done || sc.guard_mode == kNone || i >= capacity || i >= sc.guard_pairs || !d.hit[i]) return;
  int p[8];
  pair_points(d, i, p);
  for (int k = 0; k < 8; ++k) {
    d.hold[p[k]] = round + 1;
    if (d.group[p[k]] >= 0) d.hold_group[d.group[p[k]]] = round + 1;
  }
}

/// Halves or holds the marked points' moves; the rest of the yarn keeps its whole step.
__global__ void k_guard_points(Dev d, int round) {
  SKEIN_INDEX(d.num_points);
  const Scalars& sc = *d.sc;
  if (sc.guard_done || sc.guard_mode == kNone) return;
  if (d.hold[i] != round + 1 && !(d.group[i] >= 0 && d.hold_group[d.group[i]] == round + 1)) return;
  d.hold[i] = round + 1;
  const V delta = d.delta(i);
  if (sc.guard_mode == kHalve) {
    // Each point moves on a straight line, so a halved move is the first half of the same path.
    d.delta.store(i, delta * 0.5f);
    return;
  }
  if (model::dot(delta, delta) > 0) atomicAdd(&d.sc->counters[kHeldPoints], 1ull);
  d.delta.store(i, V{0, 0, 0});
}

/// Pairs of unmarked points keep their paths and stay clean; pairs with a point marked in this round are tested
/// again.
__global__ void k_guard_pairs(Dev d, int capacity, int round) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  const Scalars& sc = *d.sc;
  if (sc.halt || sc.guard_done || sc.guard_mode == kNone || i >= capacity || i >= sc.guard_pairs) return;
  int p[8];
  pair_points(d, i, p);
  char any = 0;
  for (int k = 0; k < 8; ++k) any |= static_cast<char>(d.hold[p[k]] == round + 1);
  d.retest[i] = any;
}

// ---- commit ----

__global__ void k_commit(Dev d) {
  SKEIN_INDEX(d.num_points);
  const Scalars& sc = *d.sc;
  V delta = d.delta(i);
  if (sc.hold_all) {
    if (model::dot(delta, delta) > 0) atomicAdd(&d.sc->counters[kHeldPoints], 1ull);
    delta = V{0, 0, 0};
    d.delta.store(i, delta);
  }
  d.travel[i] += model::norm(delta);
  d.x.store(i, d.x(i) + delta);
  // The velocity that matches the move the guard let through.
  if (sc.hold_all || sc.scale * sc.least < 1) d.v.store(i, delta * static_cast<float>(1.0 / sc.dt));
}

/// Clean pairs restart their safe bounds from here (none when every point was held: the bounds were measured on
/// the moves proposed).
__global__ void k_commit_budgets(Dev d, int capacity) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (d.sc->halt || d.sc->hold_all || !d.guard_enabled || !d.safe_bounds || i >= capacity || i >= d.sc->guard_pairs || d.new_budget[i] < 0) return;
  d.budget[i] = d.new_budget[i];
  int p[8];
  pair_points(d, i, p);
  for (int k = 0; k < 8; ++k) d.pair_travel[8 * i + k] = d.travel[p[k]];
}

__global__ void k_end_step(Dev d) {
  Scalars& sc = *d.sc;
  if (sc.halt) return;
  const double moved = finish(d, kMoved, true);
  const long long index = sc.step - sc.log_base;
  ++sc.step;
  if (index >= 0 && index < kMaxBatch) {
    relax::YarnStepLog& log = d.logs[index];
    log.step = sc.step;
    log.energy = sc.energy;
    log.residual = sc.residual / sc.residual0;
    log.time_step = sc.hold_all ? 0.0 : sc.dt * sc.scale * sc.least;
    log.moved = moved;
    log.contacts = sc.contacts;
    log.guard_hits = static_cast<long>(sc.counters[kFinestHits] - sc.finest_before);
    log.held_points = static_cast<long>(sc.counters[kHeldPoints] - sc.held_before);
    log.crossings = 0;
    log.awake = d.num_points;
  }
  sc.moved_since_rebuild += moved;
  if (sc.moved_since_rebuild >= d.rebuild_after) sc.halt = static_cast<int>(Halt::Rebuild);
}

// ---- contact pairs (find_contact_pairs on the GPU) ----

struct SphereRadius {
  __device__ void operator()(const Dev& d, int s, double* acc) const;
};

__device__ void segment_sphere(const Dev& d, int s, V& centre, float& radius) {
  V p[4];
  for (int k = 0; k < 4; ++k) p[k] = d.x(d.seg.segment_points[4 * s + k]);
  model::bezier_sphere(p, 0.0f, 1.0f, centre, radius);
}

__device__ void SphereRadius::operator()(const Dev& d, int s, double* acc) const {
  V c;
  float r;
  segment_sphere(d, s, c, r);
  acc[0] = fmax(acc[0], static_cast<double>(r));
}

__device__ long long cell_coord(float v, float cell) { return static_cast<long long>(floorf(v / cell)); }
__device__ std::uint64_t cell_key(long long cx, long long cy, long long cz) {
  const auto part = [](long long v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v + (1 << 20)) & 0x1fffff); };
  return (part(cx) << 42) | (part(cy) << 21) | part(cz);
}

__global__ void k_spheres(Dev d, float4* spheres, std::uint64_t* keys, int* ids, float cell) {
  const int s = blockIdx.x * blockDim.x + threadIdx.x;
  if (s >= d.num_segments) return;
  V c;
  float r;
  segment_sphere(d, s, c, r);
  spheres[s] = make_float4(c.x, c.y, c.z, r);
  keys[s] = cell_key(cell_coord(c.x, cell), cell_coord(c.y, cell), cell_coord(c.z, cell));
  ids[s] = s;
}

/// Segment s's partners among the 27 cells around its own (sorted keys, binary search); with `out`, writes
/// them in increasing order; returns their number.
__device__ int partners(const Dev& d, int s, const float4* spheres, const std::uint64_t* keys, const int* ids, float cell, float reach, int* out) {
  const float4 a = spheres[s];
  const long long cx = cell_coord(a.x, cell), cy = cell_coord(a.y, cell), cz = cell_coord(a.z, cell);
  int count = 0;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const std::uint64_t key = cell_key(cx + dx, cy + dy, cz + dz);
        int lo = 0, hi = d.num_segments;
        while (lo < hi) {
          const int mid = (lo + hi) / 2;
          if (keys[mid] < key) lo = mid + 1;
          else hi = mid;
        }
        for (int j = lo; j < d.num_segments && keys[j] == key; ++j) {
          const int t = ids[j];
          const float4 b = spheres[t];
          const float dist = sqrtf((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
          if (model::consecutive(d.seg, s, t) || !(dist - a.w - b.w < reach)) continue;
          if (out) {
            int k = count;  // insertion sort: partners in increasing order, as on the CPU
            while (k > 0 && out[k - 1] > t) {
              out[k] = out[k - 1];
              --k;
            }
            out[k] = t;
          }
          ++count;
        }
      }
  return count;
}

__global__ void k_count_partners(Dev d, const float4* spheres, const std::uint64_t* keys, const int* ids, float cell, float reach, int* counts) {
  const int s = blockIdx.x * blockDim.x + threadIdx.x;
  if (s < d.num_segments) counts[s] = partners(d, s, spheres, keys, ids, cell, reach, nullptr);
}

__global__ void k_fill_partners(Dev d, const float4* spheres, const std::uint64_t* keys, const int* ids, float cell, float reach, const int* start,
                                int* partner) {
  const int s = blockIdx.x * blockDim.x + threadIdx.x;
  if (s < d.num_segments) partners(d, s, spheres, keys, ids, cell, reach, partner + start[s]);
}

/// The guard watches pairs (a < b) that are not one piece of yarn (PullThroughGuard::reset).
__global__ void k_count_guard_pairs(Dev d, const int* start, const int* partner, int* counts) {
  const int s = blockIdx.x * blockDim.x + threadIdx.x;
  if (s >= d.num_segments) return;
  int n = 0;
  for (int k = start[s]; k < start[s + 1]; ++k) n += partner[k] > s && !model::adjacent(d.seg, s, partner[k]);
  counts[s] = n;
}

__global__ void k_fill_guard_pairs(Dev d, const int* start, const int* partner, const int* guard_start, int* pair_a, int* pair_b, float* budget) {
  const int s = blockIdx.x * blockDim.x + threadIdx.x;
  if (s >= d.num_segments) return;
  int out = guard_start[s];
  for (int k = start[s]; k < start[s + 1]; ++k)
    if (partner[k] > s && !model::adjacent(d.seg, s, partner[k])) {
      pair_a[out] = s;
      pair_b[out] = partner[k];
      budget[out] = -1;  // no safe bound yet: tested at the next step
      ++out;
    }
}

/// counts[0..n) -> start[0..n]: start[0] = 0, start[s+1] = counts[0] + .. + counts[s].
void exclusive_offsets(const int* counts, int* start, int n, Buffer<char>& scratch, cudaStream_t stream) {
  size_t bytes = 0;
  SKEIN_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, bytes, counts, start + 1, n, stream));
  if (scratch.size() < bytes) scratch.resize(bytes);
  bytes = scratch.size();
  SKEIN_CUDA_CHECK(cub::DeviceScan::InclusiveSum(scratch.get(), bytes, counts, start + 1, n, stream));
  SKEIN_CUDA_CHECK(cudaMemsetAsync(start, 0, sizeof(int), stream));
}

/// Grows `buffer` to hold n values with room to spare; returns true when it moved (graphs must be captured again).
template <class T>
bool reserve(Buffer<T>& buffer, size_t n) {
  if (buffer.size() >= n && buffer.size() > 0) return false;
  buffer.resize(std::max<size_t>(n + n / 4, 64));
  return true;
}

}  // namespace

struct DeviceYarn::Impl {
  relax::YarnRelaxOptions options;
  int points = 0, segments = 0, patches = 0, loops = 0, samples = 0;
  double radius = 0;
  cudaStream_t stream = nullptr;
  cudaGraphExec_t graph = nullptr;

  // The system (read-only).
  Buffer<int> segment_points, segment_curve, curve_start, contact_samples, sample_start, point_segments_start, point_segments;
  Buffer<float> rest_length, arc_start, curve_length, inv_mass, damp_coeff;
  Buffer<char> closed;
  // Shape targets.
  Buffer<int> patch_start, patch_points, point_patch_start, point_patch, loop_start, loop_points, group, hold, hold_group;
  Buffer<float> patch_weights, patch_weight_sum, point_patch_weight, patch_energy;
  Buffer<V> patch_normal, patch_start_sum, patch_slope;
  // State and per-step scratch.
  SoaBuffer x, v, grad, damp, delta, accel, good_x, good_v;
  Buffer<V> sample_pos, sample_vel, seg_grad, seg_damp;
  Buffer<float> sample_weight, sample_arc, seg_energy;
  Buffer<double> travel, partial;
  // Contacts and the guard's pairs.
  Buffer<int> pair_start, partner, pair_count, guard_start, pair_a, pair_b, sorted_ids, ids;
  Buffer<std::uint64_t> keys, sorted_keys;
  Buffer<float4> spheres;
  Buffer<float> budget, new_budget;
  Buffer<double> pair_travel;
  Buffer<char> hit, retest, scratch;
  Buffer<Scalars> scalars;
  Buffer<relax::YarnStepLog> logs;

  ~Impl() {
    if (graph) cudaGraphExecDestroy(graph);
    if (stream) cudaStreamDestroy(stream);
  }

  int guard_capacity() const { return static_cast<int>(pair_a.size()); }

  Dev view() const {
    Dev d{};
    d.seg = {segment_points.get(), segment_curve.get(), curve_start.get(), rest_length.get(), arc_start.get(), curve_length.get(), closed.get(),
             contact_samples.get(), sample_start.get(), static_cast<float>(radius)};
    d.samples = {sample_pos.get(), sample_vel.get(), sample_weight.get(), sample_arc.get()};
    d.pairs = {pair_start.get(), partner.get()};
    const auto& p = options.params;
    d.euler = options.method == relax::YarnMethod::Euler;
    d.intrinsic = {static_cast<float>(p.k_bend), static_cast<float>(p.k_stretch), static_cast<float>(p.k_length)};
    d.contact = {static_cast<float>(p.k_contact), d.euler ? static_cast<float>(p.k_dt) : 0.0f, d.euler ? static_cast<float>(p.k_dn) : 0.0f,
                 static_cast<float>(radius), static_cast<float>(p.contact_soft)};
    d.num_points = points;
    d.num_segments = segments;
    d.num_patches = patches;
    d.num_loops = loops;
    d.num_groups = loops;
    d.x = x.view();
    d.v = v.view();
    d.grad = grad.view();
    d.damp = damp.view();
    d.delta = delta.view();
    d.accel = accel.view();
    d.good_x = good_x.view();
    d.good_v = good_v.view();
    d.inv_mass = inv_mass.get();
    d.damp_coeff = damp_coeff.get();
    d.point_segments_start = point_segments_start.get();
    d.point_segments = point_segments.get();
    d.seg_grad = seg_grad.get();
    d.seg_damp = seg_damp.get();
    d.seg_energy = seg_energy.get();
    d.patch_start = patch_start.get();
    d.patch_points = patch_points.get();
    d.patch_weights = patch_weights.get();
    d.patch_normal = patch_normal.get();
    d.patch_start_sum = patch_start_sum.get();
    d.patch_weight_sum = patch_weight_sum.get();
    d.point_patch_start = point_patch_start.get();
    d.point_patch = point_patch.get();
    d.point_patch_weight = point_patch_weight.get();
    d.patch_slope = patch_slope.get();
    d.patch_energy = patch_energy.get();
    const auto& shape = options.shape;
    d.k_normal = static_cast<float>(shape.k_normal);
    d.k_far = static_cast<float>(shape.k_normal_far);
    d.threshold = static_cast<float>(shape.normal_threshold * radius);
    d.k_tangent = static_cast<float>(shape.k_tangent);
    d.loop_start = loop_start.get();
    d.loop_points = loop_points.get();
    d.group = group.get();
    d.hold = hold.get();
    d.hold_group = hold_group.get();
    d.pair_a = pair_a.get();
    d.pair_b = pair_b.get();
    d.budget = budget.get();
    d.new_budget = new_budget.get();
    d.pair_travel = pair_travel.get();
    d.travel = travel.get();
    d.hit = hit.get();
    d.retest = retest.get();
    d.guard_enabled = options.guard.enabled;
    d.safe_bounds = options.guard.safe_bounds;
    d.max_depth = options.guard.max_depth;
    d.max_halvings = options.guard.max_halvings;
    d.limit = static_cast<float>(options.guard.max_move * radius);
    d.fire_max_step = options.fire_max_step;
    d.tolerance = options.tolerance;
    d.stall = options.stall;
    d.rebuild_after = 0.5 * options.contact_margin * radius;
    d.partial = partial.get();
    d.sc = scalars.get();
    d.logs = logs.get();
    return d;
  }

  /// One step's kernels on `stream` (captured into the graph).
  void enqueue_step() {
    const Dev d = view();
    const int pb = blocks_for(points), sb = blocks_for(segments), gb = blocks_for(guard_capacity());
    k_samples<<<sb, kThreads, 0, stream>>>(d);
    k_segment_forces<<<sb, kThreads, 0, stream>>>(d);
    if (patches > 0) k_patches<<<blocks_for(patches), kThreads, 0, stream>>>(d);
    k_gather<<<pb, kThreads, 0, stream>>>(d);
    k_reduce<3, Op::Sum><<<kReduceBlocks, kThreads, 0, stream>>>(d, points, kGrad2, PointSums{});
    k_reduce<1, Op::Sum><<<kReduceBlocks, kThreads, 0, stream>>>(d, segments, kSegEnergy, SegmentEnergy{});
    if (patches > 0) k_reduce<1, Op::Sum><<<kReduceBlocks, kThreads, 0, stream>>>(d, patches, kPatchEnergy, PatchEnergy{});
    k_decide<<<1, 1, 0, stream>>>(d);
    k_save_good<<<pb, kThreads, 0, stream>>>(d);
    if (d.euler) {
      k_euler_accel<<<pb, kThreads, 0, stream>>>(d);
      k_reduce<1, Op::Min><<<kReduceBlocks, kThreads, 0, stream>>>(d, segments, kEulerBound, EulerBound{});
      k_euler_step<<<1, 1, 0, stream>>>(d);
    }
    k_integrate<<<pb, kThreads, 0, stream>>>(d);
    if (loops > 0) k_boundary<<<blocks_for(loops), kThreads, 0, stream>>>(d);
    k_reduce<1, Op::Max><<<kReduceBlocks, kThreads, 0, stream>>>(d, segments, kRateMove, DeltaMove{});
    k_guard_begin<<<1, 1, 0, stream>>>(d);
    k_guard_prepare<<<blocks_for(std::max({points, loops, guard_capacity()})), kThreads, 0, stream>>>(d, guard_capacity());
    if (options.guard.enabled)
      for (int round = 0; round <= options.guard.max_halvings + model::kGuardHoldRounds; ++round) {
        k_guard_test<<<gb, kThreads, 0, stream>>>(d);
        k_guard_decide<<<1, 1, 0, stream>>>(d, round);
        k_guard_mark<<<gb, kThreads, 0, stream>>>(d, guard_capacity(), round);
        k_guard_points<<<pb, kThreads, 0, stream>>>(d, round);
        k_guard_pairs<<<gb, kThreads, 0, stream>>>(d, guard_capacity(), round);
      }
    k_commit<<<pb, kThreads, 0, stream>>>(d);
    k_commit_budgets<<<gb, kThreads, 0, stream>>>(d, guard_capacity());
    k_reduce<1, Op::Max><<<kReduceBlocks, kThreads, 0, stream>>>(d, segments, kMoved, DeltaMove{});
    k_end_step<<<1, 1, 0, stream>>>(d);
    SKEIN_CUDA_CHECK(cudaGetLastError());
  }

  void capture() {
    if (graph) return;
    cudaGraph_t g = nullptr;
    SKEIN_CUDA_CHECK(cudaStreamBeginCapture(stream, cudaStreamCaptureModeThreadLocal));
    enqueue_step();
    SKEIN_CUDA_CHECK(cudaStreamEndCapture(stream, &g));
    const cudaError_t made = cudaGraphInstantiate(&graph, g, 0);
    cudaGraphDestroy(g);
    SKEIN_CUDA_CHECK(made);
  }

  void invalidate_graph() {
    if (graph) cudaGraphExecDestroy(graph);
    graph = nullptr;
  }

  Scalars read_scalars() const {
    Scalars s;
    SKEIN_CUDA_CHECK(cudaStreamSynchronize(stream));
    SKEIN_CUDA_CHECK(cudaMemcpy(&s, scalars.get(), sizeof s, cudaMemcpyDeviceToHost));
    return s;
  }
  void write_scalars(const Scalars& s) { SKEIN_CUDA_CHECK(cudaMemcpy(scalars.get(), &s, sizeof s, cudaMemcpyHostToDevice)); }
};

DeviceYarn::DeviceYarn(const relax::YarnSystem& system, const relax::ShapeTargets& targets, const relax::YarnRelaxOptions& options)
    : m(std::make_unique<Impl>()) {
  Impl& d = *m;
  d.options = options;
  d.points = system.num_points();
  d.segments = system.num_segments();
  d.radius = system.radius;
  d.samples = system.sample_start.back() + system.contact_samples.back();
  // A blocking stream: the plain cudaMemcpy calls (legacy default stream) stay ordered with its kernels.
  SKEIN_CUDA_CHECK(cudaStreamCreate(&d.stream));
  const auto to_float = [](const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); };
  std::vector<int> flat_points;
  for (const auto& sp : system.segment_points) flat_points.insert(flat_points.end(), sp.begin(), sp.end());
  d.segment_points.upload(flat_points);
  d.segment_curve.upload(system.segment_curve);
  d.curve_start.upload(system.curve_start);
  d.contact_samples.upload(system.contact_samples);
  d.sample_start.upload(system.sample_start);
  d.point_segments_start.upload(system.point_segments_start);
  d.point_segments.upload(system.point_segments);
  d.rest_length.upload(to_float(system.rest_length));
  d.arc_start.upload(to_float(system.arc_start));
  d.curve_length.upload(to_float(system.curve_length));
  d.closed.upload(system.closed);
  std::vector<float> inv_mass(d.points), damp_coeff(d.points);
  for (int p = 0; p < d.points; ++p) {
    const double mass = system.mass[p] * options.params.density;
    inv_mass[p] = static_cast<float>(1 / mass);
    damp_coeff[p] = static_cast<float>(options.params.k_global * mass);
  }
  d.inv_mass.upload(inv_mass);
  d.damp_coeff.upload(damp_coeff);

  // Patches as CSR over points, and the transpose for the per-point gather.
  d.patches = static_cast<int>(targets.patches.size());
  std::vector<int> patch_start{0}, patch_points;
  std::vector<float> patch_weights, weight_sum;
  std::vector<V> normal, start_sum;
  std::vector<std::vector<std::pair<int, float>>> of_point(d.points);
  for (int k = 0; k < d.patches; ++k) {
    const auto& patch = targets.patches[k];
    for (size_t i = 0; i < patch.points.size(); ++i) {
      patch_points.push_back(patch.points[i]);
      patch_weights.push_back(static_cast<float>(patch.weights[i]));
      of_point[patch.points[i]].emplace_back(k, static_cast<float>(patch.weights[i]));
    }
    patch_start.push_back(static_cast<int>(patch_points.size()));
    normal.push_back({static_cast<float>(patch.normal.x()), static_cast<float>(patch.normal.y()), static_cast<float>(patch.normal.z())});
    start_sum.push_back({static_cast<float>(patch.start_sum.x()), static_cast<float>(patch.start_sum.y()), static_cast<float>(patch.start_sum.z())});
    weight_sum.push_back(static_cast<float>(patch.weight_sum));
  }
  std::vector<int> point_patch_start{0}, point_patch;
  std::vector<float> point_patch_weight;
  for (const auto& list : of_point) {
    for (const auto& [k, w] : list) {
      point_patch.push_back(k);
      point_patch_weight.push_back(w);
    }
    point_patch_start.push_back(static_cast<int>(point_patch.size()));
  }
  d.patch_start.upload(patch_start);
  d.patch_points.upload(patch_points);
  d.patch_weights.upload(patch_weights);
  d.patch_normal.upload(normal);
  d.patch_start_sum.upload(start_sum);
  d.patch_weight_sum.upload(weight_sum);
  d.point_patch_start.upload(point_patch_start);
  d.point_patch.upload(point_patch);
  d.point_patch_weight.upload(point_patch_weight);
  d.patch_slope.resize(std::max(d.patches, 1));
  d.patch_energy.resize(std::max(d.patches, 1));

  // Border loops: the projection of eq. 5 and the guard's hold groups.
  d.loops = static_cast<int>(targets.boundary_loops.size());
  std::vector<int> loop_start{0}, loop_points, group(d.points, -1);
  for (int l = 0; l < d.loops; ++l) {
    for (int p : targets.boundary_loops[l]) {
      loop_points.push_back(p);
      group[p] = l;
    }
    loop_start.push_back(static_cast<int>(loop_points.size()));
  }
  d.loop_start.upload(loop_start);
  d.loop_points.upload(loop_points);
  d.group.upload(group);
  d.hold.resize(d.points);
  d.hold_group.resize(std::max(d.loops, 1));

  for (auto* b : {&d.x, &d.v, &d.grad, &d.damp, &d.delta, &d.accel, &d.good_x, &d.good_v}) b->resize(d.points);
  d.sample_pos.resize(d.samples);
  d.sample_vel.resize(d.samples);
  d.sample_weight.resize(d.samples);
  d.sample_arc.resize(d.samples);
  d.seg_grad.resize(4 * static_cast<size_t>(d.segments));
  d.seg_damp.resize(4 * static_cast<size_t>(d.segments));
  d.seg_energy.resize(d.segments);
  d.travel.resize(d.points);
  d.partial.resize(kSlots * kReduceBlocks);
  d.pair_start.resize(d.segments + 1);
  d.pair_count.resize(d.segments);
  d.guard_start.resize(d.segments + 1);
  d.keys.resize(d.segments);
  d.sorted_keys.resize(d.segments);
  d.ids.resize(d.segments);
  d.sorted_ids.resize(d.segments);
  d.spheres.resize(d.segments);
  d.scalars.resize(1);
  d.logs.resize(kMaxBatch);
  SKEIN_CUDA_CHECK(cudaMemset(d.scalars.get(), 0, sizeof(Scalars)));
}

DeviceYarn::~DeviceYarn() = default;

namespace {
/// The controller between the device's scalars and a YarnState: into the scalars from a const state, out of
/// them into a mutable one.
template <class State>
void exchange(Scalars& s, State& state) {
  constexpr bool to_device = std::is_const_v<State>;
  const auto move = [](auto& device, auto& host) {
    if constexpr (to_device) device = static_cast<std::remove_reference_t<decltype(device)>>(host);
    else host = static_cast<std::remove_cvref_t<decltype(host)>>(device);
  };
  move(s.step, state.step);
  move(s.time_step, state.time_step);
  move(s.alpha, state.fire_alpha);
  move(s.positive, state.fire_positive);
  move(s.residual0, state.residual0);
  move(s.residual_prev, state.residual_prev);
  auto& g = state.guard;  // GuardCounters, in Counter order
  decltype(&g.steps) counters[kCounters] = {&g.steps, &g.rate_limited, &g.pairs_tested, &g.pairs_skipped, &g.sphere_tests, &g.finest_hits, &g.halvings, &g.held_points};
  for (int k = 0; k < kCounters; ++k) move(s.counters[k], *counters[k]);
}
}  // namespace

void DeviceYarn::set_state(const relax::YarnState& state) {
  m->x.upload(state.points);
  m->v.upload(state.velocities);
  m->good_x.copy_from(m->x, m->points);
  m->good_v.copy_from(m->v, m->points);
  Scalars s{};
  exchange(s, state);
  m->write_scalars(s);
}

void DeviceYarn::get_state(relax::YarnState& state) const {
  Scalars s = m->read_scalars();
  m->x.download(state.points, m->points);
  m->v.download(state.velocities, m->points);
  exchange(s, state);
}

void DeviceYarn::get_points(Eigen::Matrix3Xd& points) const {
  SKEIN_CUDA_CHECK(cudaStreamSynchronize(m->stream));
  m->x.download(points, m->points);
}

long DeviceYarn::rebuild_contacts() {
  Impl& d = *m;
  cudaStream_t st = d.stream;
  Dev view = d.view();
  const int n = d.segments, sb = blocks_for(n);
  // The largest segment sphere sets the cell: two spheres close enough lie in neighbouring cells.
  SKEIN_CUDA_CHECK(cudaStreamSynchronize(st));
  Scalars s = d.read_scalars();
  const int halt = s.halt;
  s.halt = 0;  // the reduction kernels run only while the device is not halted
  d.write_scalars(s);
  k_reduce<1, Op::Max><<<kReduceBlocks, kThreads, 0, st>>>(view, n, kSphereRadius, SphereRadius{});
  SKEIN_CUDA_CHECK(cudaGetLastError());
  SKEIN_CUDA_CHECK(cudaStreamSynchronize(st));
  const auto partial = d.partial.download(kSlots * kReduceBlocks);
  double largest = 0;
  for (int b = 0; b < kReduceBlocks; ++b) largest = std::max(largest, partial[kSphereRadius * kReduceBlocks + b]);
  const double reach = 2 * d.radius + d.options.contact_margin * d.radius;
  const float cell = static_cast<float>(2 * largest + reach);
  k_spheres<<<sb, kThreads, 0, st>>>(view, d.spheres.get(), d.keys.get(), d.ids.get(), cell);
  SKEIN_CUDA_CHECK(cudaGetLastError());
  size_t bytes = 0;
  SKEIN_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, d.keys.get(), d.sorted_keys.get(), d.ids.get(), d.sorted_ids.get(), n, 0, 64, st));
  if (d.scratch.size() < bytes) d.scratch.resize(bytes);
  bytes = d.scratch.size();
  SKEIN_CUDA_CHECK(
      cub::DeviceRadixSort::SortPairs(d.scratch.get(), bytes, d.keys.get(), d.sorted_keys.get(), d.ids.get(), d.sorted_ids.get(), n, 0, 64, st));
  k_count_partners<<<sb, kThreads, 0, st>>>(view, d.spheres.get(), d.sorted_keys.get(), d.sorted_ids.get(), cell, static_cast<float>(reach),
                                           d.pair_count.get());
  SKEIN_CUDA_CHECK(cudaGetLastError());
  exclusive_offsets(d.pair_count.get(), d.pair_start.get(), n, d.scratch, st);
  int total = 0;
  SKEIN_CUDA_CHECK(cudaMemcpyAsync(&total, d.pair_start.get() + n, sizeof total, cudaMemcpyDeviceToHost, st));
  SKEIN_CUDA_CHECK(cudaStreamSynchronize(st));
  if (reserve(d.partner, total)) d.invalidate_graph();
  view = d.view();
  k_fill_partners<<<sb, kThreads, 0, st>>>(view, d.spheres.get(), d.sorted_keys.get(), d.sorted_ids.get(), cell, static_cast<float>(reach),
                                          d.pair_start.get(), d.partner.get());
  k_count_guard_pairs<<<sb, kThreads, 0, st>>>(view, d.pair_start.get(), d.partner.get(), d.pair_count.get());
  SKEIN_CUDA_CHECK(cudaGetLastError());
  exclusive_offsets(d.pair_count.get(), d.guard_start.get(), n, d.scratch, st);
  int guard_total = 0;
  SKEIN_CUDA_CHECK(cudaMemcpyAsync(&guard_total, d.guard_start.get() + n, sizeof guard_total, cudaMemcpyDeviceToHost, st));
  SKEIN_CUDA_CHECK(cudaStreamSynchronize(st));
  bool moved = reserve(d.pair_a, guard_total);
  moved |= reserve(d.pair_b, guard_total);
  moved |= reserve(d.budget, guard_total);
  moved |= reserve(d.new_budget, guard_total);
  moved |= reserve(d.hit, guard_total);
  moved |= reserve(d.retest, guard_total);
  moved |= reserve(d.pair_travel, 8 * static_cast<size_t>(guard_total));
  if (moved) d.invalidate_graph();
  view = d.view();
  k_fill_guard_pairs<<<sb, kThreads, 0, st>>>(view, d.pair_start.get(), d.partner.get(), d.guard_start.get(), d.pair_a.get(), d.pair_b.get(),
                                             d.budget.get());
  SKEIN_CUDA_CHECK(cudaGetLastError());
  // Every safe bound starts afresh, so travel may too (a resumed run starts from zero as well).
  SKEIN_CUDA_CHECK(cudaMemsetAsync(d.travel.get(), 0, d.travel.size() * sizeof(double), st));
  s = d.read_scalars();
  s.guard_pairs = guard_total;
  s.contacts = total / 2;
  s.moved_since_rebuild = 0;
  s.halt = halt == static_cast<int>(Halt::Rebuild) ? 0 : halt;
  d.write_scalars(s);
  return total / 2;
}

relax::ContactPairs DeviceYarn::contact_pairs() const {
  relax::ContactPairs pairs;
  pairs.start = m->pair_start.download(m->segments + 1);
  pairs.partner = m->partner.download(pairs.start.back());
  return pairs;
}

DeviceStatus DeviceYarn::run(long stop_at, int batch, std::vector<relax::YarnStepLog>& logs) {
  Impl& d = *m;
  batch = std::clamp(batch, 1, kMaxBatch);
  d.capture();
  Scalars s = d.read_scalars();
  s.halt = 0;
  s.stop_at = stop_at;
  s.log_base = s.step;
  d.write_scalars(s);
  for (int k = 0; k < batch; ++k) SKEIN_CUDA_CHECK(cudaGraphLaunch(d.graph, d.stream));
  const Scalars after = d.read_scalars();
  const long done = static_cast<long>(after.step - s.step);
  logs.clear();
  if (done > 0) {
    logs.resize(done);
    SKEIN_CUDA_CHECK(cudaMemcpy(logs.data(), d.logs.get(), done * sizeof(relax::YarnStepLog), cudaMemcpyDeviceToHost));
  }
  DeviceStatus status;
  status.halt = static_cast<Halt>(after.halt);
  status.step = static_cast<long>(after.step);
  status.energy = after.energy;
  status.residual = after.residual0 > 0 ? after.residual / after.residual0 : 0;
  return status;
}

void DeviceYarn::roll_back() {
  Impl& d = *m;
  SKEIN_CUDA_CHECK(cudaStreamSynchronize(d.stream));
  d.x.copy_from(d.good_x, d.points);
  d.v.copy_from(d.good_v, d.points);
  Scalars s = d.read_scalars();
  s.time_step *= 0.5;
  s.halt = 0;
  d.write_scalars(s);
}

}  // namespace skein::cuda
