// Tests of TREE-MAKER templates: the paper's dogwood parses as Figure 6 describes, and every
// malformed input is refused with its position.
#include "generator/models/treemaker/treemaker_template.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "generator/grow.h"
#include "formats/skeleton_file.h"
#include "generator/geometry/tree_geometry.h"
#include "generator/export/tree_stats.h"
#include "generator/models/treemaker/treemaker.h"

#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "treemaker_snippets.h"
#include "generator/species.h"
#include "formats/species_file.h"
#include "formats/treemaker_template.h"
#include "generator/export/skeleton_file.h"

namespace arbor::generator {

namespace {

void expect_error(const std::string& text, int line, int column, const std::string& fragment) {
  testing::expect_input_error([&] { formats::parse_treemaker_template(text, "t.tmpl"); }, "t.tmpl",
                              line, column, fragment);
}

}  // namespace

namespace {

Skeleton grow_template(const std::string& text, std::uint64_t seed = 1) {
  TreeMakerOptions o;
  o.seed = seed;
  return grow_treemaker(formats::parse_treemaker_template(text, "t.tmpl"), o);
}

Skeleton dogwood(std::uint64_t seed) {
  const Species s = formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/dogwood.tmpl");
  GrowOptions o;
  o.seed = seed;
  return grow_tree(s, o);
}

// A straight trunk growing 10 units (10 cm) a step for 5 iterations, no branching.
std::string trunk(const std::string& extra_particle = "", const std::string& gravity = "0") {
  return "iterations { i= 5 }\ngravity { g= " + gravity + " }\n" + testing::kTmColor +
         "branch { level= 1 number= 0 to 0.5 (p=1 angle= 90 to 90 dir= 0 to 0 factor= 1 to 1) }\n"
         "particle { pos=0,0,0 mag= 10 to 10 dir= 0,0,1:0 growth= 0.5 color= green " +
         extra_particle + " }\n" + testing::kTmLeaf;
}

}  // namespace

TEST(TreeMakerGrowth, TheDogwoodGrowsAValidTreeWithLeavesAndFlowers) {
  long long green = 0, white = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Skeleton sk = dogwood(seed);
    ASSERT_EQ(validate(sk), "") << "seed " << seed;
    const TreeStats st = compute_stats(sk);
    // Level 1: number = 2 to 3, truncated: 2 at each of the trunk's 13 segments; the 2 born in
    // the last iteration never grow (no length) and are left out.
    EXPECT_EQ(st.stems_per_level[1], 24) << "seed " << seed;
    EXPECT_GT(st.height, 1.0);
    EXPECT_LT(st.height, 4.0);
    // One leaf per branch end (§II): leaves (green, two triangles) or flowers (five, white first).
    std::int32_t last = -1;
    for (const LeafTriangle& t : sk.leaf_triangles) {
      if (t.leaf == last) continue;
      last = t.leaf;
      (t.color.x > 0.5f ? white : green) += 1;
    }
  }
  // p = 0.6 leaves, 0.4 flowers.
  EXPECT_NEAR(double(green) / double(green + white), 0.6, 0.05);
}

TEST(TreeMakerGrowth, ParticlesAddSegmentsAndWidenTheirLimbs) {
  const Skeleton sk = grow_template(trunk());
  ASSERT_EQ(sk.stems.size(), 1u);
  const Stem& t = sk.stems[0];
  ASSERT_EQ(t.point_count, 6u);  // 5 stored positions and the end
  for (std::uint32_t k = 0; k < t.point_count; ++k) {
    EXPECT_NEAR(sk.points[t.first_point + k].position.z, 0.1f * k, 1e-6f);
  }
  // Widths: every stored position widens by growth each iteration: the base by 5 × 0.5 cm.
  EXPECT_NEAR(sk.points[t.first_point].radius, 0.5f * 2.5f * 0.01f, 1e-7f);
  EXPECT_NEAR(sk.points[t.first_point + 4].radius, 0.5f * 0.5f * 0.01f, 1e-7f);
  EXPECT_EQ(sk.points[t.first_point + 5].radius, 0.0f);
}

