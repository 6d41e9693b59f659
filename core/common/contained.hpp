#pragma once
// Untrusted input parsed where a crash or a blow-up inside a library cannot take skein down (issue 25, part 3):
// the work runs in a forked child with an address-space limit and a deadline; what it returns comes back
// through a pipe. A signal, running out of memory or time becomes a skein::Error naming the file.
#include <functional>
#include <string>

namespace skein {

struct ContainedLimits {
  double memory_gb = 4;   ///< address space the child may take beyond what the process already holds
  double seconds = 0;     ///< wall time before the child is killed; 0: the caller's default for its input
  /// SKEIN_READER_GB and SKEIN_READER_SECONDS where set (positive numbers), else the defaults; throws
  /// skein::Error naming the variable for a value that is not one.
  static ContainedLimits from_environment();
};

/// Runs `work` in a child process under `limits` and returns the bytes it returned. A skein::Error thrown in
/// the child is thrown again here as it was; a crash (a signal), std::bad_alloc or another exception in the
/// child, or the deadline passing (`limits.seconds`, which must be positive here), throws skein::Error(file, "", "the mesh reader ...") with what happened.
/// `what` names the work in those messages ("the mesh reader").
std::string run_contained(const std::string& file, const std::string& what, const ContainedLimits& limits,
                          const std::function<std::string()>& work);

}  // namespace skein
