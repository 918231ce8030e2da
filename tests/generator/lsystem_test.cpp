// Tests of the L-system language and its turtle.
#include "generator/models/lsystem/lsystem.h"

#include <cmath>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "expect_input_error.h"

#include "generator/grow.h"
#include "generator/export/tree_stats.h"
#include "formats/lsystem_file.h"
#include "formats/species_file.h"

namespace arbor::generator {

namespace {

void expect_error(const std::string& text, int line, int column, const std::string& fragment) {
  testing::expect_input_error([&] { formats::parse_lsystem(text, "t.lsys"); }, "t.lsys", line,
                              column, fragment);
}

Skeleton grow(const std::string& text, std::uint64_t seed = 1) {
  LSystemOptions o;
  o.seed = seed;
  return grow_lsystem(formats::parse_lsystem(text, "t.lsys"), o);
}

}  // namespace

TEST(LSystem, IterationsBoundTheRecursion) {
  // A: f[+A][-A] draws 2^(n+1) - 1 segments with n iterations.
  for (int n : {0, 1, 2, 5}) {
    const Skeleton sk = grow("iterations = " + std::to_string(n) + ";\nA: f[+A][-A];\n");
    long long segments = 0;
    for (const Stem& s : sk.stems) segments += s.point_count - 1;
    EXPECT_EQ(segments, (1LL << (n + 1)) - 1) << n;
    EXPECT_EQ(validate(sk), "");
  }
  EXPECT_DOUBLE_EQ(
      estimate_segments(formats::parse_lsystem("iterations = 5;\nA: f[+A][-A];\n", "t")), 63.0);
}

TEST(LSystem, TurtleStepsTurnsAndMultipliers) {
  // f(2) at step 0.5 then a 90° left turn and f: ends at (1, 0, 1) (turning toward +x, "left").
  const Skeleton sk = grow("step = 0.5;\nangle = 90;\nA: f(2) + f;\n");
  ASSERT_EQ(sk.stems.size(), 1u);
  const glm::vec3 end = sk.points[sk.stems[0].first_point + 2].position;
  EXPECT_NEAR(end.x, 0.5f, 1e-6f);
  EXPECT_NEAR(end.z, 1.0f, 1e-6f);
  // s multiplies the step; u multiplies the + angle; r the radius.
  const Skeleton m = grow("step = 1;\nangle = 90;\nradius = 0.1;\nA: s(0.5) u(0.5) + r(0.5) f;\n");
  const glm::vec3 p = m.points[m.stems[0].first_point + 1].position;
  EXPECT_NEAR(p.x, 0.5f * std::sin(0.7853982f), 1e-6f);
  EXPECT_NEAR(p.z, 0.5f * std::cos(0.7853982f), 1e-6f);
  EXPECT_NEAR(m.points[m.stems[0].first_point + 1].radius, 0.05f, 1e-7f);
  // A number after a turn is its angle in degrees.
  const Skeleton d = grow("A: ^(90) f;\n");
  const glm::vec3 q = d.points[d.stems[0].first_point + 1].position;
  EXPECT_NEAR(q.y, 1.0f, 1e-6f);  // pitched up toward the turtle's up (+y)
}

TEST(LSystem, BranchesStartAtTheirParentsPointAndRestoreTheTurtle) {
  const Skeleton sk = grow("angle = 90;\nA: f [+f] [-f] f;\n");
  ASSERT_EQ(sk.stems.size(), 3u);
  EXPECT_EQ(validate(sk), "");
  for (int c = 1; c <= 2; ++c) {
    const Stem& child = sk.stems[static_cast<size_t>(c)];
    EXPECT_EQ(child.parent, 0);
    EXPECT_EQ(child.parent_point, 1);
    EXPECT_EQ(child.level, 1);
  }
  // After the branches the trunk goes on straight up.
  const glm::vec3 top = sk.points[sk.stems[0].first_point + 2].position;
  EXPECT_NEAR(top.z, 2.0f, 1e-6f);
  EXPECT_NEAR(top.x, 0.0f, 1e-6f);
}

TEST(LSystem, SameSeedSameTreeAndRandomnessVaries) {
  const std::string text = "iterations = 4;\nrandomness = 0.2;\nA: f[+A][-A];\n";
  const Skeleton a = grow(text, 3), b = grow(text, 3), c = grow(text, 4);
  ASSERT_EQ(a.points.size(), b.points.size());
  EXPECT_EQ(std::memcmp(a.points.data(), b.points.data(), a.points.size() * sizeof(SkeletonPoint)),
            0);
  EXPECT_NE(std::memcmp(a.points.data(), c.points.data(), a.points.size() * sizeof(SkeletonPoint)),
            0);
}

TEST(LSystem, RuleWeightsChooseAlternativesInProportion) {
  // B(3): f and B(1): f f — the first is chosen about 3 times in 4.
  const LSystem s = formats::parse_lsystem(
      "iterations = 1;\nA: f[B][B][B][B][B][B][B][B];\nB(3): f;\nB(1): f f;\n", "t");
  long long one = 0, two = 0;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    LSystemOptions o;
    o.seed = seed;
    for (const Stem& st : grow_lsystem(s, o).stems) {
      if (st.level == 1) (st.point_count == 2 ? one : two) += 1;
    }
  }
  EXPECT_NEAR(double(one) / double(one + two), 0.75, 0.03);
}

