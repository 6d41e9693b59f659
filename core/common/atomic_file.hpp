#pragma once
#include <filesystem>
#include <functional>
#include <ostream>

namespace skein {

/// Writes a file so that it either appears whole or not at all: the content goes to a temporary file
/// beside the target, which is renamed over it only after a successful flush. Throws skein::Error
/// naming the path when the folder is missing or unwritable, or the disk is full.
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write,
                           bool binary = false);

/// Fails early (before hours of work) when `path` could not be written: missing folder, no permission.
void check_writable(const std::filesystem::path& path);

}  // namespace skein
