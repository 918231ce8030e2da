// The up-front memory estimate: absurd sizes are refused before anything is allocated.
#include "scene/render_budget.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "common/error.h"

namespace arbor::scene {
namespace {

// A film's costs as tracer/film.h states them (Film::costs(); tests/tracer/film_test.cpp checks
// that they are a real film's): the estimate's arithmetic is tested here, the film's sizes there.
constexpr FilmCosts kFilm{88, 8, 8, 16, 7, 23};

TEST(RenderBudget, EstimateGrowsWithPixelsChannelsAndTrees) {
  spec::SceneDesc s;
  s.render.width = 1000;
  s.render.height = 1000;
  const MemoryEstimate plain = estimate_render_memory(s, kFilm);
  // What was measured (render_budget.h: about 225 bytes a pixel over the baseline with the beauty
  // alone), rounded up but by no more than a fifth: an estimate far above the real need would
  // refuse renders that fit.
  EXPECT_GE(plain.image_bytes, 225u * 1000000u);
  EXPECT_LE(plain.image_bytes, 270u * 1000000u);
  s.output.aovs = {};
  for (imaging::Aov a :
       {imaging::Aov::Albedo, imaging::Aov::Normal, imaging::Aov::Depth, imaging::Aov::Variance})
    s.output.aovs.add(a);
  const MemoryEstimate aovs = estimate_render_memory(s, kFilm);
  EXPECT_GE(aovs.image_bytes, 106u * 1000000u);
  EXPECT_GT(aovs.image_bytes, plain.image_bytes);
  s.output.aovs = {};
  s.output.aovs.add(imaging::Aov::Treemaker);
  EXPECT_GE(estimate_render_memory(s, kFilm).image_bytes, 257u * 1000000u);
  spec::ForestDesc f;
  f.count = 100000;
  s.forests = {f, f};
  s.trees.resize(3);
  const MemoryEstimate forest = estimate_render_memory(s, kFilm);
  EXPECT_EQ(forest.instances, 200003u);
  EXPECT_GE(forest.instance_bytes, 700u * 200003u);
}

TEST(RenderBudget, TheLargestImageIsRefusedUnlessForced) {
  spec::SceneDesc s;
  s.path = "big.toml";
  s.render.width = s.render.height = 16384;
  s.output.aovs = {};
  for (imaging::Aov a :
       {imaging::Aov::Albedo, imaging::Aov::Normal, imaging::Aov::Depth, imaging::Aov::Variance})
    s.output.aovs.add(a);
  // 268 million pixels at over 100 bytes each: more than any machine of CI's kind has.
  ASSERT_GT(estimate_render_memory(s, kFilm).total(), usable_memory_bytes());
  try {
    check_render_memory(s, kFilm, false);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().path, "big.toml");
    EXPECT_NE(e.message().find("16384x16384"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("--force"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(check_render_memory(s, kFilm, true));
  s.render.width = s.render.height = 1024;
  EXPECT_NO_THROW(check_render_memory(s, kFilm, false));
}

// The largest forest count the scene allows needs about 10 GB: refused on a machine (or under a
// ulimit) of 8 GB, at the forest's table.
TEST(RenderBudget, TheLargestForestIsRefusedWhereItDoesNotFit) {
  spec::SceneDesc s;
  s.path = "forest.toml";
  s.render.width = s.render.height = 8;
  spec::ForestDesc f;
  f.count = 10000000;
  f.where = {"forest.toml", 5, 1};
  s.forests = {f};
  const std::uint64_t eight_gb = 8ull << 30;
  try {
    check_render_memory(s, kFilm, false, eight_gb);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 5);
    EXPECT_NE(e.message().find("10000000 trees"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(check_render_memory(s, kFilm, true, eight_gb));
  EXPECT_NO_THROW(check_render_memory(s, kFilm, false, 16ull << 30));
}

// ulimit -v and -d lower what a render may use below the physical memory.
TEST(RenderBudget, TheProcessLimitsLowerTheUsableMemory) {
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const rlimit limit{3ull << 30, 3ull << 30};
    if (setrlimit(RLIMIT_DATA, &limit) != 0) _exit(3);
    _exit(usable_memory_bytes() == (3ull << 30) ? 0 : 1);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_GT(usable_memory_bytes(), 1ull << 30);  // this machine's own memory, over a gigabyte
}

}  // namespace
}  // namespace arbor::scene
