#pragma once
// Before a text reader takes a file whole: it must be a regular file (not a folder, a FIFO or /dev/zero) of at
// most a size that reader can mean.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace skein {

/// Throws skein::Error naming `path` unless it is a regular file of at most `max_bytes`.
void check_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes);

/// The files of `folder` whose extension is `extension` (".vdb"), in name order; the folder must exist.
std::vector<std::filesystem::path> files_with_extension(const std::filesystem::path& folder, const std::string& extension);

}  // namespace skein
