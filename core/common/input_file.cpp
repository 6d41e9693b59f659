#include "common/input_file.hpp"

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

}  // namespace skein
