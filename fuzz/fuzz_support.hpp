#pragma once
// What every reader harness shares. A reader may refuse its input only with skein::Error (the file, the place
// and the rule); anything else that escapes — another exception, a crash, a sanitizer report — is a bug that
// libFuzzer reports.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "common/error.hpp"

namespace skein::fuzz {

inline std::string text(const std::uint8_t* data, std::size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

/// The input written to a file of this process (for readers that take a path).
inline std::filesystem::path as_file(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const auto path = std::filesystem::temp_directory_path() / ("skein-fuzz-" + std::to_string(::getpid()) + extension);
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

template <class F>
void expect_clean(F&& read) {
  try {
    read();
  } catch (const skein::Error&) {
  }
}

}  // namespace skein::fuzz
