#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "stitchmesh/input_mesh.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/stitch_mesh.hpp"
#include "stitchmesh/tessellation.hpp"

namespace skein::mesh {

/// Everything a user saves: the input mesh with its labels and tessellation values, and the stitch mesh.
/// Stored as a `.skein` file (docs/FORMATS.md): versioned, line-based text, numbers in their shortest
/// exact form, so that reading a written project gives back the same values and the same text.
struct Project {
  StitchSize stitch_size;
  std::optional<InputMesh> input;
  std::optional<Labeling> labels;              ///< needs input
  std::optional<TessellationValues> values;    ///< needs labels
  std::optional<StitchMesh> stitch;
};

inline constexpr int kProjectVersion = 1;

std::string project_text(const Project& project);
/// Parses a project; throws skein::Error naming `name`, the line and the rule broken.
Project parse_project(const std::string& text, const std::string& name);

void write_project(const Project& project, const std::filesystem::path& path);  ///< atomic
Project read_project(const std::filesystem::path& path);

}  // namespace skein::mesh
