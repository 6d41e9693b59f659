// The thread count that follows the free cores (common/cpu_threads.hpp, issue 28 part 3).
#include <gtest/gtest.h>
#include <omp.h>
#include <sched.h>

#include <cstdlib>

#include "common/cpu_threads.hpp"

namespace skein {
namespace {

int usable_cores() {
  cpu_set_t set;
  EXPECT_EQ(sched_getaffinity(0, sizeof(set), &set), 0);
  return CPU_COUNT(&set);
}

TEST(CpuThreads, FreeCoresAreAtLeastOneAndAtMostTheUsableCores) {
  const int cores = usable_cores();
  for (int i = 0; i < 20; ++i) {
    const int free = free_cores();
    EXPECT_GE(free, 1);
    EXPECT_LE(free, cores);
  }
}

TEST(CpuThreads, FollowingSetsTheThreadCountUnlessOmpNumThreadsIsSet) {
  const int before = omp_get_max_threads();
  unsetenv("OMP_NUM_THREADS");
  omp_set_num_threads(64);
  follow_free_cores(true);
  EXPECT_LE(omp_get_max_threads(), usable_cores());  // free_cores() at the moment of the call
  EXPECT_GE(omp_get_max_threads(), 1);
  follow_free_cores(false);
  omp_set_num_threads(64);
  refresh_thread_count();
  EXPECT_EQ(omp_get_max_threads(), 64);  // not following: left alone

  setenv("OMP_NUM_THREADS", "3", 1);
  omp_set_num_threads(3);
  follow_free_cores(true);  // the user's choice wins
  EXPECT_EQ(omp_get_max_threads(), 3);
  refresh_thread_count();
  EXPECT_EQ(omp_get_max_threads(), 3);
  follow_free_cores(false);
  unsetenv("OMP_NUM_THREADS");
  omp_set_num_threads(before);
}

}  // namespace
}  // namespace skein
