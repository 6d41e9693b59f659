#pragma once
// Woven test inputs: the bundled weave patterns, and small exemplars quick to make.
#include <filesystem>
#include <string>
#include <vector>

#include "stitchmesh/pattern.hpp"
#include "woven/exemplar.hpp"
#include "woven/weave.hpp"

namespace skein::testing {

inline woven::Weave bundled_weave(const std::string& name) { return woven::from_pattern(skein::mesh::read_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / (name + ".weave"))); }

inline skein::mesh::Pattern weave_pattern(const std::string& name) { return skein::mesh::read_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / (name + ".weave")); }

/// Small exemplars, quick to make: 6 x 6 crossings of 10 x 10 voxels.
inline woven::ExemplarOptions small() {
  woven::ExemplarOptions o;
  o.crossings = 6;
  o.voxels_per_crossing = 10;
  return o;
}

inline const std::vector<woven::Exemplar>& small_set() {
  static const std::vector<woven::Exemplar> set = [] {
    std::vector<woven::Exemplar> out;
    for (const char* n : {"plain-weave", "twill-3-2", "satin-5-2"}) out.push_back(woven::make_exemplar(weave_pattern(n), small()));
    return out;
  }();
  return set;
}

}  // namespace skein::testing
