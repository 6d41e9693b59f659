// The yarn options' one schema: every option's range, default and help, the same everywhere.
#include <gtest/gtest.h>

#include <set>

#include "common/error.hpp"
#include "relax/yarn_relax.hpp"
#include "workflow/yarn_options.hpp"
#include "workflow/yarn_settings.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;
using Eigen::Vector3d;

TEST(YarnOptions, EachOptionHasOneRangeAndItsDefaultIsInIt) {
  const YarnSettings defaults;
  std::set<std::string> keys;
  for (const auto& option : yarn_options()) {
    SCOPED_TRACE(option.key);
    EXPECT_TRUE(keys.insert(option.key).second);  // declared once
    EXPECT_FALSE(option.help.empty());
    EXPECT_EQ(&yarn_option(option.key), &option);
    // The default reads back as itself.
    YarnSettings copy = defaults;
    option.set(copy, option.get(defaults));
    EXPECT_EQ(option.get(copy), option.get(defaults));
    if (option.kind != YarnOption::Kind::Number && option.kind != YarnOption::Kind::Integer) continue;
    EXPECT_TRUE(option.allows(std::stod(option.get(defaults))));
    EXPECT_TRUE(option.allows(option.high));
    EXPECT_EQ(option.allows(option.low), !option.above_low);
    EXPECT_FALSE(option.allows(option.high * 2 + 1));
    EXPECT_FALSE(option.allows(option.low - 1));
    // A project line past the range is refused, naming the key and the range.
    if (!option.in_project) continue;
    const std::string too_big = option.kind == YarnOption::Kind::Integer ? std::to_string(static_cast<long>(option.high) + 1) : "1e12";
    const std::string msg = skein::testing::error_of([&] { read_yarn_settings({{"yarn." + option.key, too_big, 3}}, "p.skein"); });
    EXPECT_NE(msg.find("yarn." + option.key + ": must be in " + option.range()), std::string::npos) << msg;
  }
  EXPECT_THROW(yarn_option("colour"), Error);
}