TEST(TreeMakerGrowth, AgingShortensTheGrowthVector) {
  const Skeleton sk = grow_template(trunk("acc= -2"));
  const Stem& t = sk.stems[0];
  for (std::uint32_t k = 1; k < t.point_count; ++k) {
    const float step =
        sk.points[t.first_point + k].position.z - sk.points[t.first_point + k - 1].position.z;
    EXPECT_NEAR(step, 0.01f * (10.0f - 2.0f * (k - 1)), 1e-6f);
  }
}

TEST(TreeMakerGrowth, GravityPullsHorizontalGrowthDown) {
  auto end_height = [](const std::string& g) {
    const std::string text =
        "iterations { i= 8 }\ngravity { g= " + g + " }\n" + testing::kTmColor +
        "branch { level= 1 number= 0 to 0.5 (p=1 angle= 90 to 90 dir= 0 to 0 factor= 1 to 1) }\n"
        "particle { pos=0,0,1 mag= 10 to 10 dir= 1,0,0:0 color= green }\n" +
        testing::kTmLeaf;
    const Skeleton sk = grow_template(text);
    return sk.points[sk.stems[0].first_point + sk.stems[0].point_count - 1].position.z;
  };
  EXPECT_NEAR(end_height("0"), 0.01f, 1e-6f);
  EXPECT_LT(end_height("2"), 0.009f);
  EXPECT_LT(end_height("4"), end_height("2"));
}

TEST(TreeMakerGrowth, BranchesLeaveAtTheRuleAngleFromTheHorizontalDirection) {
  // Every branch at 90° from a vertical trunk, dir 90: straight "up" in the turtle's sense, i.e.
  // horizontal (the trunk is vertical), and the branch ends are all at its birth height.
  const std::string text =
      "iterations { i= 3 }\n" + testing::kTmColor +
      "branch { level= 1 number= 1 to 1 (p=1 angle= 90 to 90 dir= 0 to 360 factor= 1 to 1) }\n"
      "branch { level= 2 number= 0 to 0.5 (p=1 angle= 10 to 10 dir= 0 to 0 factor= 1 to 1) }\n"
      "particle { pos=0,0,0 mag= 10 to 10 dir= 0,0,1:0 color= green }\n" +
      testing::kTmLeaf;
  const Skeleton sk = grow_template(text);
  int branches = 0;
  for (const Stem& s : sk.stems) {
    if (s.level != 1) continue;
    const glm::vec3 a = sk.points[s.first_point].position,
                    b = sk.points[s.first_point + s.point_count - 1].position;
    EXPECT_NEAR(b.z, a.z, 1e-5f);
    ++branches;
  }
  EXPECT_EQ(branches, 2);  // born in iterations 1 and 2 (the last one's never grows)
}

TEST(TreeMakerGrowth, SameSeedSameTreeAndRoundTripsThroughSkeletonFiles) {
  const Skeleton a = dogwood(5), b = dogwood(5), c = dogwood(6);
  ASSERT_EQ(a.points.size(), b.points.size());
  EXPECT_EQ(std::memcmp(a.points.data(), b.points.data(), a.points.size() * sizeof(SkeletonPoint)),
            0);
  EXPECT_NE(a.points.size() == c.points.size() &&
                std::memcmp(a.points.data(), c.points.data(),
                            a.points.size() * sizeof(SkeletonPoint)) == 0,
            true);
  const std::string path = ::testing::TempDir() + "dogwood.skel";
  write_skeleton_file(a, path);
  const Skeleton back = formats::parse_skeleton_file(formats::read_text_file(path), path);
  ASSERT_EQ(back.stems.size(), a.stems.size());
  ASSERT_EQ(back.leaf_triangles.size(), a.leaf_triangles.size());
  for (std::size_t i = 0; i < a.stems.size(); ++i) {
    ASSERT_EQ(back.stems[i].parent, a.stems[i].parent);
    ASSERT_EQ(back.stems[i].parent_point, a.stems[i].parent_point);
    ASSERT_EQ(back.stems[i].color, a.stems[i].color);
  }
  EXPECT_EQ(back.leaf_triangles[7].color, a.leaf_triangles[7].color);
  EXPECT_EQ(back.leaf_triangles[7].v[2], a.leaf_triangles[7].v[2]);
}

