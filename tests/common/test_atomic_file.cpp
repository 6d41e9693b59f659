// Files written whole or not at all: a writer that fails leaves the old file as it was and no temporary beside
// it; folders that cannot be written are named before any work.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::error_of;
using skein::testing::ScratchDir;

namespace {
std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
long entries(const std::filesystem::path& dir) { return std::distance(std::filesystem::directory_iterator(dir), {}); }
}  // namespace

TEST(AtomicFile, AFailedWriteLeavesTheOldFileAndNoTemporary) {
  ScratchDir dir;
  const auto path = dir / "yarn.bcc";
  write_file_atomically(path, [](std::ostream& out) { out << "first"; });
  EXPECT_EQ(read(path), "first");
  EXPECT_THROW(write_file_atomically(path, [](std::ostream& out) {
                 out << "half of the second";
                 throw std::runtime_error("the writer failed");
               }),
               std::runtime_error);
  EXPECT_EQ(read(path), "first");
  EXPECT_EQ(entries(dir.path()), 1);
  write_file_atomically(path, [](std::ostream& out) { out << std::string("a\0b\n", 4); }, true);
  EXPECT_EQ(read(path), std::string("a\0b\n", 4));
  EXPECT_EQ(entries(dir.path()), 1);
}

TEST(AtomicFile, UnwritablePlacesAreNamedBeforeAnyWork) {
  ScratchDir dir;
  bool wrote = false;
  const auto writer = [&](std::ostream&) { wrote = true; };
  EXPECT_EQ(error_of([&] { write_file_atomically(dir / "missing" / "a.bcc", writer); }),
            (dir / "missing" / "a.bcc").string() + ": cannot write: folder " + (dir / "missing").string() + " does not exist");
  const auto file = dir.write("plain.txt", "x");
  EXPECT_NE(error_of([&] { check_writable(file / "a.bcc"); }).find("is a file, not a folder"), std::string::npos);
  std::filesystem::create_directory(dir / "folder");
  EXPECT_NE(error_of([&] { check_writable(dir / "folder"); }).find("cannot write: it is a folder"), std::string::npos);
  EXPECT_FALSE(wrote);
}
