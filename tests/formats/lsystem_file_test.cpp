// Tests of the L-system file reader: the grammar is read, and malformed input is refused with
// its position.
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

namespace arbor::formats {

using namespace generator;  // the readers fill the generator's types

namespace {

void expect_error(const std::string& text, int line, int column, const std::string& fragment) {
  testing::expect_input_error([&] { parse_lsystem(text, "t.lsys"); }, "t.lsys", line, column,
                              fragment);
}

}  // namespace

TEST(LSystemFile, ParsesTheGrammar) {
  const LSystem s = formats::parse_lsystem(
      "# comment\niterations = 3;\nangle = 30;\nA: f [-s(0.6)C] f(2) +(10) <>v^ h(2)u(0.5)l(1) "
      "r(0.5) B;\n"
      "B(2): f;\nB(1): f f;\nC: f;\n",
      "t.lsys");
  EXPECT_EQ(s.iterations, 3);
  EXPECT_DOUBLE_EQ(s.angle, 30.0);
  ASSERT_EQ(s.rules.size(), 4u);
  EXPECT_EQ(s.rules[0].name, 'A');
  EXPECT_DOUBLE_EQ(s.rules[1].weight, 2.0);
  const std::vector<LAction>& a = s.rules[0].body;
  EXPECT_EQ(a[0].kind, LAction::Forward);
  EXPECT_EQ(a[1].kind, LAction::Branch);
  EXPECT_EQ(a[1].branch.size(), 3u);
  EXPECT_TRUE(a[2].has_number);
  EXPECT_DOUBLE_EQ(a[2].number, 2.0);
  EXPECT_EQ(a.back().kind, LAction::Rule);
  EXPECT_EQ(a.back().rule, 'B');
}

TEST(LSystemFile, MalformedInputIsRefusedWithItsPosition) {
  expect_error("A: f[+A;\n", 1, 8, "']' is missing");
  expect_error("A: f]+A;\n", 1, 5, "']' without a matching '['");
  expect_error("A: ;\n", 1, 1, "rule A is empty");
  expect_error("A: fB;\n", 1, 5, "rule B is used but never defined");
  expect_error("A: f x;\n", 1, 6, "unknown action 'x'");
  expect_error("A: f s;\n", 1, 7, "expected '('");
  expect_error("A: f s(x);\n", 1, 8, "expected a number");
  expect_error("A: f r(1.5);\n", 1, 6, "r(n) needs 0 < n");
  expect_error("A: f", 1, 5, "the file ends where ';' to end rule A was expected");
  expect_error("A: f[+A]", 1, 9, "';' to end rule A");
  expect_error("iterations = 100;\nA: f;\n", 1, 14, "iterations = 100 is out of range");
  expect_error("iterations = 2.5;\nA: f;\n", 1, 14, "whole number");
  expect_error("depth = 3;\nA: f;\n", 1, 1, "unknown setting 'depth'");
  expect_error("angle = 3;\nangle = 4;\nA: f;\n", 2, 1, "set twice");
  expect_error("# only a comment\n", 1, 1, "no rules");
  expect_error("A(0): f;\n", 1, 2, "weight must be above 0");
  expect_error("A: f; 7\n", 1, 7, "expected a rule");
}

TEST(LSystemFile, NumbersTooLargeForADoubleAreInputErrors) {
  expect_error("step = " + std::string(400, '9') + ";\nA: f;\n", 1, 8, "too large");
  expect_error("A: f(" + std::string(400, '1') + ");\n", 1, 6, "too large");
  // Long but representable numbers are read exactly as short ones.
  const LSystem s =
      formats::parse_lsystem("angle = 30." + std::string(300, '0') + ";\nA: f;\n", "t.lsys");
  EXPECT_EQ(s.angle, 30.0);
}

}  // namespace arbor::formats