TEST(TreeMakerGrowth, SeveralParticlesFromOnePointMakeAShrub) {
  const std::string two = testing::kTmColor + testing::kTmRule + testing::kTmParticle +
                          "particle { pos=0,0,0 mag= 8 to 9 dir= 1,0,1:5 color= green }\n" +
                          testing::kTmLeaf;
  const Skeleton sk = grow_template("iterations { i= 4 }\n" + two);
  EXPECT_EQ(validate(sk), "");
  int from_root = 0;
  for (const Stem& s : sk.stems) from_root += (s.parent == 0 && s.parent_point == 0) ? 1 : 0;
  EXPECT_GE(from_root, 1);
  const std::string apart = testing::kTmColor + testing::kTmRule + testing::kTmParticle +
                            "particle { pos=5,0,0 mag= 8 to 9 dir= 0,0,1:5 color= green }\n" +
                            testing::kTmLeaf;
  testing::expect_input_error([&] { grow_template(apart); }, "t.tmpl", 4, 1, "one root");
}

TEST(TreeMakerGrowth, LeafLinesBecomeThinLimbs) {
  const std::string text = "iterations { i= 2 }\n" + testing::kTmColor + testing::kTmRule +
                           testing::kTmParticle +
                           "leaf { p= 1 coord= limb out= 0 up= 0 color= green ln= 0,0,0 0,0,5 }\n";
  const Skeleton sk = grow_template(text);
  ASSERT_GT(sk.leaf_lines.size(), 0u);
  EXPECT_NEAR(glm::length(sk.leaf_lines[0].b - sk.leaf_lines[0].a), 0.05f, 1e-5f);
  const TreeGeometry g = build_tree_geometry(sk);
  int thin = 0;
  for (std::size_t i = 0; i < g.curves.size(); ++i) thin += g.curves.segments[i].limb < 0 ? 1 : 0;
  EXPECT_EQ(thin, static_cast<int>(sk.leaf_lines.size()));
}

TEST(TreeMakerGrowth, AbsurdTemplatesAreRefusedWithTheEstimate) {
  const std::string text =
      "iterations { i= 40 }\n" + testing::kTmColor +
      "branch { level= 1 number= 3 to 4 (p=1 angle= 30 to 40 dir= 0 to 360 factor= 1 to 1) }\n" +
      testing::kTmParticle + testing::kTmLeaf;
  try {
    grow_template(text);
    FAIL();
  } catch (const RuntimeFailure& e) {
    EXPECT_NE(std::string(e.what()).find("could grow about"), std::string::npos) << e.what();
  }
}

// The estimate is the most branches the rules allow: with up to 3 new branches per branch and
// iteration, f(n) = 1 + 3 Σ_{r<n} f(r) = 4^(n-1) for n iterations left, times the particles.
TEST(TreeMakerGrowth, TheSizeEstimateCountsTheMostBranchesTheRulesAllow) {
  for (int i : {1, 2, 3, 6}) {
    const std::string text = "iterations { i= " + std::to_string(i) + " }\n" + testing::kTmColor +
                             "branch { level= 1 number= 2 to 3.5 (p=1 angle= 30 to 40 dir= 0 to "
                             "360 factor= 1 to 1) }\n" +
                             testing::kTmParticle + testing::kTmParticle + testing::kTmLeaf;
    EXPECT_DOUBLE_EQ(treemaker_estimate(formats::parse_treemaker_template(text, "t.tmpl")),
                     2.0 * std::pow(4.0, i))
        << i;
  }
  // A second rule from level 3 on, allowing none.
  const std::string two =
      "iterations { i= 3 }\n" + testing::kTmColor +
      "branch { level= 1 number= 3 to 3 (p=1 angle= 30 to 40 dir= 0 to 360 factor= 1 to 1) }\n"
      "branch { level= 3 number= 0 to 0.5 (p=1 angle= 30 to 40 dir= 0 to 360 factor= 1 to 1) }\n" +
      testing::kTmParticle + testing::kTmLeaf;
  // Level 0 (the particle) with 4 iterations left: 1 + 3 [f1(1) + f1(2) + f1(3)], where level-1
  // branches spawn level-2 ones by the first rule (3 each) and level-2 branches spawn level-3
  // ones by the second (0 each): f2 = 1, f1(n) = 1 + 3 (n - 1), so 1 + 3 (1 + 4 + 7) = 37.
  EXPECT_DOUBLE_EQ(treemaker_estimate(formats::parse_treemaker_template(two, "t.tmpl")), 37.0);
}

