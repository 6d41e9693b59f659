// Smocking patterns drawn as SVG (front stitches solid, back dashed) and written back as .smock text.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "smocking/smocking_svg.hpp"
#include "testing.hpp"

using namespace skein;
using namespace skein::smocking;
using skein::testing::ScratchDir;

namespace {
std::string svg(const std::string& body) { return "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\">\n" + body + "</svg>\n"; }
std::string error_of_svg(const ScratchDir& dir, const std::string& body, const SvgImport& import = {}) {
  const auto file = dir.write("d.svg", svg(body));
  return skein::testing::error_of([&] { read_smocking_svg(file, import); });
}
}  // namespace

TEST(SmockingSvg, StitchesDrawnAsLinesChainIntoThreadsOnTheGrid) {
  ScratchDir dir;
  // A zigzag of four stitches drawn stitch by stitch, every second dashed, in a translated and scaled group,
  // with a dot and a curve in <defs> that are not stitches.
  const auto file = dir.write("z.svg", svg("<defs><path d=\"M0 0 C 1 1 2 2 3 3\"/></defs>\n<circle cx=\"1\" cy=\"1\" r=\"1\"/>\n"
                                           "<g transform=\"translate(100 50) scale(2)\">\n"
                                           "<line x1=\"0\" y1=\"10\" x2=\"10\" y2=\"0\" stroke=\"black\"/>\n"
                                           "<line x1=\"10\" y1=\"0\" x2=\"20\" y2=\"10\" stroke-dasharray=\"2 1\"/>\n"
                                           "<line x1=\"20\" y1=\"10\" x2=\"30\" y2=\"0\"/>\n"
                                           "<line x1=\"30\" y1=\"0\" x2=\"40\" y2=\"10\" style=\"stroke:#000;stroke-dasharray:4,2\"/>\n"
                                           "</g>\n<path d=\"M 100 110 l 20 0 h 20\" style=\"stroke-dasharray:none\"/>\n"));
  SvgImport import;
  import.margin = 0;
  const auto p = read_smocking_svg(file, import);
  ASSERT_EQ(p.threads.size(), 2u);
  const std::vector<Eigen::Vector2i> zigzag{{0, 1}, {1, 0}, {2, 1}, {3, 0}, {4, 1}};
  EXPECT_EQ(p.threads[0].points, zigzag);
  EXPECT_TRUE(p.threads[0].first_front);
  EXPECT_EQ(p.threads[0].line, 6);  // the first <line>, after the XML declaration, <svg>, <defs>, <circle> and <g>
  // The path at y = 110 is 3 grid squares (20 units) below the zigzag's top at 50: a front stitch, then a back one.
  EXPECT_EQ(p.threads[1].points, (std::vector<Eigen::Vector2i>{{0, 3}, {1, 3}, {2, 3}}));
  EXPECT_TRUE(p.threads[1].first_front);
  EXPECT_EQ(p.columns, 5);
  EXPECT_EQ(p.rows, 4);
}

TEST(SmockingSvg, ErrorsNameTheFileTheElementAndTheRule) {
  ScratchDir dir;
  EXPECT_NE(error_of_svg(dir, "<path id=\"w\" d=\"M0 0 C 10 10 20 10 30 0\"/>\n").find("<path id=\"w\"> on line 3 has a curve or arc (C)"), std::string::npos);
  EXPECT_NE(error_of_svg(dir, "<path d=\"M0 0 L 10 0 Z\"/>\n").find("closes (Z): a stitching path has two ends"), std::string::npos);
  EXPECT_NE(error_of_svg(dir, "<polygon points=\"0,0 10,0 10,10\"/>\n").find("is closed"), std::string::npos);
  const std::string same_side = "<line x2=\"10\" y2=\"10\"/>\n<line x1=\"10\" y1=\"10\" x2=\"20\"/>\n";
  EXPECT_NE(error_of_svg(dir, same_side).find("d.svg: line 4: <line> on line 4: stitch 2 of the thread that starts on line 3 is on the front like the one before it"),
            std::string::npos)
      << error_of_svg(dir, same_side);
  SvgImport ten;
  ten.grid = 10;
  const std::string off = "<line x2=\"10\"/><line x1=\"10\" x2=\"14\" y2=\"10\" stroke-dasharray=\"1\"/>\n";
  EXPECT_NE(error_of_svg(dir, off, ten).find("the point (14, 10) is 0.4 of a grid square (10) off the grid"), std::string::npos) << error_of_svg(dir, off, ten);
  EXPECT_NE(error_of_svg(dir, "<g transform=\"rotate(45)\"><line x2=\"10\"/></g>\n").find("the transform \"rotate\" with 1 numbers is not read"), std::string::npos);
  EXPECT_NE(error_of_svg(dir, "<line x1=\"a\" x2=\"10\"/>\n").find("x1 is not a number: \"a\""), std::string::npos);
  EXPECT_NE(error_of_svg(dir, "<rect width=\"10\" height=\"10\"/>\n").find("draws no stitching line"), std::string::npos);
  EXPECT_NE(error_of_svg(dir, "<line x2=\"10\">\n").find("line 4, column 3: is not well-formed XML: mismatched tag"), std::string::npos)
      << error_of_svg(dir, "<line x2=\"10\">\n");
  SvgImport canadian;
  canadian.style = Style::Canadian;
  EXPECT_NE(error_of_svg(dir, "<line x2=\"10\" stroke-dasharray=\"2\"/>\n", canadian).find("Canadian smocking is stitched on the front only"), std::string::npos);
  const std::string missing = skein::testing::error_of([] { read_smocking_svg("/no/such/drawing.svg"); });
  EXPECT_NE(missing.find("/no/such/drawing.svg: does not exist"), std::string::npos) << missing;
}

TEST(SmockingSvg, EveryBundledPatternWritesBackAsTextThatReadsTheSame) {
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(SKEIN_PATTERNS_DIR) / "smocking")) {
    if (e.path().extension() != ".smock") continue;
    SCOPED_TRACE(e.path().filename().string());
    const auto p = read_smocking_pattern(e.path());
    const auto q = parse_smocking_pattern(smocking_text(p), "written");
    EXPECT_EQ(q.name, p.name);
    EXPECT_EQ(q.style, p.style);
    EXPECT_EQ(q.columns, p.columns);
    EXPECT_EQ(q.rows, p.rows);
    EXPECT_EQ(q.spacing, p.spacing);
    EXPECT_EQ(q.gamma, p.gamma);
    ASSERT_EQ(q.threads.size(), p.threads.size());
    for (size_t t = 0; t < p.threads.size(); ++t) {
      EXPECT_EQ(q.threads[t].points, p.threads[t].points);
      EXPECT_EQ(q.threads[t].first_front, p.threads[t].first_front);
    }
  }
}
