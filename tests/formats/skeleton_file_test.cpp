// Tests of skeleton files: Bloomenthal's validation rules with positions, and exact round trips.
#include "formats/skeleton_file.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "expect_input_error.h"

#include "generator/grow.h"
#include "generator/geometry/tree_geometry.h"
#include "formats/species_file.h"
#include "generator/export/skeleton_file.h"

namespace arbor::formats {

using namespace generator;  // the readers fill the generator's types

namespace {

void expect_error(const std::string& text, int line, int column, const std::string& fragment) {
  testing::expect_input_error([&] { formats::parse_skeleton_file(text, "t.skel"); }, "t.skel", line,
                              column, fragment);
}

// Bytewise equality of two arrays (memcmp on empty vectors would pass null pointers).
template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(SkeletonFile, ReadsPointsAndConnections) {
  // A Y: a trunk 0→1→2 with a branch 1→3; radius given per point or by default.
  const Skeleton sk = formats::parse_skeleton_file(
      "# a small tree\nradius 0.05\npoint 0 0 0 0 0.2\npoint 1 0 0 2 0.15\npoint 2 0 0 4 0.1\n"
      "point 3 1 0 3\nconnect 0 1\nconnect 1 2\nconnect 1 3\n",
      "t.skel");
  ASSERT_EQ(sk.stems.size(), 2u);
  EXPECT_EQ(sk.stems[0].point_count, 3u);
  EXPECT_EQ(sk.stems[1].parent, 0);
  EXPECT_EQ(sk.stems[1].parent_point, 1);
  EXPECT_EQ(sk.stems[1].level, 1);
  EXPECT_FLOAT_EQ(sk.points[sk.stems[1].first_point + 1].radius, 0.05f);
  EXPECT_EQ(validate(sk), "");
  // It renders like any tree: two limbs (dominance continues the trunk).
  const TreeGeometry g = build_tree_geometry(sk);
  EXPECT_EQ(g.stats.limbs, 2u);
}

TEST(SkeletonFile, ViolationsNameThePointAndLine) {
  const std::string pts = "point 0 0 0 0 0.1\npoint 1 0 0 1 0.1\npoint 2 0 1 1 0.1\n";
  expect_error(pts + "connect 0 1\nconnect 0 2\nconnect 1 2\n", 6, 11,
               "point 2 already has an incoming limb (from point 0)");
  expect_error(pts + "connect 0 1\n", 3, 1, "exactly one root");  // point 2 is a second root
  expect_error(pts + "connect 0 1\nconnect 1 2\nconnect 2 0\n", 1, 1,
               "exactly one root");  // a cycle: no root
  // A loop off to the side: every point has one incoming limb, but 3 and 4 never reach the root.
  expect_error(
      pts + "point 3 5 5 5\npoint 4 5 5 6\nconnect 0 1\nconnect 1 2\nconnect 3 4\nconnect 4 3\n", 4,
      1, "point 3 is not connected to the root");
  expect_error(pts + "connect 0 7\n", 4, 11, "point 7 is not defined");
  expect_error(pts + "point 1 3 3 3\n", 4, 7, "point 1 is defined twice (first on line 2)");
  expect_error("point 0 0 0 zero\n", 1, 13, "'zero' is not a number");
  expect_error("point 0 0 0 nan\n", 1, 13, "not a finite number");
  expect_error("point 0 0 0\n", 1, 1, "'point' takes 4 to 5 values");
  expect_error("point 0 0 0 0 -1\n", 1, 15, "must not be negative");
  expect_error("joint 0 0 0 0\n", 1, 1, "unknown record 'joint'");
  expect_error(pts + "connect 0 0\n", 4, 11, "connected to itself");
  expect_error(pts + "connect 0 1\nconnect 1 2\nbranch 2 on 0 1 1.5\n", 6, 17, "in [0, 1]");
  expect_error("", 1, 1, "no points");
}

TEST(SkeletonFile, UnconnectedPointsAreErrors) {
  // Point 3 hangs on nothing: with one root and one incoming limb each, it can only be a root.
  expect_error("point 0 0 0 0 0.1\npoint 1 0 0 1 0.1\npoint 3 2 2 2 0.1\nconnect 0 1\n", 3, 1,
               "exactly one root");
}

TEST(SkeletonFile, RoundTripsAnyModelExactly) {
  for (const char* name : {"ca_black_oak.toml", "quaking_aspen.toml", "lsystem_almost_real.lsys",
                           "fractal_broadleaf.toml", "dogwood.tmpl"}) {
    const Species sp = formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/" + name);
    GrowOptions o;
    o.seed = 2;
    o.quality = 0.3;
    const Skeleton original = grow_tree(sp, o);
    const std::string path = ::testing::TempDir() + "round.skel";
    write_skeleton_file(original, path);
    const Skeleton back = formats::parse_skeleton_file(slurp(path), path);
    ASSERT_EQ(back.stems.size(), original.stems.size()) << name;
    ASSERT_EQ(back.leaves.size(), original.leaves.size()) << name;
    for (std::size_t i = 0; i < original.stems.size(); ++i) {
      ASSERT_EQ(back.stems[i].parent, original.stems[i].parent) << name << " stem " << i;
      ASSERT_EQ(back.stems[i].parent_point, original.stems[i].parent_point)
          << name << " stem " << i;
      ASSERT_EQ(back.stems[i].level, original.stems[i].level) << name;
    }
    const TreeGeometry a = build_tree_geometry(original), b = build_tree_geometry(back);
    EXPECT_TRUE(same_bytes(a.curves.points, b.curves.points)) << name;
    EXPECT_TRUE(same_bytes(a.curves.tangents, b.curves.tangents)) << name;
    EXPECT_TRUE(same_bytes(a.grids.vertices, b.grids.vertices)) << name;
    EXPECT_TRUE(same_bytes(a.leaves.positions, b.leaves.positions)) << name;
    EXPECT_TRUE(same_bytes(a.leaves.color, b.leaves.color)) << name;
  }
}

// A chain of limbs nested 20,000 deep once overflowed the stack (a recursion per stem).
TEST(SkeletonFile, DeeplyNestedBranchesAreReadWithoutRecursion) {
  const int depth = 20000;
  std::string text = "radius 0.001\npoint 0 0 0 0\n";
  // Point 2k+1 continues the stem, point 2k+2 starts a new one from it.
  for (int k = 0; k < depth; ++k) {
    const int at = k == 0 ? 0 : 2 * k - 1;
    text += "point " + std::to_string(2 * k + 1) + " 0 0 " + std::to_string(k + 1) + "\n";
    text += "point " + std::to_string(2 * k + 2) + " 1 0 " + std::to_string(k + 1) + "\n";
    text += "connect " + std::to_string(at) + " " + std::to_string(2 * k + 1) + "\n";
    text += "connect " + std::to_string(at) + " " + std::to_string(2 * k + 2) + "\n";
  }
  const Skeleton sk = formats::parse_skeleton_file(text, "t.skel");
  EXPECT_EQ(validate(sk), "");
  EXPECT_EQ(sk.stems.size(), static_cast<std::size_t>(depth) + 1);
}

// 100,000 limbs from one point once took over a minute (quadratic); linear now, so this runs in
// well under a second.
TEST(SkeletonFile, ManyChildrenOfOnePointAreRead) {
  const int children = 100000;
  std::string text = "radius 0.01\npoint 0 0 0 0\npoint 1 0 0 10\nconnect 0 1\n";
  for (int k = 0; k < children; ++k) {
    const int id = k + 2;
    text += "point " + std::to_string(id) + " " + std::to_string(1 + k % 7) + " " +
            std::to_string(k / 7) + " 5 0.001\nconnect 1 " + std::to_string(id) + "\n";
  }
  // Branch records on the trunk's segment take the same path.
  for (int k = 0; k < 1000; ++k) {
    const std::string c = std::to_string(children + 2 + 2 * k),
                      d = std::to_string(children + 3 + 2 * k);
    text += "point " + c + " 0 0 5 0.001\npoint " + d + " 2 2 " + std::to_string(k) + " 0.001\n";
    text += "branch " + c + " on 0 1 0.5\nconnect " + c + " " + d + "\n";
  }
  const Skeleton sk = formats::parse_skeleton_file(text, "t.skel");
  EXPECT_EQ(validate(sk), "");
  // The trunk continues into point 1's first limb; every other limb and branch is a stem.
  EXPECT_EQ(sk.stems.size(), static_cast<std::size_t>(children) + 1000);
}

// Two coincident points on a limb once gave NaN positions; the limb has no direction there.
TEST(SkeletonFile, CoincidentPointsOnALimbAreRefused) {
  expect_error("point 0 0 0 0\npoint 1 0 0 1\npoint 2 0 0 1\nconnect 0 1\nconnect 1 2\n", 5, 1,
               "points 1 and 2 are at the same position");
  expect_error("point 0 0 0 0\npoint 1 0 0 0\nconnect 0 1\n", 3, 1, "same position");
}

// Found by fuzzing: a coordinate of 1e23 overflowed the splines' float arithmetic (NaN curves).
TEST(SkeletonFile, CoordinatesBeyondAThousandKilometresAreRefused) {
  expect_error("point 0 0 0 0\npoint 1 0 99999999999999999999999 1.5\nconnect 0 1\n", 2, 11,
               "out of range [-1e6, 1e6]");
  expect_error("point 0 0 0 0 2e6\n", 1, 15, "out of range");
  expect_error("point 0 0 0 0\npoint 1 0 0 0.0000001\nconnect 0 1\n", 3, 1,
               "closer than 1 micrometre");
}

}  // namespace arbor::formats