// i= 1000 (the largest allowed) with deep rules once spent a minute estimating before refusing.
TEST(TreeMakerGrowth, TheLargestTemplateIsRefusedAtOnce) {
  std::string text = "iterations { i= 1000 }\n" + testing::kTmColor;
  for (int level = 1; level <= 1000; level += 37) {
    text += "branch { level= " + std::to_string(level) +
            " number= 1 to 2 (p=1 angle= 30 to 40 dir= 0 to 360 factor= 1 to 1) }\n";
  }
  text += testing::kTmParticle + testing::kTmLeaf;
  EXPECT_THROW(grow_template(text), RuntimeFailure);
}

// Found by fuzzing (tests/fuzz/regressions/): a branch born where its parent began is moved to
// the grandparent, and once started thicker than the grandparent there (an invalid skeleton).
TEST(TreeMakerGrowth, ABranchMovedToItsGrandparentStartsNoThickerThanIt) {
  const std::string path =
      std::string(ARBOR_SOURCE_DIR) + "/tests/fuzz/regressions/treemaker_thick_child.tmpl";
  const TreeMakerTemplate t =
      formats::parse_treemaker_template(formats::read_text_file(path), path);
  const Skeleton sk = grow_treemaker(t, TreeMakerOptions{});
  EXPECT_EQ(validate(sk), "");
}

// Found by fuzzing (tests/fuzz/regressions/): a leaf line reaching 1e67 cm became a limb with
// infinite float coordinates. Template numbers are bounded, and any tree grown past 1000 km is
// refused at its file.
TEST(TreeMakerGrowth, NumbersPastAMillionAreRefused) {
  const std::string path =
      std::string(ARBOR_SOURCE_DIR) + "/tests/fuzz/regressions/treemaker_huge_leaf_line.tmpl";
  testing::expect_input_error(
      [&] { formats::parse_treemaker_template(formats::read_text_file(path), path); }, path, 30, 30,
      "out of range [-1e6, 1e6]");
  expect_error("iterations { i= 3 }\ngravity { g= 2000000 }\n", 2, 14, "out of range");
  Skeleton sk;
  sk.points = {{glm::vec3(0.0f), 0.1f}, {glm::vec3(0.0f, 0.0f, 2e6f), 0.1f}};
  EXPECT_NE(scale_problem(sk), "");
  sk.points[1].position.z = 10.0f;
  EXPECT_EQ(scale_problem(sk), "");
  sk.leaf_lines.push_back({});
  sk.leaf_lines.back().b = glm::vec3(std::nanf(""), 0.0f, 0.0f);
  EXPECT_NE(scale_problem(sk), "");
}

// Found by fuzzing (tests/fuzz/regressions/): age= -1 drove the width growth below zero, so
// limbs got negative radii; the growth stops at zero.
TEST(TreeMakerGrowth, ANegativeAgeNeverMakesANegativeWidth) {
  const std::string path =
      std::string(ARBOR_SOURCE_DIR) + "/tests/fuzz/regressions/treemaker_negative_age.tmpl";
  const Skeleton sk = grow_treemaker(
      formats::parse_treemaker_template(formats::read_text_file(path), path), TreeMakerOptions{});
  EXPECT_EQ(validate(sk), "");
  for (const SkeletonPoint& p : sk.points) ASSERT_GE(p.radius, 0.0f);
}

}  // namespace arbor::generator
