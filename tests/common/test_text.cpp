// The text readers' shared line and word reading (common/text.hpp).
#include <gtest/gtest.h>

#include <sstream>

#include "common/error.hpp"
#include "common/text.hpp"

using namespace skein;

TEST(LineReader, NumbersLinesDropsAByteOrderMarkAndCarriageReturns) {
  std::istringstream in("\xEF\xBB\xBF" "format knit\r\nk p\r\n\nlast");
  LineReader reader(in, "a.knit");
  std::vector<std::pair<int, std::string>> lines;
  while (reader.next()) lines.emplace_back(reader.number(), reader.line());
  const std::vector<std::pair<int, std::string>> expected{{1, "format knit"}, {2, "k p"}, {3, ""}, {4, "last"}};
  EXPECT_EQ(lines, expected);
  // A mark is only a mark before the first line.
  std::istringstream later("a\n\xEF\xBB\xBF" "b\n");
  LineReader second(later, "b.knit");
  ASSERT_TRUE(second.next() && second.next());
  EXPECT_EQ(second.line(), "\xEF\xBB\xBF" "b");
}

TEST(LineReader, ALineLongerThanItsBoundIsRefusedNamingFileAndLine) {
  std::istringstream in("short\n" + std::string(41, 'x') + "\n");
  LineReader reader(in, "long.txt", 40);
  ASSERT_TRUE(reader.next());
  try {
    reader.next();
    FAIL() << "a 41-character line passed a bound of 40";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "long.txt: line 2: is longer than 40 characters");
  }
  std::istringstream exact(std::string(40, 'x') + "\r\n");  // the carriage return does not count
  LineReader fits(exact, "exact.txt", 40);
  EXPECT_TRUE(fits.next());
}

TEST(LineReader, FailNamesTheColumnWhenGivenOne) {
  std::istringstream in("one\ntwo words\n");
  LineReader reader(in, "f.txt");
  reader.next();
  reader.next();
  EXPECT_EQ(reader.place(5), "line 2, column 5");
  EXPECT_EQ(text_place(3), "line 3");
  try {
    reader.fail("unknown word 'words'", 5);
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "f.txt: line 2, column 5: unknown word 'words'");
  }
}

TEST(Split, WordsKeepTheirOneBasedColumns) {
  const auto words = split("  k2tog\tyo  ssk\r");
  ASSERT_EQ(words.size(), 3u);
  EXPECT_EQ(words[0].text, "k2tog");
  EXPECT_EQ(words[0].column, 3);
  EXPECT_EQ(words[1].text, "yo");
  EXPECT_EQ(words[1].column, 9);
  EXPECT_EQ(words[2].text, "ssk");
  EXPECT_EQ(words[2].column, 13);
  EXPECT_EQ(trim(" \t x y \r"), "x y");
  EXPECT_EQ(lower("K2TOG"), "k2tog");
}
