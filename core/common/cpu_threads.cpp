#include "common/cpu_threads.hpp"

#include <omp.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace skein {

void wait_passively(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  // A few microseconds of spinning before sleeping: with none at all the seed pattern took about 2.3 s alone
  // instead of 1.8 s (docs/BENCHMARKS.md, "Steady under load").
  setenv("GOMP_SPINCOUNT", "3000", 0);
  execv("/proc/self/exe", argv);  // returns only on failure: go on with the spinning default
}

namespace {

int usable_cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
}

// The fourth field of /proc/loadavg is "running/total" scheduling entities, this process's threads included.
// -1 when it cannot be read.
int running_threads() {
  std::ifstream in("/proc/loadavg");
  double one, five, fifteen;
  int running = -1;
  char slash;
  if (in >> one >> five >> fifteen >> running >> slash && slash == '/') return running;
  return -1;
}

// This process's threads that are running now (state R in /proc/self/task/*/stat), this one included: OpenMP
// threads still spinning after a parallel region count, and must not be taken for other work.
int own_running_threads() {
  int running = 0;
  std::error_code error;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", error)) {
    std::ifstream in(task.path() / "stat");
    std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto name_end = stat.rfind(')');  // the thread's name, in parentheses, may hold spaces
    if (name_end != std::string::npos && name_end + 2 < stat.size() && stat[name_end + 2] == 'R') ++running;
  }
  return std::max(1, running);
}

}  // namespace

int free_cores() {
  const int cores = usable_cores();
  const int running = running_threads();
  if (running < 1) return cores;
  return std::clamp(cores - (running - own_running_threads()), 1, cores);
}

namespace {
std::atomic<bool> g_follow{false};
}

void follow_free_cores(bool on) {
  g_follow = on && std::getenv("OMP_NUM_THREADS") == nullptr;
  refresh_thread_count();
}

bool following_free_cores() { return g_follow; }

const char* wait_policy() {
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  return policy != nullptr ? policy : "default";
}

void refresh_thread_count() {
  if (g_follow) omp_set_num_threads(free_cores());
}

}  // namespace skein
