// The commands' shared options (app/commands/options.h): the checks refuse what a user could
// mistype (NaN, a seed past 2^64-1, an empty value), the overrides land where the scene keeps
// them, and override_arguments hands a work unit exactly the overrides it was given.
#include "app/commands/options.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace arbor::app {
namespace {

// Parses `args` as `arbor render`'s overrides would be (every option offered).
RenderOverrides parsed(std::vector<std::string> args) {
  CLI::App app;
  RenderOverrides o;
  add_override_options(
      &app, o,
      kSppOption | kSeedOption | kIntegratorOption | kTransparentOption | kRegularizeOption,
      "samples");
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  app.parse(args);
  return o;
}

bool refused(const std::vector<std::string>& args) {
  try {
    parsed(args);
  } catch (const CLI::ParseError&) {
    return true;
  }
  return false;
}

TEST(Options, TheChecksRefuseWhatAUserCouldMistype) {
  EXPECT_TRUE(refused({"--time", "nan"}));
  EXPECT_TRUE(refused({"--time", "inf"}));
  EXPECT_TRUE(refused({"--time", "1000001"}));
  EXPECT_FALSE(refused({"--time", "-1000000"}));
  EXPECT_TRUE(refused({"--seed", "18446744073709551616"}));  // 2^64
  EXPECT_TRUE(refused({"--seed", "-1"}));
  EXPECT_TRUE(refused({"--seed", ""}));
  EXPECT_EQ(*parsed({"--seed", "18446744073709551615"}).seed, 18446744073709551615ull);
  EXPECT_TRUE(refused({"--integrator", "Path"}));
  EXPECT_TRUE(refused({"--integrator", "0"}));
  EXPECT_TRUE(refused({"--width", "0"}));
  EXPECT_TRUE(refused({"--spp", "1048577"}));
  // Ranges read as people write them.
  std::string v = "2e6";
  EXPECT_EQ(finite_in(-1e6, 1e6)(v), "2e6 is out of range [-1000000, 1000000]");
  std::string empty;
  EXPECT_FALSE(non_empty()(empty).empty());
}

TEST(Options, OverridesLandWhereTheSceneKeepsThem) {
  spec::SceneDesc s;
  s.trees.resize(2);
  apply_overrides(s, parsed({"--integrator", "treemaker", "--spp", "8", "--width", "33", "--time",
                             "2.5", "--seed", "9", "--transparent", "--lod"}));
  EXPECT_EQ(s.render.integrator, spec::Integrator::Treemaker);
  EXPECT_EQ(s.render.treemaker_spp, 8);  // the integrator in use's
  EXPECT_EQ(s.render.spp, spec::RenderSettings{}.spp);
  EXPECT_EQ(s.render.width, 33);
  EXPECT_EQ(s.render.height, spec::RenderSettings{}.height);
  EXPECT_EQ(s.render.seed, 9u);
  EXPECT_DOUBLE_EQ(s.trees[1].time, 2.5);
  EXPECT_TRUE(s.output.transparent_sky);
  EXPECT_TRUE(s.render.lod);
  EXPECT_FALSE(s.render.regularize);
  spec::SceneDesc path;
  apply_overrides(path, parsed({"--spp", "8"}));
  EXPECT_EQ(path.render.spp, 8);
}

TEST(Options, AWorkUnitGetsExactlyTheOverrides) {
  const RenderOverrides o =
      parsed({"--integrator", "treemaker", "--spp", "8", "--height", "20", "--time",
              "0.30000000000000004", "--seed", "18446744073709551615", "--regularize"});
  const RenderOverrides back = parsed(override_arguments(o));
  EXPECT_EQ(back.integrator, o.integrator);
  EXPECT_EQ(back.spp, 8);
  EXPECT_EQ(back.height, 20);
  EXPECT_EQ(back.width, 0);
  EXPECT_EQ(back.seed, o.seed);
  EXPECT_EQ(*back.time, 0.1 + 0.2);  // exactly, not 0.3
  EXPECT_TRUE(back.regularize);
  EXPECT_FALSE(back.transparent);
  EXPECT_TRUE(override_arguments(RenderOverrides{}).empty());
}

}  // namespace
}  // namespace arbor::app
