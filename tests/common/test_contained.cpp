// The contained reader (issue 25): a crash, a blow-up or a hang inside a reader is an error naming the file, and
// what the reader returns or throws comes back whole.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/contained.hpp"
#include "common/error.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::error_of;

// The contained reader (issue 25): a crash, a blow-up or a hang inside the reader is an error naming the file.
TEST(ContainedReader, ACrashInTheReaderIsAnErrorNamingTheSignal) {
  const std::string msg = error_of([] {
    run_contained("mesh.ply", "the mesh reader", {4, 60}, []() -> std::string {
      std::raise(SIGSEGV);
      return "";
    });
  });
  EXPECT_EQ(msg.rfind("mesh.ply: the mesh reader crashed (signal 11, ", 0), 0u) << msg;
}

TEST(ContainedReader, RunningOutOfMemoryOrTimeStopsTheReader) {
  const ContainedLimits small{0.25, 60};
  std::string msg = error_of([&] {
    run_contained("huge.off", "the mesh reader", small, [] {
      std::vector<std::unique_ptr<char[]>> blocks;
      for (;;) blocks.emplace_back(new char[64 << 20]);
      return std::string();
    });
  });
  EXPECT_EQ(msg, "huge.off: the mesh reader needed more than 0.25 GB (SKEIN_READER_GB) and was stopped");
  const auto started = std::chrono::steady_clock::now();
  msg = error_of([] {
    run_contained("slow.obj", "the mesh reader", {4, 0.3}, [] {
      ::sleep(30);
      return std::string();
    });
  });
  EXPECT_EQ(msg, "slow.obj: the mesh reader took longer than 0.3 s (SKEIN_READER_SECONDS) and was stopped");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 10);
}

TEST(ContainedReader, AChildStuckWithoutUsingTheCpuIsStartedOnceMore) {
  // As a child forked while another thread held a lock waits on it: the first one sleeps past the limit (a file
  // says it came), the second answers.
  const auto marker = std::filesystem::temp_directory_path() / ("skein-stuck-" + std::to_string(::getpid()));
  std::filesystem::remove(marker);
  const std::string answer = run_contained("stuck.vdb", "the OpenVDB reader", {4, 0.5}, [&] {
    if (!std::filesystem::exists(marker)) {
      std::ofstream(marker) << "came";
      ::sleep(30);
    }
    return std::string("read");
  });
  std::filesystem::remove(marker);
  EXPECT_EQ(answer, "read");
}

TEST(ContainedReader, AnswersAndErrorsComeBackWhole) {
  std::string big(5 << 20, 0);  // larger than a pipe's buffer
  for (size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 7919 % 251);
  const ContainedLimits limits{4, 60};
  EXPECT_EQ(run_contained("x", "the mesh reader", limits, [&] { return big; }), big);
  try {
    run_contained("x", "the mesh reader", limits, []() -> std::string { throw Error("a.obj", "line 3", "expected a number"); });
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), "a.obj");
    EXPECT_EQ(e.place(), "line 3");
    EXPECT_EQ(e.rule(), "expected a number");
  }
  EXPECT_EQ(error_of([&] { run_contained("x", "the mesh reader", limits, []() -> std::string { throw std::runtime_error("boom"); }); }),
            "x: the mesh reader failed: boom");
}

TEST(ContainedReader, LimitsFromTheEnvironment) {
  ::setenv("SKEIN_READER_GB", "1.5", 1);
  ::setenv("SKEIN_READER_SECONDS", "7", 1);
  const auto limits = ContainedLimits::from_environment();
  EXPECT_EQ(limits.memory_gb, 1.5);
  EXPECT_EQ(limits.seconds, 7);
  ::unsetenv("SKEIN_READER_SECONDS");
  EXPECT_EQ(ContainedLimits::from_environment().seconds, 0);  // the reader's default for its file
  ::setenv("SKEIN_READER_GB", "lots", 1);
  EXPECT_EQ(error_of([] { ContainedLimits::from_environment(); }), "environment variable SKEIN_READER_GB: expected a positive number, found 'lots'");
  ::unsetenv("SKEIN_READER_GB");
  ::unsetenv("SKEIN_READER_SECONDS");
}
