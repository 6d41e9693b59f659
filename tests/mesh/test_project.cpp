#include <gtest/gtest.h>

#include "common/error.hpp"
#include "garments.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/project.hpp"
#include "stitch_fixtures.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::error_of;
using skein::testing::ScratchDir;

namespace {
mesh::Project full_project() {
  mesh::Project p;
  p.stitch_size = {6.25, 4.1};
  p.input = models::mitten();
  p.labels = mesh::auto_label(*p.input, mesh::default_start_edge(*p.input));
  p.values = mesh::initial_values(*p.input, *p.labels, p.stitch_size);
  p.values->marked[p.input->face_edge(3, p.labels->faces[3].left)] = 1;
  auto s = mesh::tessellate(*p.input, *p.labels, *p.values);
  s = mesh::fill(s, skein::testing::all_faces(s), mesh::parse_fill("rib2x2"));
  p.stitch = mesh::mark_cable(s, mesh::top_edge_path(s, 3, 2, 4), 1, -1);
  p.settings = {{"yarn.tolerance", "0.005"}, {"yarn.method", "euler"}};
  // Yarn in two colours: a run of faces in the second (issue 26), the description's comment mark made harmless.
  p.stitch->palette = {{"MC", "cream", {240 / 255.0, 230 / 255.0, 207 / 255.0}, ""}, {"CC", "navy #1", {31 / 255.0, 42 / 255.0, 68 / 255.0}, ""}};
  for (int f = 10; f < 30; ++f) p.stitch->faces[f].colour = 1;
  return p;
}

std::string parse_error(const std::string& text) {
  return error_of([&] { mesh::parse_project(text, "bad.skein"); });
}

const char* kTinyHeader = "skein 1\nstitch-size 6 5\ninput-mesh\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 0 1 2 3\n";
}  // namespace

TEST(Project, RoundTripIsExact) {
  const auto p = full_project();
  const std::string text = mesh::project_text(p);
  const auto back = mesh::parse_project(text, "mem");
  EXPECT_EQ(mesh::project_text(back), text);
  ASSERT_TRUE(back.input && back.labels && back.values && back.stitch);
  EXPECT_EQ(back.input->points(), p.input->points());  // bit-exact doubles
  EXPECT_EQ(back.input->faces(), p.input->faces());
  EXPECT_EQ(back.labels->edges, p.labels->edges);
  EXPECT_EQ(back.labels->rows, p.labels->rows);
  EXPECT_EQ(back.values->edge, p.values->edge);
  EXPECT_EQ(back.values->marked, p.values->marked);
  EXPECT_EQ(back.stitch->faces, p.stitch->faces);
  EXPECT_EQ(back.stitch->cables, p.stitch->cables);
  ASSERT_EQ(back.stitch->palette.size(), 2u);
  EXPECT_EQ(back.stitch->palette[1].description, "navy _1");
  EXPECT_EQ(mesh::colour_code(back.stitch->palette[1].srgb), "#1f2a44");
  EXPECT_NE(text.find("colour CC 1f2a44 navy _1\nface-colour 10 29 1\n"), std::string::npos);
  EXPECT_EQ(back.stitch_size.width, 6.25);
  EXPECT_EQ(back.settings, p.settings);
  EXPECT_EQ(back.settings[1].line, 4);  // after the header and the stitch size
}

TEST(Project, FilesRoundTripAndWriteAtomically) {
  ScratchDir dir;
  const auto p = full_project();
  mesh::write_project(p, dir / "mitten.skein");
  const auto back = mesh::read_project(dir / "mitten.skein");
  EXPECT_EQ(mesh::project_text(back), mesh::project_text(p));
  // No temporary file is left behind, and an unwritable place fails before anything is written.
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) files += entry.is_regular_file();
  EXPECT_EQ(files, 1);
  const std::string msg = error_of([&] { mesh::write_project(p, dir / "missing" / "x.skein"); });
  EXPECT_NE(msg.find("does not exist"), std::string::npos) << msg;
}

