#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "stitchmesh/input_mesh.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/stitch_mesh.hpp"
#include "stitchmesh/tessellation.hpp"

namespace skein::mesh {

/// One `set KEY VALUE` line of a project: a setting the app saves with the project (the yarn relaxation's:
/// workflow::read_yarn_settings reads them), kept here as text with its line for errors.
struct ProjectSetting {
  std::string key, value;
  int line = 0;  ///< where it was read, 0 when made in memory
  bool operator==(const ProjectSetting& o) const { return key == o.key && value == o.value; }
};

/// Everything a user saves: the input mesh with its labels and tessellation values, and the stitch mesh.
/// Stored as a `.skein` file (docs/FORMATS.md): versioned, line-based text, numbers in their shortest
/// exact form, so that reading a written project gives back the same values and the same text.
struct Project {
  StitchSize stitch_size;
  std::optional<InputMesh> input;
  std::optional<Labeling> labels;              ///< needs input
  std::optional<TessellationValues> values;    ///< needs labels
  std::optional<StitchMesh> stitch;
  std::vector<ProjectSetting> settings;  ///< keys of letters, digits, '.', '_' and '-', each once
};

inline constexpr int kProjectVersion = 1;

std::string project_text(const Project& project);
/// Parses a project; throws skein::Error naming `name`, the line and the rule broken.
Project parse_project(const std::string& text, const std::string& name);

void write_project(const Project& project, const std::filesystem::path& path);  ///< atomic
Project read_project(const std::filesystem::path& path);

}  // namespace skein::mesh
