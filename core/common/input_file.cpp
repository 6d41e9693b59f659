#include "common/input_file.hpp"

#include <algorithm>
#include <string>
#include <system_error>

#include "common/error.hpp"

namespace skein {

void check_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw Error(path.string(), "", error ? "cannot be read: " + error.message() : "does not exist");
  if (!std::filesystem::is_regular_file(path, error)) throw Error(path.string(), "", "is not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) throw Error(path.string(), "", "cannot be read: " + error.message());
  if (size > max_bytes)
    throw Error(path.string(), "", "is " + std::to_string(size) + " bytes; a file of this kind holds at most " + std::to_string(max_bytes));
}

std::vector<std::filesystem::path> files_with_extension(const std::filesystem::path& folder, const std::string& extension) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.path().extension() == extension) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace skein