TEST(LSystem, AbsurdSizesAreRefusedWithTheEstimate) {
  const LSystem s = formats::parse_lsystem("iterations = 30;\nA: f[+A][-A][^A];\n", "t");
  try {
    grow_lsystem(s, LSystemOptions{});
    FAIL() << "an absurd L-system was grown";
  } catch (const RuntimeFailure& e) {
    EXPECT_NE(std::string(e.what()).find("about 3.09e+14 segments"), std::string::npos) << e.what();
  }
}

TEST(LSystem, RecursionThatDrawsNothingIsRefusedNotHung) {
  // Draws no segment but would expand 2^64 rules: refused at once with the estimate.
  const LSystem s = formats::parse_lsystem("iterations = 64;\nA: A A;\n", "t");
  try {
    grow_lsystem(s, LSystemOptions{});
    FAIL() << "an unbounded recursion was accepted";
  } catch (const RuntimeFailure& e) {
    EXPECT_NE(std::string(e.what()).find("actions"), std::string::npos) << e.what();
  }
}

TEST(LSystem, SeveralTrunksAreRefused) {
  try {
    grow("A: [f][f];\n");
    FAIL() << "two roots were accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 1);
    EXPECT_EQ(e.where().column, 8);
  }
}

TEST(LSystem, ShippedExamplesGrowValidTrees) {
  for (const char* name : {"lsystem_2d_branching", "lsystem_weed", "lsystem_bush",
                           "lsystem_realistic_tree", "lsystem_almost_real"}) {
    const Species sp =
        formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/" + name + ".lsys");
    GrowOptions o;
    const Skeleton sk = grow_tree(sp, o);
    EXPECT_EQ(validate(sk), "") << name;
    EXPECT_GT(sk.stems.size(), 10u) << name;
    EXPECT_GT(compute_stats(sk).height, 1.0) << name;
  }
}

// 50,000 nested brackets once overflowed the stack: the nesting is bounded with a positioned
// error, and the deepest nesting allowed still grows at the most iterations allowed.
TEST(LSystem, DeepNestingIsRefusedAndTheDeepestAllowedGrows) {
  const std::string deep = "A: f" + std::string(50000, '[') + "f" + std::string(50000, ']') + ";\n";
  expect_error(deep, 1, 105, "nested more than 100 deep");
  const std::string limit =
      "iterations = 64;\nA: f" + std::string(100, '[') + "f A" + std::string(100, ']') + ";\n";
  const Skeleton sk = grow(limit);
  EXPECT_EQ(validate(sk), "");
  EXPECT_EQ(sk.stems.size(), 66u);  // the trunk and one branch per depth 0..64
  expect_error("A: f" + std::string(101, '[') + "f" + std::string(101, ']') + ";\n", 1, 105,
               "nested more than 100");
}

// Found by fuzzing: s(1e23) sent the turtle past float range (NaN and inf geometry), and a
// move of length 0 made a limb segment with no direction.
TEST(LSystem, MovesOutOfRangeOrOfNoLengthAreRefusedAtTheAction) {
  auto expect_grow_error = [](const std::string& text, int line, int column,
                              const std::string& fragment) {
    testing::expect_input_error([&] { grow(text); }, "t.lsys", line, column, fragment);
  };
  expect_grow_error("A: f s(99999999999999999999999) f;\n", 1, 33,
                    "more than 1000 km from the root");
  expect_grow_error("iterations = 64;\nA: s(3) f A;\n", 2, 9, "more than 1000 km");
  expect_grow_error("A: f f(0);\n", 1, 6, "limb segments must be at least 1 micrometre");
  expect_grow_error("iterations = 40;\nA: f s(0.5) A;\n", 2, 4, "at least 1 micrometre");
}

}  // namespace arbor::generator
