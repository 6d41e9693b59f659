// skein-models: writes the bundled garments as OBJ meshes with their labelings (.skein), into a folder.
#include <cstdio>
#include <filesystem>

#include "common/error.hpp"
#include "garments.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/project.hpp"

int main(int argc, char** argv) {
  const std::filesystem::path out = argc > 1 ? argv[1] : "models";
  try {
    for (const auto& g : skein::models::garments()) {
      skein::mesh::Project project;
      project.input = g.make();
      const auto& mesh = *project.input;
      project.labels = skein::mesh::auto_label(mesh, skein::mesh::default_start_edge(mesh));
      const auto report = skein::mesh::validate_labels(mesh, *project.labels);
      skein::mesh::write_obj(mesh, out / (g.name + ".obj"));
      skein::mesh::write_project(project, out / (g.name + ".skein"));
      std::printf("%-9s %4d faces, %3d rows, %zu unlabelable faces, %zu mismatched edges\n", g.name.c_str(), mesh.num_faces(),
                  project.labels->rows, report.face_problems.size(), report.mismatches.size());
    }
  } catch (const skein::Error& e) {
    std::fprintf(stderr, "skein-models: %s\n", e.what());
    return 1;
  }
}
