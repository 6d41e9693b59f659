#pragma once
// What the command-line tests share: running the skein binary, reading what it wrote, small jobs and processes
// started in the background (the tests of each subcommand's file: test_stitch_command.cpp, test_job.cpp, ...).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "testing.hpp"

namespace skein::testing::cli {

/// Runs the skein binary with arguments and returns its exit status and merged output.
inline Run run_skein(const std::string& args) { return skein::testing::run_command(std::string(SKEIN_BIN) + " " + args); }
/// `skein COMMAND -o OUTPUT` is refused: exit 2, `message` in what it prints, nothing written.
inline void expect_refused(const std::string& command, const std::filesystem::path& output, const std::string& message) {
  const auto r = run_skein(command + " -o " + output.string());
  EXPECT_EQ(r.status, 2) << command << "\n" << r.output;
  EXPECT_NE(r.output.find(message), std::string::npos) << command << "\n" << r.output;
  EXPECT_FALSE(std::filesystem::exists(output)) << command;
}
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
/// An OBJ's polygons fanned into triangles (every other line kept).
inline std::string fanned_into_triangles(const std::string& text) {
  std::string obj;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("f ", 0) != 0) {
      obj += line + "\n";
      continue;
    }
    std::istringstream f(line.substr(2));
    std::vector<std::string> corners{std::istream_iterator<std::string>(f), {}};
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) obj += "f " + corners[0] + " " + corners[k] + " " + corners[k + 1] + "\n";
  }
  return obj;
}
inline const std::string kModels = SKEIN_MODELS_DIR;
/// One line of a stitch ids side file (docs/FORMATS.md).
struct PointId {
  int point = 0, curve = 0, face = 0, row = 0;
  std::string type;
};
/// The side file's lines after its header, which must be the documented one.
inline std::vector<PointId> read_ids(const std::filesystem::path& path) {
  std::istringstream in(slurp(path));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "point,curve,face,row,type") << path;
  std::vector<PointId> out;
  while (std::getline(in, line)) {
    PointId id;
    char type[16] = "";
    EXPECT_GE(std::sscanf(line.c_str(), "%d,%d,%d,%d,%15s", &id.point, &id.curve, &id.face, &id.row, type), 4) << line;
    id.type = type;
    out.push_back(id);
  }
  return out;
}

inline const std::string kPatterns = SKEIN_PATTERNS_DIR;

/// A small job on the swatch (big stitches, a yarn run to its step cap, checkpoints every 20 steps).
inline std::string swatch_job(const std::string& extra = "", int max_steps = 60) {
  return R"({"name": "swatch", "mesh": ")" + kModels + R"(/swatch.obj", "labels": ")" + kModels + R"(/swatch.skein",
  "stitch_size": {"width": 12, "height": 10},
  "edits": [{"fill": "rib", "near_border": 2}, {"pattern": ")" + kPatterns + R"(/seed.knit", "rows": "4:6"}],
  "relax_yarn": {"max_steps": )" + std::to_string(max_steps) + R"(, "tolerance": 0, "checkpoint_every": 20}, "pictures": false)" + extra + "}";
}

/// Starts `skein ARGS` in the background (output to `log`) and returns its process id.
inline pid_t spawn_skein(const std::vector<std::string>& args, const std::filesystem::path& log) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    std::vector<char*> argv{const_cast<char*>(SKEIN_BIN)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(SKEIN_BIN, argv.data());
    ::_exit(127);
  }
  return pid;
}

/// Waits until `path` exists (true) or `seconds` pass (false).
inline bool wait_for(const std::filesystem::path& path, double seconds) {
  for (int i = 0; i < seconds * 20; ++i) {
    if (std::filesystem::exists(path)) return true;
    ::usleep(50000);
  }
  return false;
}

inline int exit_code(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace skein::testing::cli
