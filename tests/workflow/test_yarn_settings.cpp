// A project's yarn settings: set yarn.KEY lines read, written and refused.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "relax/yarn_relax.hpp"
#include "workflow/yarn_settings.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;
using Eigen::Vector3d;

TEST(YarnSettings, WrittenAsProjectLinesTheyReadBackTheSame) {
  YarnSettings s;
  s.relax.method = YarnMethod::Euler;
  s.relax.tolerance = 0.0035;
  s.relax.max_steps = 1234;
  s.take_up = 0.9;
  s.relax.audit = false;
  s.relax.active_set.enabled = true;
  s.relax.sampling.spacing = 2.2;
  s.relax.jam_steps = 0;
  s.relax.clipped_scale = true;
  s.local.rings = 2;
  s.local.halo = 3;
  s.weight = "worsted";
  const auto lines = yarn_setting_lines(s);
  EXPECT_EQ(lines.size(), 12u);
  const auto back = read_yarn_settings(lines, "p.skein");
  EXPECT_EQ(back.relax.method, s.relax.method);
  EXPECT_EQ(back.relax.tolerance, s.relax.tolerance);
  EXPECT_EQ(back.relax.max_steps, s.relax.max_steps);
  EXPECT_EQ(back.take_up, s.take_up);
  EXPECT_EQ(back.relax.audit, s.relax.audit);
  EXPECT_EQ(back.relax.active_set.enabled, s.relax.active_set.enabled);
  EXPECT_EQ(back.relax.sampling.spacing, s.relax.sampling.spacing);
  EXPECT_EQ(back.relax.jam_steps, s.relax.jam_steps);
  EXPECT_EQ(back.relax.clipped_scale, s.relax.clipped_scale);
  EXPECT_EQ(back.local.rings, s.local.rings);
  EXPECT_EQ(back.local.halo, s.local.halo);
  EXPECT_EQ(back.weight, "worsted");
  // A project without settings: the defaults (no yarn weight: written as none). A weight by alias or CYC number.
  const auto none = read_yarn_settings({}, "p.skein");
  EXPECT_EQ(none.relax.tolerance, YarnRelaxOptions{}.tolerance);
  EXPECT_EQ(none.take_up, 1.0);
  EXPECT_EQ(none.weight, "");
  for (const auto& line : yarn_setting_lines(none))
    if (line.key == "yarn.weight") {
      EXPECT_EQ(line.value, "none");
    }
  EXPECT_EQ(read_yarn_settings({{"yarn.weight", "aran", 3}}, "p.skein").weight, "worsted");
  EXPECT_EQ(read_yarn_settings({{"yarn.weight", "3", 3}}, "p.skein").weight, "dk");
}

TEST(YarnSettings, BadLinesNameTheFileTheLineAndTheRule) {
  const std::vector<std::pair<mesh::ProjectSetting, std::string>> cases{
      {{"yarn.colour", "red", 7}, "'yarn.colour' is not a setting this skein knows"},
      {{"yarn.tolerance", "tight", 7}, "'tight' is not a number"},
      {{"yarn.max_steps", "1.5", 7}, "'1.5' is not an integer"},
      {{"yarn.audit", "yes", 7}, "neither true nor false"},
      {{"yarn.method", "verlet", 7}, "verlet"},
      {{"yarn.take_up", "20", 7}, "yarn.take_up: must be in [0.1, 10], found 20"},
      {{"yarn.jam_steps", "-3", 7}, "yarn.jam_steps: must be in [0, 1e+09] steps, found -3"},
      {{"yarn.stop_scale", "median", 7}, "'median' is not first or clipped"},
      {{"yarn.weight", "wool", 7}, "'wool' is not a yarn weight; one of lace, fingering"},
  };
  for (const auto& [line, rule] : cases) {
    const std::string msg = skein::testing::error_of([&] { read_yarn_settings({line}, "p.skein"); });
    EXPECT_NE(msg.find("p.skein"), std::string::npos) << msg;
    EXPECT_NE(msg.find("line 7"), std::string::npos) << msg;
    EXPECT_NE(msg.find(rule), std::string::npos) << msg;
  }
}