TEST(Project, BadFilesNameTheLineAndRule) {
  struct Case {
    std::string text, place, rule;
  };
  const std::string h = kTinyHeader;
  const std::vector<Case> cases{
      {"", "", "empty file"},
      {"hello\n", "line 1", "starts with 'skein <version>'"},
      {"skein 7\n", "line 1", "version 7 is not supported"},
      {"skein 1\nstitch-size 6\n", "line 2", "expected width and height"},
      {"skein 1\nstitch-size -1 5\nend\n", "line 2", "positive"},
      {"skein 1\nbanana\nend\n", "line 2", "'banana' is not expected"},
      {"skein 1\ninput-mesh\nv 0 zero 0\n", "line 3", "'zero' is not a number"},
      {"skein 1\ninput-mesh\nv 0 0 0\nf 0 1 2\nend\n", "line 4", "out of range"},
      {h, "line 8", "ends without 'end'"},
      {h + "end\nv 1 2 3\n", "line 10", "nothing may follow 'end'"},
      {h + "labels\nface 9 0 1 3\nend\n", "line 10", "face 9 does not exist"},
      {h + "labels\nface 0 0 1 7\nend\n", "line 10", "has 4 edges"},
      {h + "labels\nedge 0 Q 1 0\nend\n", "line 10", "edge label must be W"},
      {h + "labels\nedge 0 W 1 0\nedge 1 C 0 0\nend\n", "line 11", "tessellation value 0"},
      {h + "stitch-mesh\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 0 1 knit -1 0 1 2 3\nend\n", "line 14", "'knit' is not a known stitch type"},
      {h + "stitch-mesh\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 0 2 k -1 0 1 2 3\nend\n", "line 14", "leaves no top edge"},
      {h + "stitch-mesh\nv 0 0 0\nf 0 1 k -1 0 0 0 9\nend\n", "line 11", "out of range"},
      {"skein 1\ninput-mesh\nv 0 0 0\nv 1 0 0\nv 2 0 0\nf 0 1 2\nend\n", "face 0", "zero area"},
      {"skein 1\nset yarn.tolerance\nend\n", "line 2", "expected a key and a value, found 1 value after 'set'"},
      {"skein 1\nset yarn/tolerance 0.1\nend\n", "line 2", "may hold only letters"},
      {"skein 1\nset yarn.halo 2\nset yarn.halo 3\nend\n", "line 3", "'yarn.halo' is set twice (first at line 2)"},
      {h + "stitch-mesh\ncolour A f0e6\nend\n", "line 10", "a colour is six hex digits (f0e6cf), found 'f0e6'"},
      {h + "stitch-mesh\ncolour A f0e6cf\ncolour a 000000\nend\n", "line 11", "colour 'a' is given twice"},
      {h + "stitch-mesh\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 0 1 k -1 0 1 2 3\ncolour A f0e6cf\nface-colour 0 0 1\nend\n", "line 16",
       "colour 1 is not one of the 1 colours given"},
      {h + "stitch-mesh\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 0 1 k -1 0 1 2 3\ncolour A f0e6cf\ncolour B 000000\nface-colour 0 3 1\nend\n", "line 17",
       "faces 0 to 3 are not faces of the stitch mesh (it has 1)"},
  };
  for (const auto& c : cases) {
    const std::string msg = parse_error(c.text);
    EXPECT_NE(msg.find("bad.skein"), std::string::npos) << c.text << "\n→ " << msg;
    EXPECT_NE(msg.find(c.place), std::string::npos) << c.text << "\n→ " << msg;
    EXPECT_NE(msg.find(c.rule), std::string::npos) << c.text << "\n→ " << msg;
  }
}

TEST(Project, BinaryAndMissingFilesAreRejected) {
  ScratchDir dir;
  EXPECT_NE(error_of([&] { mesh::read_project(dir / "nope.skein"); }).find("no such file"), std::string::npos);
  EXPECT_NE(error_of([&] { mesh::read_project(dir / (std::string(300, 'x') + ".skein")); }).find("File name too long"), std::string::npos);
  const auto bin = dir.write("bin.skein", std::string("skein 1\n\0\x01\x02", 11));
  EXPECT_NE(error_of([&] { mesh::read_project(bin); }).find("binary"), std::string::npos);
}

TEST(Project, TruncationAnywhereIsAnErrorNotACrash) {
  const std::string text = mesh::project_text(full_project());
  for (size_t cut = 0; cut < text.size(); cut += std::max<size_t>(1, text.size() / 97)) {
    const std::string part = text.substr(0, cut);
    EXPECT_THROW(mesh::parse_project(part, "cut.skein"), Error) << "cut at " << cut;
  }
}
