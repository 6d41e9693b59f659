#pragma once
// Before a text reader takes a file whole: it must be a regular file (not a folder, a FIFO or /dev/zero) of at
// most a size that reader can mean.
#include <cstdint>
#include <filesystem>

namespace skein {

/// Throws skein::Error naming `path` unless it is a regular file of at most `max_bytes`.
void check_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes);

}  // namespace skein
