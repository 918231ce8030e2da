// Tests of the TREE-MAKER template reader: the shipped dogwood parses, spacing is free, and
// malformed templates are refused with their position.
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

namespace arbor::formats {

using namespace generator;  // the readers fill the generator's types

namespace {

void expect_error(const std::string& text, int line, int column, const std::string& fragment) {
  testing::expect_input_error([&] { formats::parse_treemaker_template(text, "t.tmpl"); }, "t.tmpl",
                              line, column, fragment);
}

}  // namespace

TEST(TreeMakerTemplate, TheDogwoodParses) {
  const std::string path = std::string(ARBOR_SOURCE_DIR) + "/species/dogwood.tmpl";
  const TreeMakerTemplate t =
      formats::parse_treemaker_template(formats::read_text_file(path), path);
  EXPECT_EQ(t.iterations, 13);
  EXPECT_DOUBLE_EQ(t.gravity, 0.08);
  EXPECT_DOUBLE_EQ(*t.light.height, 0.4);
  EXPECT_DOUBLE_EQ(*t.light.angle, 0.2);
  ASSERT_EQ(t.colors.size(), 3u);
  EXPECT_DOUBLE_EQ(t.color("brown")->rgb.y, 0.9);
  ASSERT_EQ(t.branches.size(), 5u);
  EXPECT_EQ(t.branches[2].choices.size(), 3u);
  EXPECT_DOUBLE_EQ(t.branches[2].choices[2].factor.hi, 0.2);
  // Levels without a rule use the nearest lower level's (§IV): 4–6 use level 3's, 8 uses 7's.
  EXPECT_EQ(t.rule_for(5)->level, 3);
  EXPECT_EQ(t.rule_for(8)->level, 7);
  EXPECT_EQ(t.rule_for(13)->level, 9);
  ASSERT_EQ(t.particles.size(), 1u);
  EXPECT_DOUBLE_EQ(t.particles[0].mag.hi, 25.0);
  EXPECT_DOUBLE_EQ(t.particles[0].max_deviation, 10.0);
  EXPECT_DOUBLE_EQ(t.particles[0].acc, -0.8);
  ASSERT_EQ(t.leaves.size(), 2u);
  EXPECT_FALSE(t.leaves[0].limb_coords);
  EXPECT_EQ(t.leaves[1].elements.size(), 5u);
  EXPECT_EQ(t.leaves[1].elements[4].color, "green");
  EXPECT_DOUBLE_EQ(t.leaves[1].elements[4].brightness.lo, 0.5);
}

TEST(TreeMakerTemplate, AnySpacingIsAllowed) {
  const TreeMakerTemplate t = formats::parse_treemaker_template(
      "iterations{i=3}color{green=0,1,0}branch{level=1 number=1 to 2(p=1 angle=30 to 40 dir=0 to "
      "360 factor=0.5 to 0.6)}particle{pos=0,0,0 mag=10 to 12 dir=0,0,1:5 color=green}"
      "leaf{p=1 coord=leaf out=1 up=1 color=green ln=0,0,0 0,0,1}",
      "t.tmpl");
  EXPECT_EQ(t.iterations, 3);
  EXPECT_TRUE(t.leaves[0].elements[0].line);
}

TEST(TreeMakerTemplate, MalformedTemplatesAreRefusedWithTheirPosition) {
  const std::string ok =
      testing::kTmColor + testing::kTmRule + testing::kTmParticle + testing::kTmLeaf;
  EXPECT_NO_THROW(formats::parse_treemaker_template(ok, "t.tmpl"));
  expect_error(testing::kTmColor + testing::kTmParticle + testing::kTmRule + testing::kTmLeaf, 3, 1,
               "branching rules must come before the particles");
  expect_error(
      testing::kTmColor +
          "branch { level= 1 number= 1 to 2 (p=0.5 angle= 1 to 2 dir= 0 to 1 factor= 1 to 1) }\n" +
          testing::kTmParticle + testing::kTmLeaf,
      2, 1, "add up to 0.5");
  expect_error(testing::kTmColor + testing::kTmRule + testing::kTmParticle +
                   "leaf { p= 0.7 coord= leaf out= 1 up= 1 color= green tri= 0,0,0 1,0,0 0,1,0 }\n",
               4, 1, "leaf probabilities add up to 0.7");
  expect_error(
      testing::kTmColor + testing::kTmRule + "particle { color= red }\n" + testing::kTmLeaf, 3, 19,
      "colour 'red' is not defined");
  expect_error(
      testing::kTmColor + testing::kTmRule + testing::kTmParticle + "leaf { p= 1 coord= tree }\n",
      4, 20, "coord must be 'limb' or 'leaf'");
  expect_error(testing::kTmColor + testing::kTmRule + testing::kTmParticle +
                   "leaf { p= 1 tri= 0,0,0 1,1,1 2,2,2 }\n",
               4, 13, "color= before");
  expect_error(
      testing::kTmColor + testing::kTmRule + "particle { mag= 20 to 10 }\n" + testing::kTmLeaf, 3,
      17, "low end must not exceed");
  expect_error(
      testing::kTmColor + testing::kTmRule + "particle { dir= 0,0,1 }\n" + testing::kTmLeaf, 3, 23,
      "expected ':'");
  expect_error(testing::kTmColor + testing::kTmRule + "particle { speed= 3 }\n" + testing::kTmLeaf,
               3, 12, "unknown particle key 'speed'");
  expect_error("iterations { i= 0 }\n", 1, 17, "iterations must be a whole number");
  expect_error("iterations { i= 3 }\niterations { i= 4 }\n", 2, 1, "given twice");
  expect_error("weather { rain= 3 }\n", 1, 1, "unknown section 'weather'");
  expect_error("iterations { i= 3 \n", 2, 1, "expected '}' before the end of the file");
  expect_error("iterations { i= 3x }\n", 1, 18, "expected '}'");
  expect_error("color { green= 0,1 }\n", 1, 20, "expected ','");
  expect_error(testing::kTmColor + "branch { level= 1 number= 1 to 2 }\n", 2, 1,
               "at least one (p angle dir factor)");
  expect_error(testing::kTmColor + testing::kTmRule + testing::kTmLeaf, 1, 1,
               "at least one particle");
  expect_error(testing::kTmColor + testing::kTmRule + testing::kTmParticle, 1, 1,
               "at least one leaf");
  expect_error("", 1, 1, "at least one branching rule");
}

}  // namespace arbor::formats
