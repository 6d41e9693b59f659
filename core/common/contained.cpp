#include "common/contained.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <new>
#include <sstream>

#include "common/error.hpp"

// Defined only by a sanitizer runtime (the fuzz build), where libFuzzer registers a death callback that writes
// the input as a crash: a dying child must not run it, for its death is the parent's to report as an Error.
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

namespace skein {
namespace {

// The child's answer: one status byte, then the payload (the work's bytes, or an error's three strings).
enum Status : char { kDone = 0, kError = 1, kOutOfMemory = 2, kOtherException = 3 };

void put_string(std::string& out, const std::string& s) {
  const std::uint64_t n = s.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  out += s;
}

std::string take_string(const std::string& in, size_t& at) {
  std::uint64_t n = 0;
  if (at + sizeof n > in.size()) return {};
  std::memcpy(&n, in.data() + at, sizeof n);
  at += sizeof n;
  if (n > in.size() - at) return {};
  std::string s = in.substr(at, n);
  at += n;
  return s;
}

bool write_all(int fd, const std::string& data) {
  for (size_t done = 0; done < data.size();) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

/// The process's current address space [bytes] (/proc/self/statm), 0 when unknown.
std::uint64_t address_space() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  if (!(statm >> pages)) return 0;
  return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

double positive_variable(const char* name, double fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (*end != 0 || !std::isfinite(v) || v <= 0) throw Error("", std::string("environment variable ") + name, std::string("expected a positive number, found '") + text + "'");
  return v;
}

[[noreturn]] void child(int fd, double memory_gb, const std::function<std::string()>& work) {
  // Only this thread lives on in the child; it does the work and leaves with _exit (no atexit handlers, no
  // destructors of the parent's objects).
  const std::uint64_t limit = address_space() + static_cast<std::uint64_t>(memory_gb * 1073741824.0);
  const rlimit as{limit, limit};
  ::setrlimit(RLIMIT_AS, &as);
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  std::string answer(1, kDone);
  try {
    answer += work();
  } catch (const Error& e) {
    answer.assign(1, kError);
    put_string(answer, e.file());
    put_string(answer, e.place());
    put_string(answer, e.rule());
  } catch (const std::bad_alloc&) {
    answer.assign(1, kOutOfMemory);
  } catch (const std::exception& e) {
    answer.assign(1, kOtherException);
    put_string(answer, e.what());
  } catch (...) {
    answer.assign(1, kOtherException);
    put_string(answer, "an unknown exception");
  }
  _exit(write_all(fd, answer) ? 0 : 3);
}

}  // namespace

ContainedLimits ContainedLimits::from_environment() {
  ContainedLimits limits;
  limits.memory_gb = positive_variable("SKEIN_READER_GB", limits.memory_gb);
  limits.seconds = positive_variable("SKEIN_READER_SECONDS", limits.seconds);
  return limits;
}

namespace {

/// The CPU time a process has used so far [s], from /proc; 0 when it cannot be read.
double cpu_seconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto name_end = stat.rfind(')');  // fields 14 and 15 (utime, stime) come after the name, in parentheses
  if (name_end == std::string::npos) return 0;
  std::istringstream fields(stat.substr(name_end + 2));
  std::string field;
  double ticks = 0;
  for (int k = 3; k <= 15 && fields >> field; ++k)
    if (k >= 14) ticks += std::atof(field.c_str());
  return ticks / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

struct Attempt {
  std::string answer;
  int status = 0;
  bool late = false;
  bool stuck = false;  ///< late, having used under a tenth of the time on the CPU
};

Attempt attempt(const std::string& file, const std::string& what, const ContainedLimits& limits, const std::function<std::string()>& work) {
  int fds[2];
  if (::pipe(fds) != 0) throw Error(file, "", what + " could not start: pipe: " + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error(file, "", what + " could not start: fork: " + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(nullptr);
    for (int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) ::signal(sig, SIG_DFL);  // a crash ends the child only
    child(fds[1], limits.memory_gb, work);
  }
  ::close(fds[1]);
  // Read everything the child writes until it closes the pipe (by exiting or dying), or the deadline.
  Attempt a;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limits.seconds);
  char buffer[1 << 16];
  for (;;) {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) {
      a.late = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min(left * 1000 + 1, 1e9)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    a.answer.append(buffer, static_cast<size_t>(n));
  }
  ::close(fds[0]);
  if (a.late) {
    a.stuck = cpu_seconds(pid) < 0.1 * limits.seconds;
    ::kill(pid, SIGKILL);
  }
  while (::waitpid(pid, &a.status, 0) < 0 && errno == EINTR) {
  }
  return a;
}

}  // namespace

std::string run_contained(const std::string& file, const std::string& what, const ContainedLimits& limits,
                          const std::function<std::string()>& work) {
  if (!(limits.seconds > 0)) throw Error(file, "", what + " needs a time limit");
  Attempt a = attempt(file, what, limits, work);
  // A child forked while another thread of this process held a lock (a library's, not malloc's) can wait on it
  // forever: a child that ran out of time without using the CPU was stuck, not slow, and is started once more.
  if (a.late && a.stuck) a = attempt(file, what, limits, work);
  const std::string& answer = a.answer;
  const int status = a.status;
  const bool late = a.late;
  const auto gb = [&] {
    char text[32];
    std::snprintf(text, sizeof text, "%g", limits.memory_gb);
    return std::string(text);
  };
  if (late) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", limits.seconds);
    throw Error(file, "", what + " took longer than " + text + " s (SKEIN_READER_SECONDS) and was stopped");
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    // Running out of address space inside a library often ends in an abort (an uncaught bad_alloc) or a fault.
    throw Error(file, "", what + " crashed (signal " + std::to_string(signal) + ", " + (::strsignal(signal) ? ::strsignal(signal) : "?") +
                              "); the file is damaged or more than the reader can take (it may use " + gb() + " GB, SKEIN_READER_GB)");
  }
  if (answer.empty() || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(file, "", what + " stopped without an answer (exit status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  size_t at = 1;
  switch (answer[0]) {
    case kDone: return answer.substr(1);
    case kError: {
      std::string f = take_string(answer, at), place = take_string(answer, at), rule = take_string(answer, at);
      throw Error(std::move(f), std::move(place), std::move(rule));
    }
    case kOutOfMemory: throw Error(file, "", what + " needed more than " + gb() + " GB (SKEIN_READER_GB) and was stopped");
    default: throw Error(file, "", what + " failed: " + take_string(answer, at));
  }
}

}  // namespace skein
