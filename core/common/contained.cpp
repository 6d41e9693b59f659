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
#include <new>

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

std::string run_contained(const std::string& file, const std::string& what, const ContainedLimits& limits,
                          const std::function<std::string()>& work) {
  if (!(limits.seconds > 0)) throw Error(file, "", what + " needs a time limit");
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
  std::string answer;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limits.seconds);
  bool late = false;
  char buffer[1 << 16];
  for (;;) {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) {
      late = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min(left * 1000 + 1, 1e9)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    answer.append(buffer, static_cast<size_t>(n));
  }
  ::close(fds[0]);
  if (late) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
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
