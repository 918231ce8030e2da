// The up-front memory estimate: absurd sizes are refused before anything is allocated.
#include "tracer/render_budget.h"

#include <gtest/gtest.h>

#include "common/error.h"

namespace arbor::trace {
namespace {

TEST(RenderBudget, EstimateGrowsWithPixelsChannelsAndTrees) {
  SceneDesc s;
  s.render.width = 1000;
  s.render.height = 1000;
  const MemoryEstimate plain = estimate_render_memory(s);
  // At least what was measured (77 bytes a pixel with the beauty alone).
  EXPECT_GE(plain.image_bytes, 77u * 1000000u);
  s.output.aovs = {"albedo", "normal", "depth", "variance"};
  const MemoryEstimate aovs = estimate_render_memory(s);
  EXPECT_GE(aovs.image_bytes, 106u * 1000000u);
  EXPECT_GT(aovs.image_bytes, plain.image_bytes);
  s.output.aovs = {"treemaker"};
  EXPECT_GE(estimate_render_memory(s).image_bytes, 257u * 1000000u);
  ForestDesc f;
  f.count = 100000;
  s.forests = {f, f};
  s.trees.resize(3);
  const MemoryEstimate forest = estimate_render_memory(s);
  EXPECT_EQ(forest.instances, 200003u);
  EXPECT_GE(forest.instance_bytes, 700u * 200003u);
}

TEST(RenderBudget, TheLargestImageIsRefusedUnlessForced) {
  SceneDesc s;
  s.path = "big.toml";
  s.render.width = s.render.height = 16384;
  s.output.aovs = {"albedo", "normal", "depth", "variance"};
  // 268 million pixels at over 100 bytes each: more than any machine of CI's kind has.
  ASSERT_GT(estimate_render_memory(s).total(), usable_memory_bytes());
  try {
    check_render_memory(s, false);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().path, "big.toml");
    EXPECT_NE(e.message().find("16384x16384"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("--force"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(check_render_memory(s, true));
  s.render.width = s.render.height = 1024;
  EXPECT_NO_THROW(check_render_memory(s, false));
}

}  // namespace
}  // namespace arbor::trace
