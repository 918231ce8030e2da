// Tests of the leaves' margins (issue 45): the teeth are cut into the outline, as many and as
// deep as asked, the outline stays a fan of triangles, and the renderer's outline test, the
// exports and the statistics all see them.
#include "generator/geometry/leaf_margin.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/math.h"
#include "expect_input_error.h"
#include "formats/species_file.h"
#include "generator/export/tree_stats.h"
#include "generator/geometry/geometry_plan.h"
#include "generator/geometry/leaf_cards.h"
#include "generator/geometry/leaf_shapes.h"
#include "generator/grow.h"

namespace arbor::generator {

namespace {

constexpr std::size_t kOval = 0;
// The share of a half-circle between 30 % and 70 % of its diameter: (acos(−0.4) − acos(0.4)) / π.
const double kMiddleArc = (std::acos(-0.4) - std::acos(0.4)) / kPi;

LeafMarginSpec margin(LeafMargin kind, int teeth, double depth) {
  LeafMarginSpec m;
  m.kind = kind;
  m.teeth = teeth;
  m.depth = depth;
  return m;
}

double area(const LeafShape& s) {
  double a = 0.0;
  for (const auto& t : s.triangles) {
    const glm::vec2 p = s.vertices[t[0]], q = s.vertices[t[1]], r = s.vertices[t[2]];
    a += 0.5 * ((q.x - p.x) * (r.y - p.y) - (r.x - p.x) * (q.y - p.y));
  }
  return a;
}

// The teeth on the right side of a margined oval: for the ring's points right of the midrib and
// between 30 % and 70 % of the length, how far each lies in from the same point of the uncut
// outline (the margin of depth 0, sampled alike), in order along the ring.
std::vector<double> right_side_cuts(const LeafShape& s, const LeafShape& uncut) {
  std::vector<double> cut;
  const glm::vec2 c = s.vertices[0];
  for (std::size_t k = 1; k < s.vertices.size(); ++k) {
    const glm::vec2 p = uncut.vertices[k];
    if (p.x > 0.0f && p.y > 0.3f && p.y < 0.7f)
      cut.push_back(glm::length(p - c) - glm::length(s.vertices[k] - c));
  }
  return cut;
}

int notches(const std::vector<double>& cut, double depth) {
  int n = 0;
  for (std::size_t k = 1; k + 1 < cut.size(); ++k)
    n += cut[k] > 0.5 * depth && cut[k] >= cut[k - 1] && cut[k] > cut[k + 1] ? 1 : 0;
  return n;
}

}  // namespace

// The profiles: 0 on the outline at a tooth's point or crest, 1 at the notch; a serrate tooth's
// point at three quarters of its length (its front steep), a crenate tooth's crest in its middle.
TEST(LeafMargin, ProfilesReachTheOutlineAndTheNotch) {
  EXPECT_DOUBLE_EQ(margin_profile(LeafMargin::Serrate, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(margin_profile(LeafMargin::Serrate, 0.75), 0.0);
  EXPECT_GT(margin_profile(LeafMargin::Serrate, 0.9), margin_profile(LeafMargin::Serrate, 0.6));
  EXPECT_DOUBLE_EQ(margin_profile(LeafMargin::Crenate, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(margin_profile(LeafMargin::Crenate, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(margin_profile(LeafMargin::Lobed, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(margin_profile(LeafMargin::Lobed, 0.0), 0.0);
  for (double phase = 0.0; phase < 1.0; phase += 0.01) {
    for (LeafMargin kind : {LeafMargin::Serrate, LeafMargin::Crenate, LeafMargin::Lobed}) {
      EXPECT_GE(margin_profile(kind, phase), 0.0);
      EXPECT_LE(margin_profile(kind, phase), 1.0);
    }
  }
}

// On a round leaf (aspect 1) the teeth along a side are as many as asked and as deep: between
// 30 % and 70 % of the length a side holds (acos(−0.4) − acos(0.4)) / π = 26 % of its
// half-circle's arc, so 0.26 × teeth notches (± 1), each cut in by the depth (× the width, which is
// the outline's unit). Power: a spacing from the whole perimeter (not half of it) halves the
// notches; a cut × aspect² or missing the 0.8 cap's share fails the depth.
TEST(LeafMargin, TeethAreAsManyAndAsDeepAsAsked) {
  for (LeafMargin kind : {LeafMargin::Serrate, LeafMargin::Crenate, LeafMargin::Lobed}) {
    for (int teeth : {10, 25}) {
      SCOPED_TRACE(std::string(kLeafMarginNames[static_cast<int>(kind)]) + " " +
                   std::to_string(teeth));
      const double depth = 0.04;
      const LeafShape s = margined_shape(leaf_outline(kOval), margin(kind, teeth, depth), 1.0);
      const LeafShape uncut = margined_shape(leaf_outline(kOval), margin(kind, teeth, 0.0), 1.0);
      ASSERT_EQ(s.vertices.size(), uncut.vertices.size());
      const std::vector<double> cut = right_side_cuts(s, uncut);
      EXPECT_NEAR(notches(cut, depth), kMiddleArc * teeth, 1.0);
      EXPECT_NEAR(*std::max_element(cut.begin(), cut.end()), depth, 0.002);
      EXPECT_LT(*std::min_element(cut.begin(), cut.end()), 0.002);  // crests on the outline
    }
  }
}

// A narrow leaf's teeth are spaced by length along its side, not by angle: on a willow-like
// oval (width 0.2 of the length) nearly all of a half-perimeter is the side, so its middle 40 %
// holds about 0.4 × the teeth (counted as local minima of x, deeper than half the depth; the cut
// is radial and there almost along x). Power: spacing the teeth by the ring's angle puts most of
// them at the tip and base and fails the count.
TEST(LeafMargin, ANarrowLeafsTeethAreSpacedAlongItsSides) {
  const double depth = 0.05;
  const int teeth = 30;
  const LeafShape s =
      margined_shape(leaf_outline(kOval), margin(LeafMargin::Serrate, teeth, depth), 0.2);
  std::vector<glm::vec2> side;
  for (std::size_t k = 1; k < s.vertices.size(); ++k) {
    const glm::vec2 p = s.vertices[k];
    if (p.x > 0.0f && p.y > 0.3f && p.y < 0.7f) side.push_back(p);
  }
  int n = 0;
  for (std::size_t k = 1; k + 1 < side.size(); ++k) {
    const double circle = std::sqrt(0.25 - (side[k].y - 0.5) * (side[k].y - 0.5));
    n += side[k].x <= side[k - 1].x && side[k].x < side[k + 1].x && side[k].x < circle - 0.5 * depth
             ? 1
             : 0;
  }
  EXPECT_GE(n, static_cast<int>(0.35 * teeth));
  EXPECT_LE(n, static_cast<int>(0.5 * teeth));
}

// Every shape with every margin: still a fan about each part's centre (the ring's turn about it
// increases, no triangle flipped), nowhere outside the shape it was cut from, smaller by no more
// than its perimeter × the depth, unchanged at the base where the petiole joins; and the
// outline test the renderer uses finds a notch outside and a crest inside. Power: a cut moved
// out instead of in fails "inside the base"; teeth at the base fail the base check.
TEST(LeafMargin, EveryShapeStaysAFanInsideItsOutline) {
  for (std::size_t shape = 0; shape < leaf_shape_count(); ++shape) {
    for (LeafMargin kind : {LeafMargin::Serrate, LeafMargin::Crenate, LeafMargin::Lobed}) {
      SCOPED_TRACE(std::string(leaf_shapes()[shape].name) + " " +
                   kLeafMarginNames[static_cast<int>(kind)]);
      const LeafShape& base = leaf_shapes()[shape];
      const LeafOutline& outline = leaf_outline(shape);
      const std::size_t index = margined_shape_index(shape, margin(kind, 20, 0.05), 0.7);
      ASSERT_GE(index, leaf_shape_count());
      EXPECT_EQ(margined_shape_index(shape, margin(kind, 20, 0.05), 0.7), index);  // made once
      const LeafShape& s = leaf_shape(index);
      for (const auto& t : s.triangles) {
        const glm::vec2 p = s.vertices[t[0]], q = s.vertices[t[1]], r = s.vertices[t[2]];
        EXPECT_GE((q.x - p.x) * (r.y - p.y) - (r.x - p.x) * (q.y - p.y), 0.0f);
      }
      int outside = 0;
      for (const auto& t : s.triangles) {
        // A ring point nudged 0.1 % towards its part's centre: on the outline counts as in.
        const glm::vec2 c = s.vertices[t[0]], v = s.vertices[t[1]];
        outside += outline.contains(v + (c - v) * 1e-3f) ? 0 : 1;
      }
      EXPECT_EQ(outside, 0);
      EXPECT_LT(area(s), area(base));
      EXPECT_GT(area(s), area(base) * 0.8);
      EXPECT_TRUE(leaf_outline(index).contains({0.0f, 0.5f * (outline.lo.y + outline.hi.y)}) ||
                  shape == 5);  // the leaflets' middle is between them
    }
  }
  // The oval's margin near the base is the oval's: its ring points there are the uncut ones.
  const LeafShape s =
      margined_shape(leaf_outline(kOval), margin(LeafMargin::Serrate, 20, 0.05), 1.0);
  const LeafShape uncut =
      margined_shape(leaf_outline(kOval), margin(LeafMargin::Serrate, 20, 0.0), 1.0);
  ASSERT_EQ(s.vertices.size(), uncut.vertices.size());
  int base = 0;
  for (std::size_t k = 1; k < s.vertices.size(); ++k) {
    if (uncut.vertices[k].y >= 0.02f) continue;
    EXPECT_NEAR(glm::length(s.vertices[k] - uncut.vertices[k]), 0.0f, 1e-6f);
    ++base;
  }
  EXPECT_GT(base, 2);
}

// A leaf on a tree gets its species' margin: the cards name the margined outline, the statistics
// count its triangles the same whether the geometry is counted or built, and the exported
// triangles carry the teeth. Power: leaving the cards on the base shape fails the first check;
// counting the skeleton's outlines fails the statistics.
TEST(LeafMargin, TheTreesLeavesCarryTheSpeciesMargin) {
  Species sp = formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml");
  sp.leaf.margin = margin(LeafMargin::Crenate, 18, 0.04);
  GrowOptions grow;
  grow.seed = 2;
  grow.quality = 0.1;
  const Skeleton sk = grow_tree(sp, grow);
  const GeometryOptions o = geometry_options_for(sp);
  const TreeGeometry g = build_tree_geometry(sk, o);
  ASSERT_FALSE(g.cards.cards.empty());
  const std::size_t drawn = drawn_leaf_shapes(sk, o)[static_cast<std::size_t>(sk.leaves[0].shape)];
  EXPECT_GE(drawn, leaf_shape_count());
  for (const LeafCard& c : g.cards.cards) EXPECT_EQ(c.shape, drawn);
  const std::size_t per_leaf = leaf_shape(drawn).triangles.size();
  EXPECT_GT(per_leaf, 2u * 18u * 6u);  // a dozen ring points a tooth, two sides
  EXPECT_EQ(g.stats.leaf_outline_triangles, per_leaf * sk.leaves.size());
  EXPECT_EQ(count_tree_geometry(sk, o).leaf_outline_triangles, g.stats.leaf_outline_triangles);
  TreeStats st = compute_stats(sk);
  add_geometry_stats(st, g.stats, 0.0);
  EXPECT_EQ(st.leaf_triangles, static_cast<long long>(per_leaf * sk.leaves.size()));
  EXPECT_GE(leaf_triangles(g).triangle_count(), per_leaf * sk.leaves.size());
}

// The species keys: margin by name, teeth a whole number in [1, 100], tooth_depth in [0, 0.3];
// errors at the value's line and column.
TEST(LeafMargin, SpeciesKeysAreReadAndCheckedAtTheirPosition) {
  const std::string head = "model = \"weber-penn\"\n[leaf]\n";
  const Species sp = formats::parse_species_toml(
      head + "margin = \"serrate\"\nteeth = 30\ntooth_depth = 0.05\n", "s.toml");
  EXPECT_EQ(sp.leaf.margin.kind, LeafMargin::Serrate);
  EXPECT_EQ(sp.leaf.margin.teeth, 30);
  EXPECT_DOUBLE_EQ(sp.leaf.margin.depth, 0.05);
  testing::expect_input_error(
      [&] { formats::parse_species_toml(head + "margin = \"jagged\"\n", "s.toml"); }, "s.toml", 3,
      10, "leaf.margin");
  testing::expect_input_error([&] { formats::parse_species_toml(head + "teeth = 0\n", "s.toml"); },
                              "s.toml", 3, 9, "out of range [1, 100]");
  testing::expect_input_error(
      [&] { formats::parse_species_toml(head + "teeth = 2.5\n", "s.toml"); }, "s.toml", 3, 9,
      "whole number");
  testing::expect_input_error(
      [&] { formats::parse_species_toml(head + "tooth_depth = 0.5\n", "s.toml"); }, "s.toml", 3, 15,
      "out of range [0, 0.3]");
}

}  // namespace arbor::generator
