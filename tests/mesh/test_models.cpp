#include <gtest/gtest.h>

#include "garments.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/project.hpp"
#include "testing.hpp"

using namespace skein;

// The committed models/ files are what the generator makes today (run `build/bin/skein-models models` after
// changing models/garments.cpp).
TEST(Models, CommittedFilesMatchTheGenerator) {
  for (const auto& g : models::garments()) {
    const auto made = g.make();
    const auto project = mesh::read_project(skein::testing::models_dir() / (g.name + ".skein"));
    ASSERT_TRUE(project.input && project.labels) << g.name;
    EXPECT_EQ(project.input->points(), made.points()) << g.name;
    EXPECT_EQ(project.input->faces(), made.faces()) << g.name;
    const auto labels = mesh::auto_label(made, mesh::default_start_edge(made));
    EXPECT_EQ(project.labels->edges, labels.edges) << g.name;
    for (int f = 0; f < made.num_faces(); ++f) {
      EXPECT_EQ(project.labels->faces[f].row, labels.faces[f].row) << g.name;
      EXPECT_EQ(project.labels->faces[f].left, labels.faces[f].left) << g.name;
    }
    const auto obj = mesh::load_mesh(skein::testing::models_dir() / (g.name + ".obj"));
    // assimp numbers vertices its own way and reads single-precision floats; faces and corners keep their order.
    ASSERT_EQ(obj.num_faces(), made.num_faces()) << g.name;
    for (int f = 0; f < made.num_faces(); ++f) {
      ASSERT_EQ(obj.face(f).size(), made.face(f).size()) << g.name;
      for (size_t k = 0; k < made.face(f).size(); ++k)
        EXPECT_LT((obj.point(obj.face(f)[k]) - made.point(made.face(f)[k])).norm(), 1e-6 * made.bounding_diagonal()) << g.name << " face " << f;
    }
  }
}
