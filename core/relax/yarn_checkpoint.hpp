#pragma once
#include <cstdint>
#include <filesystem>

#include "relax/yarn_relax.hpp"

namespace skein::relax {

/// A fingerprint of what a checkpoint may be resumed against: the yarn's structure, rest lengths and
/// radius, and the method (a checkpoint of one yarn or method cannot continue another).
std::uint64_t checkpoint_fingerprint(const YarnSystem& system, YarnMethod method);

/// Writes `state` atomically: "SKEINCKP", format version, fingerprint, sizes, the state, and a checksum of
/// everything before it (FORMATS.md).
void write_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint, const YarnState& state);

/// Reads a checkpoint for the yarn with this fingerprint. Throws skein::Error naming the file, the byte
/// offset and the rule for a damaged, truncated or foreign file.
YarnState read_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint, int num_points);

}  // namespace skein::relax
