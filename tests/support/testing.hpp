#pragma once
// Shared test helpers: scratch files, tolerances and the bundled models.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/wait.h>

namespace skein::testing {

/// Geometric tolerance relative to a model's size.
inline constexpr double kRelativeTolerance = 1e-9;

/// A fresh folder under the system temp folder, removed at the end of the test.
class ScratchDir {
public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_path = std::filesystem::temp_directory_path() / ("skein-test-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" +
                                                       std::to_string(::getpid()));
    std::filesystem::remove_all(m_path);
    std::filesystem::create_directories(m_path);
  }
  ~ScratchDir() { std::filesystem::remove_all(m_path); }
  std::filesystem::path operator/(const std::string& name) const { return m_path / name; }
  const std::filesystem::path& path() const { return m_path; }

  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto p = m_path / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

private:
  std::filesystem::path m_path;
};

inline std::filesystem::path models_dir() { return SKEIN_MODELS_DIR; }

/// What a program run printed (stdout and stderr merged) and its exit status (-1 when a signal ended it).
struct Run {
  int status;
  std::string output;
};
/// Runs a shell command line.
inline Run run_command(const std::string& command) {
  std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  std::string out;
  std::array<char, 4096> buf;
  while (size_t n = std::fread(buf.data(), 1, buf.size(), pipe)) out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

/// Runs `call` and returns the message of the skein::Error it throws ("" if it throws none).
template <class F>
std::string error_of(F&& call) {
  try {
    call();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace skein::testing
