#include "common/atomic_file.hpp"

#include <fstream>
#include <system_error>
#include <unistd.h>

#include "common/error.hpp"

namespace skein {
namespace fs = std::filesystem;

namespace {
fs::path temporary_beside(const fs::path& path) {
  return path.parent_path() / ("." + path.filename().string() + ".tmp" + std::to_string(::getpid()));
}
}  // namespace

void check_writable(const fs::path& path) {
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw Error(path.string(), "", "cannot write: " + dir.string() + " is a file, not a folder");
  if (!fs::is_directory(dir, ec)) throw Error(path.string(), "", "cannot write: folder " + dir.string() + " does not exist");
  if (fs::is_directory(path, ec)) throw Error(path.string(), "", "cannot write: it is a folder");
  if (::access(dir.c_str(), W_OK) != 0) throw Error(path.string(), "", "cannot write: no permission to write in " + dir.string());
}

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write, bool binary) {
  check_writable(path);
  const fs::path tmp = temporary_beside(path);
  {
    std::ofstream out(tmp, binary ? std::ios::out | std::ios::binary | std::ios::trunc : std::ios::out | std::ios::trunc);
    if (!out) throw Error(path.string(), "", "cannot open a temporary file for writing in " + tmp.parent_path().string());
    try {
      write(out);
    } catch (...) {
      out.close();
      fs::remove(tmp);
      throw;
    }
    out.flush();
    if (!out) {
      out.close();
      fs::remove(tmp);
      throw Error(path.string(), "", "write failed (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp);
    throw Error(path.string(), "", "cannot replace the file: " + ec.message());
  }
}

}  // namespace skein
