// libFuzzer harness: mesh files (OBJ, PLY, OFF, STL) through load_mesh. assimp parses them in the contained
// reader's child process (issue 25), so what this finds is a reader crash or blow-up that escapes as something
// other than skein::Error, and every rule of InputMesh on what the reader gives back. The first byte picks the
// format; the rest is the file. Limits of 0.5 GB and 2 s keep each input well inside libFuzzer's own timeout.
#include "fuzz_support.hpp"
#include "stitchmesh/input_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const extensions[] = {".obj", ".ply", ".off", ".stl"};
  const auto path = skein::fuzz::as_file(data + 1, size - 1, extensions[data[0] % 4]);
  skein::fuzz::expect_clean([&] { skein::mesh::load_mesh(path, {0.5, 2}); });
  std::filesystem::remove(path);
  return 0;
}
