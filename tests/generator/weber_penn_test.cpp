// Tests of the Weber & Penn generator: determinism, Skeleton invariants, and each parameter
// family's effect on a grown tree.
#include "generator/models/weber_penn/weber_penn.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/error.h"
#include "generator/species.h"
#include "generator/export/tree_stats.h"
#include "generator/models/weber_penn/weber_penn_formulas.h"
#include "generator/models/weber_penn/weber_penn_leaves.h"
#include "common/fast_trig.h"
#include "common/frame.h"
#include "common/rng.h"
#include "formats/species_file.h"
#include "common/math.h"

namespace arbor::generator {

namespace {

std::string species_path(const std::string& name) {
  return std::string(ARBOR_SOURCE_DIR) + "/species/" + name + ".toml";
}

WeberPennParams paper_species(const std::string& name) {
  return formats::load_species(species_path(name)).weber_penn();
}

// A straight trunk of 10 m with `branches` children at 90°, no variation anywhere.
WeberPennParams simple_tree(int levels = 2, double branches = 8) {
  WeberPennParams p;
  p.shape = 3;
  p.scale = 10.0;
  p.levels = levels;
  p.ratio = 0.02;
  p.leaf_bend = 0.0;
  p.level[0].length = 1.0;
  p.level[0].curve_res = 4;
  for (int l = 1; l < 4; ++l) {
    p.level[static_cast<size_t>(l)].down_angle = 90.0;
    p.level[static_cast<size_t>(l)].rotate = 140.0;
    p.level[static_cast<size_t>(l)].branches = branches;
    p.level[static_cast<size_t>(l)].length = 0.3;
    p.level[static_cast<size_t>(l)].curve_res = 3;
  }
  return p;
}

Skeleton grow(const WeberPennParams& p, std::uint64_t seed = 1, double time = 0.0,
              double quality = 1.0) {
  GrowOptions o;
  o.seed = seed;
  o.time = time;
  o.quality = quality;
  return grow_weber_penn(p, o);
}

glm::dvec3 direction(const Skeleton& sk, const Stem& s, std::uint32_t segment) {
  const glm::vec3 a = sk.points[s.first_point + segment].position;
  const glm::vec3 b = sk.points[s.first_point + segment + 1].position;
  return glm::normalize(glm::dvec3(b - a));
}

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * 180.0 / kPi;
}

bool same_bytes(const Skeleton& a, const Skeleton& b) {
  return a.points.size() == b.points.size() && a.leaves.size() == b.leaves.size() &&
         a.stems.size() == b.stems.size() &&
         std::memcmp(a.points.data(), b.points.data(), a.points.size() * sizeof(SkeletonPoint)) ==
             0 &&
         std::memcmp(a.leaves.data(), b.leaves.data(), a.leaves.size() * sizeof(Leaf)) == 0;
}

}  // namespace

TEST(WeberPenn, SameSeedGivesSameTree) {
  for (const char* name : {"quaking_aspen", "weeping_willow", "ca_black_oak"}) {
    const WeberPennParams p = paper_species(name);
    EXPECT_TRUE(same_bytes(grow(p, 5), grow(p, 5))) << name;
  }
}

// Seeds draw the paper's variations: eight seeds give eight different trees whose trunks
// (§4.3: length_trunk = (0Length ± 0LengthV) × (Scale ± ScaleV)) all lie in the species' range and
// spread over it, not one length with different twigs.
TEST(WeberPenn, DifferentSeedsGiveDifferentTrees) {
  const WeberPennParams p = paper_species("black_tupelo");
  const WeberPennLevel& trunk = p.level[0];
  const double lo = (trunk.length - trunk.length_v) * (p.scale - p.scale_v);
  const double hi = (trunk.length + trunk.length_v) * (p.scale + p.scale_v);
  ASSERT_GT(hi - lo, 1.0);  // the species varies its height: black tupelo's ScaleV is 5 m
  std::vector<Skeleton> trees;
  double shortest = hi, longest = lo;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    trees.push_back(grow(p, seed));
    const double length = trees.back().stems.front().length;
    EXPECT_GE(length, lo - 1e-4) << "seed " << seed;
    EXPECT_LE(length, hi + 1e-4) << "seed " << seed;
    shortest = std::min(shortest, length);
    longest = std::max(longest, length);
  }
  for (std::size_t a = 0; a < trees.size(); ++a) {
    for (std::size_t b = a + 1; b < trees.size(); ++b) {
      EXPECT_FALSE(same_bytes(trees[a], trees[b])) << "seeds " << a + 1 << " and " << b + 1;
    }
  }
  // Eight uniform draws over [lo, hi] span at least a quarter of it with probability > 0.999.
  EXPECT_GT(longest - shortest, 0.25 * (hi - lo));
}

TEST(WeberPenn, PaperSpeciesSatisfyTheSkeletonInvariants) {
  for (const char* name : {"quaking_aspen", "black_tupelo", "weeping_willow", "ca_black_oak"}) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      const Skeleton sk = grow(paper_species(name), seed);
      EXPECT_EQ(validate(sk), "") << name << " seed " << seed;
      EXPECT_GT(sk.leaves.size(), 0u) << name;
    }
  }
}

TEST(WeberPenn, ValidateCatchesBrokenSkeletons) {
  Skeleton sk = grow(simple_tree());
  ASSERT_EQ(validate(sk), "");
  Skeleton two_roots = sk;
  two_roots.stems[1].parent = -1;
  EXPECT_NE(validate(two_roots).find("roots"), std::string::npos);
  Skeleton forward = sk;
  forward.stems[1].parent = 5;
  EXPECT_NE(validate(forward).find("earlier stem"), std::string::npos);
  Skeleton thick = sk;
  thick.points[thick.stems[1].first_point].radius = 10.0f;
  EXPECT_NE(validate(thick).find("thicker than its parent"), std::string::npos);
}

TEST(WeberPenn, FirstLevelCountIsBranchesExactly) {
  // §4.3: the trunk's children number exactly 1Branches (error diffusion keeps the total).
  const Skeleton sk = grow(simple_tree(2, 13));
  const TreeStats st = compute_stats(sk);
  ASSERT_EQ(st.stems_per_level.size(), 2u);
  EXPECT_EQ(st.stems_per_level[0], 1);
  EXPECT_EQ(st.stems_per_level[1], 13);
  EXPECT_EQ(compute_stats(grow(paper_species("quaking_aspen"))).stems_per_level[1], 50);
}

TEST(WeberPenn, SegSplitsCompoundOverSegments) {
  // §4.2 example: 0SegSplits 1 with 0CurveRes 3 gives (1 + 1)^(3 - 1) = 4 trunk stems.
  WeberPennParams p = simple_tree(1);
  p.level[0].curve_res = 3;
  p.level[0].seg_splits = 1.0;
  p.level[0].split_angle = 20.0;
  EXPECT_EQ(compute_stats(grow(p)).stems_per_level[0], 4);
  p.level[0].seg_splits = 2.0;
  p.level[0].curve_res = 5;  // (2 + 1)^4 = 81
  EXPECT_EQ(compute_stats(grow(p)).stems_per_level[0], 81);
}

TEST(WeberPenn, BaseSplitsMakeSeveralTrunks) {
  WeberPennParams p = simple_tree(1);
  p.level[0].base_splits = 2;
  p.level[0].split_angle = 10.0;
  const Skeleton sk = grow(p);
  EXPECT_EQ(compute_stats(sk).stems_per_level[0], 3);
  // All three start at the end of the first segment and lean apart.
  for (size_t i = 1; i < sk.stems.size(); ++i) {
    EXPECT_TRUE(sk.stems[i].is_clone);
    EXPECT_NEAR(sk.stems[i].parent_offset, 10.0 / 4.0, 1e-5);
  }
}

TEST(WeberPenn, SplitTurnsStemsAwayThenBackRotatesThem) {
  // One clone on a vertical trunk: both turn 20° from vertical; the back-rotation spread over the
  // remaining segments returns them toward vertical (§4.2).
  WeberPennParams p = simple_tree(1);
  p.level[0].curve_res = 6;
  p.level[0].base_splits = 1;
  p.level[0].split_angle = 20.0;
  const Skeleton sk = grow(p);
  ASSERT_EQ(sk.stems.size(), 2u);
  const glm::dvec3 up(0, 0, 1);
  for (const Stem& s : sk.stems) {
    const std::uint32_t after_split = s.is_clone ? 0 : 1;
    EXPECT_NEAR(angle_between(direction(sk, s, after_split), up), 20.0, 0.01);
    // 20° taken back over 4 more segments: 5° each.
    EXPECT_NEAR(angle_between(direction(sk, s, after_split + 1), up), 15.0, 0.01);
  }
}

TEST(WeberPenn, DownAngleIsTheAngleFromTheParent) {
  WeberPennParams p = simple_tree(2);
  p.level[1].down_angle = 35.0;
  const Skeleton sk = grow(p);
  for (const Stem& s : sk.stems) {
    if (s.level != 1) continue;
    EXPECT_NEAR(angle_between(direction(sk, s, 0), glm::dvec3(0, 0, 1)), 35.0, 1e-3);
  }
}

TEST(WeberPenn, PositiveRotateIsHelical) {
  WeberPennParams p = simple_tree(2, 6);
  const Skeleton sk = grow(p);
  std::vector<double> azimuths;
  for (const Stem& s : sk.stems) {
    if (s.level == 1) {
      const glm::dvec3 d = direction(sk, s, 0);
      azimuths.push_back(std::atan2(d.y, d.x) * 180.0 / kPi);
    }
  }
  ASSERT_EQ(azimuths.size(), 6u);
  for (size_t i = 1; i < azimuths.size(); ++i) {
    EXPECT_NEAR(std::remainder(azimuths[i] - azimuths[i - 1], 360.0), 140.0, 1e-3);
  }
}

TEST(WeberPenn, NegativeRotateAlternatesInOnePlane) {
  // nRotate = -90: children at ±90° from the parent's y axis, on alternating sides, coplanar.
  WeberPennParams p = simple_tree(2, 6);
  p.level[1].rotate = -90.0;
  const Skeleton sk = grow(p);
  double previous_x = 0.0;
  int children = 0;
  for (const Stem& s : sk.stems) {
    if (s.level != 1) continue;
    const glm::dvec3 d = direction(sk, s, 0);
    EXPECT_NEAR(std::fabs(d.x), 1.0, 1e-4);  // all in the trunk's xz plane, pointing along ±x
    if (children++ > 0) {
      EXPECT_LT(d.x * previous_x, 0.0);
    }
    previous_x = d.x;
  }
  EXPECT_EQ(children, 6);
}

TEST(WeberPenn, CurveTurnsTheStemByCurveOverAllButTheFirstSegment) {
  WeberPennParams p = simple_tree(1);
  p.level[0].curve_res = 10;
  p.level[0].curve = 90.0;
  const Skeleton sk = grow(p);
  const Stem& trunk = sk.stems[0];
  EXPECT_NEAR(angle_between(direction(sk, trunk, 0), direction(sk, trunk, 9)), 81.0, 1e-3);
  p.level[0].curve_back = -90.0;  // S-curve: +18° per segment in the first half, -18° after
  const Skeleton s2 = grow(p);
  EXPECT_NEAR(angle_between(direction(s2, s2.stems[0], 0), direction(s2, s2.stems[0], 4)), 72.0,
              1e-3);
  EXPECT_NEAR(angle_between(direction(s2, s2.stems[0], 0), direction(s2, s2.stems[0], 9)), 18.0,
              1e-3);
}

TEST(WeberPenn, NegativeCurveVMakesAHelix) {
  WeberPennParams p = simple_tree(1);
  p.level[0].curve_res = 8;
  p.level[0].curve_v = -30.0;
  const Skeleton sk = grow(p);
  for (std::uint32_t i = 0; i < 8; ++i) {
    EXPECT_NEAR(angle_between(direction(sk, sk.stems[0], i), glm::dvec3(0, 0, 1)), 30.0, 1e-3);
  }
  // One full turn: opposite segments point to opposite sides.
  const glm::dvec3 a = direction(sk, sk.stems[0], 0), b = direction(sk, sk.stems[0], 4);
  EXPECT_NEAR(a.x, -b.x, 1e-4);
  EXPECT_NEAR(a.y, -b.y, 1e-4);
}

TEST(WeberPenn, TaperShrinksRadiusAlongTheStem) {
  WeberPennParams p = simple_tree(1);
  const Skeleton sk = grow(p);
  const Stem& t = sk.stems[0];
  EXPECT_NEAR(sk.points[t.first_point].radius, 10.0 * 0.02, 1e-6);  // §4.4 Length·Ratio·0Scale
  EXPECT_NEAR(sk.points[t.first_point + t.point_count - 1].radius, 0.0, 1e-6);
  EXPECT_NEAR(sk.points[t.first_point + 2].radius, 0.1, 1e-6);
}

TEST(WeberPenn, ChildRadiusFollowsRatioPower) {
  WeberPennParams p = simple_tree(2, 4);
  p.ratio_power = 2.0;
  const Skeleton sk = grow(p);
  const Stem& trunk = sk.stems[0];
  for (const Stem& s : sk.stems) {
    if (s.level != 1) continue;
    const double expected = trunk.base_radius * std::pow(s.length / trunk.length, 2.0);
    EXPECT_NEAR(s.base_radius, expected, 1e-6);
  }
}

TEST(WeberPenn, AttractionUpRaisesSubBranches) {
  // §4.8 turns stems about their x axis by an amount ∝ cos(orientation) = y.z; sub-branches at
  // 90° from a horizontal parent have a horizontal y and feel nothing, so these leave at 45°.
  WeberPennParams p = simple_tree(3, 6);
  p.level[2].curve_res = 8;
  p.level[2].down_angle = 45.0;
  auto mean_tip_z = [](const Skeleton& sk) {
    double sum = 0;
    int n = 0;
    for (const Stem& s : sk.stems) {
      if (s.level != 2) continue;
      sum += direction(sk, s, s.point_count - 2).z;
      ++n;
    }
    return sum / n;
  };
  const double none = mean_tip_z(grow(p));
  p.attraction_up = 2.0;
  const double up = mean_tip_z(grow(p));
  p.attraction_up = -2.0;
  const double down = mean_tip_z(grow(p));
  EXPECT_GT(up, none + 0.2);
  EXPECT_LT(down, none - 0.2);
}

TEST(WeberPenn, PrunedStemsStayInsideTheEnvelope) {
  WeberPennParams p = paper_species("weeping_willow");  // PruneRatio 1
  p.wind_speed = p.wind_gust = 0.0;  // the envelope is the tree's shape at rest; wind moves it
  const Skeleton sk = grow(p, 3);
  ASSERT_EQ(validate(sk), "");
  // Recover this seed's Scale the way the generator draws it, from the trunk: 0Length · scale.
  const double scale_tree = sk.stems[0].length / p.level[0].length;
  const wp::Envelope e{p.prune_width_peak, p.prune_power_low, p.prune_power_high};
  const double slack = 1e-3 * scale_tree;
  int checked = 0;
  for (const Stem& s : sk.stems) {
    if (s.level == 0) continue;
    for (std::uint32_t k = 1; k < s.point_count; ++k) {
      const glm::vec3 q = sk.points[s.first_point + k].position;
      const bool inside =
          wp::inside_envelope(q.x, q.y, q.z, scale_tree, p.base_size, p.prune_width, e) ||
          wp::inside_envelope(q.x * (1 - slack), q.y * (1 - slack), q.z, scale_tree, p.base_size,
                              p.prune_width, e);
      EXPECT_TRUE(inside) << "stem level " << s.level << " point " << k;
      ++checked;
      if (!inside) return;
    }
  }
  EXPECT_GT(checked, 1000);
  // Unpruned, the same tree reaches outside.
  WeberPennParams unpruned = p;
  unpruned.prune_ratio = 0.0;
  EXPECT_GT(compute_stats(grow(unpruned, 3)).crown_width, compute_stats(sk).crown_width);
}

TEST(WeberPenn, QualityScalesLeafCountAndSize) {
  const WeberPennParams p = paper_species("quaking_aspen");
  const Skeleton full = grow(p, 1, 0.0, 1.0);
  const Skeleton quarter = grow(p, 1, 0.0, 0.25);
  const double ratio = double(quarter.leaves.size()) / double(full.leaves.size());
  EXPECT_NEAR(ratio, 0.25, 0.02);
  EXPECT_NEAR(full.leaves[0].length, 0.17, 1e-6);
  EXPECT_NEAR(quarter.leaves[0].length, 0.17 / 0.5, 1e-6);
  EXPECT_NEAR(quarter.leaves[0].width, 0.17 * 1.0 / 0.5, 1e-6);
}

TEST(WeberPenn, NegativeLeavesMakeAFanAtTheTip) {
  WeberPennParams p = simple_tree(2, 3);
  p.leaves = -7;
  p.level[2].rotate = 120.0;
  const Skeleton sk = grow(p);
  ASSERT_EQ(sk.leaves.size(), 21u);
  for (const Leaf& l : sk.leaves) {
    const Stem& s = sk.stems[static_cast<size_t>(l.stem)];
    const glm::vec3 tip = sk.points[s.first_point + s.point_count - 1].position;
    EXPECT_LT(glm::length(l.position - tip), 1e-4f);
  }
}

TEST(WeberPenn, LeafBendTurnsLeavesUpward) {
  WeberPennParams p = paper_species("black_tupelo");
  auto mean_normal_z = [](const Skeleton& sk) {
    double sum = 0;
    for (const Leaf& l : sk.leaves) sum += l.normal.z;
    return sum / double(sk.leaves.size());
  };
  p.leaf_bend = 0.0;
  const double flat = mean_normal_z(grow(p));
  p.leaf_bend = 1.0;
  const Skeleton bent = grow(p);
  for (const Leaf& l : bent.leaves) EXPECT_NEAR(l.normal.z, 1.0, 1e-4);
  EXPECT_LT(flat, 0.5);
  p.leaf_bend = 0.5;
  const double half = mean_normal_z(grow(p));
  EXPECT_GT(half, flat);
  EXPECT_LT(half, 1.0);
}

TEST(WeberPenn, LeavesAreOrthonormalFrames) {
  const Skeleton sk = grow(paper_species("ca_black_oak"), 2);
  for (const Leaf& l : sk.leaves) {
    ASSERT_NEAR(glm::length(l.axis), 1.0f, 1e-4f);
    ASSERT_NEAR(glm::length(l.normal), 1.0f, 1e-4f);
    ASSERT_NEAR(glm::dot(l.axis, l.normal), 0.0f, 1e-4f);
  }
}

TEST(WeberPenn, WindSwayPerturbsOnlyTheGeometry) {
  WeberPennParams p = paper_species("black_tupelo");
  // Without wind, time changes nothing.
  p.wind_speed = p.wind_gust = 0.0;
  EXPECT_TRUE(same_bytes(grow(p, 4, 0.0), grow(p, 4, 30.0)));
  p.wind_speed = 10.0;
  p.wind_gust = 5.0;
  const Skeleton a = grow(p, 4, 0.0), b = grow(p, 4, 600.0);
  EXPECT_FALSE(same_bytes(a, b));
  ASSERT_EQ(a.stems.size(), b.stems.size());
  ASSERT_EQ(a.leaves.size(), b.leaves.size());
  double moved = 0.0;
  for (size_t i = 0; i < a.stems.size(); ++i) {
    ASSERT_EQ(a.stems[i].parent, b.stems[i].parent);
    ASSERT_EQ(a.stems[i].point_count, b.stems[i].point_count);
  }
  for (size_t i = 0; i < a.points.size(); ++i) {
    moved = std::max(moved, double(glm::length(a.points[i].position - b.points[i].position)));
  }
  EXPECT_GT(moved, 1e-3);
  EXPECT_LT(moved, 0.5 * compute_stats(a).height);
}

// With wind and pruning the envelope prunes the tree at rest, walked beside the swaying one in the
// same growth (issue 31: it was grown twice): at any time the swaying willow has the calm willow's
// stems with their lengths, bit for bit. Power: probing from the swayed pose instead of the pose at
// rest changes the lengths of hundreds of stems.
TEST(WeberPenn, PruningWithWindKeepsTheCalmTreesStems) {
  WeberPennParams p = paper_species("weeping_willow");
  p.levels = 3;  // the branches that the envelope prunes, without the twigs
  ASSERT_GT(p.prune_ratio, 0.0);
  ASSERT_TRUE(p.wind_speed != 0.0 || p.wind_gust != 0.0);
  WeberPennParams calm = p;
  calm.wind_speed = calm.wind_gust = 0.0;
  const Skeleton rest = grow(calm, 6, 0.0);
  for (const double time : {0.0, 2.5, 40.0}) {
    const Skeleton swaying = grow(p, 6, time);
    ASSERT_EQ(swaying.stems.size(), rest.stems.size()) << time;
    double moved = 0.0;
    for (std::size_t i = 0; i < rest.stems.size(); ++i) {
      ASSERT_EQ(swaying.stems[i].length, rest.stems[i].length) << "stem " << i << " t " << time;
      ASSERT_EQ(swaying.stems[i].point_count, rest.stems[i].point_count);
    }
    for (std::size_t i = 0; i < rest.points.size(); ++i)
      moved = std::max(moved,
                       double(glm::length(swaying.points[i].position - rest.points[i].position)));
    EXPECT_GT(moved, 1e-3) << time;
  }
}

// The leaves are oriented in blocks by a vectorised loop; each leaf's axis and normal must be the
// bits that the readable per-leaf code gives: the frame turned by Frame::rotated_z then rotated_x,
// then wp::orient_toward_light. Random frames and angles, plus the special cases: a leaf on the
// trunk's axis, a vertical normal (after the first turn), a level leaf, no bend. 1000 leaves: three
// blocks and a partial one. Power: evaluating the vertical case's θ from the normal fails it.
TEST(WeberPenn, VectorisedLeafOrientationIsTheScalarOneBitForBit) {
  struct Placed {  // a leaf's segment frame and its turns, as LeafOrienter::add takes them
    glm::vec3 x, y, z;
    float turn, down;
  };
  Rng rng(5);
  std::vector<Placed> pending;
  std::vector<Leaf> leaves;
  for (int i = 0; i < 1000; ++i) {
    arbor::Frame f;
    f = f.rotated_x(rng.uniform() * 6.0).rotated_z(rng.uniform() * 6.0).rotated_y(rng.uniform());
    Placed pl{glm::vec3(f.x), glm::vec3(f.y), glm::vec3(f.z),
              static_cast<float>(rng.symmetric() * kPi), static_cast<float>(rng.symmetric() * kPi)};
    Leaf leaf;
    leaf.position = glm::vec3(rng.symmetric() * 3.0, rng.symmetric() * 3.0, rng.uniform() * 9.0);
    if (i % 7 == 0) leaf.position.x = leaf.position.y = 0.0f;  // on the axis
    if (i % 11 == 0) {  // the normal vertical after the turns: frame y up, no turn, no down
      pl.x = {1, 0, 0}, pl.y = {0, 0, 1}, pl.z = {0, -1, 0}, pl.turn = pl.down = 0.0f;
    }
    if (i % 13 == 0) {  // a level leaf that stays level: its normal up, turned about it
      pl.x = {1, 0, 0}, pl.y = {0, 0, 1}, pl.z = {0, -1, 0}, pl.down = 0.0f;
    }
    pending.push_back(pl);
    leaves.push_back(leaf);
  }
  for (const float bend : {0.0f, 0.3f, 1.0f}) {
    std::vector<Leaf> vectorised = leaves;
    wp::LeafOrienter orienter(bend, vectorised);
    for (const Placed& pl : pending) orienter.add(pl.x, pl.y, pl.z, pl.turn, pl.down);
    orienter.flush();
    for (std::size_t i = 0; i < pending.size(); ++i) {
      const Placed& pl = pending[i];
      float st = 0.0f, ct = 1.0f, sd = 0.0f, cd = 1.0f;
      fast_sincos(pl.turn, st, ct);
      fast_sincos(pl.down, sd, cd);
      const glm::vec3 turned_y = ct * pl.y - st * pl.x;
      glm::vec3 axis = cd * pl.z - sd * turned_y, normal = cd * turned_y + sd * pl.z;
      wp::orient_toward_light(bend, leaves[i].position.x, leaves[i].position.y, axis, normal);
      ASSERT_EQ(std::memcmp(&vectorised[i].axis, &axis, sizeof axis), 0) << "leaf " << i;
      ASSERT_EQ(std::memcmp(&vectorised[i].normal, &normal, sizeof normal), 0) << "leaf " << i;
    }
  }
}

TEST(WeberPenn, IndependentStreamsKeepUnrelatedPartsFixed) {
  // Changing the number of sub-branches leaves the trunk and main branches where they were.
  WeberPennParams p = paper_species("quaking_aspen");
  const Skeleton a = grow(p, 9);
  p.level[2].branches = 12;
  const Skeleton b = grow(p, 9);
  int compared = 0;
  for (size_t i = 0, j = 0; i < a.stems.size() && j < b.stems.size(); ++i, ++j) {
    while (i < a.stems.size() && a.stems[i].level > 1) ++i;
    while (j < b.stems.size() && b.stems[j].level > 1) ++j;
    if (i >= a.stems.size() || j >= b.stems.size()) break;
    const Stem& sa = a.stems[i];
    const Stem& sb = b.stems[j];
    ASSERT_EQ(sa.point_count, sb.point_count);
    for (std::uint32_t k = 0; k < sa.point_count; ++k) {
      ASSERT_EQ(a.points[sa.first_point + k].position, b.points[sb.first_point + k].position);
    }
    ++compared;
  }
  EXPECT_EQ(compared, 51);
}

TEST(WeberPenn, ZScaleStretchesHeights) {
  WeberPennParams p = simple_tree(2);
  const double h1 = compute_stats(grow(p)).height;
  p.z_scale = 2.0;
  const double h2 = compute_stats(grow(p)).height;
  EXPECT_NEAR(h2 / h1, 2.0, 0.05);
}

TEST(WeberPenn, RefusesAbsurdSizesUnlessForced) {
  WeberPennParams p = simple_tree(4, 2000);
  p.leaves = 50;
  const SizeEstimate e = estimate_size(p, 1.0);
  EXPECT_GT(e.stems, 1e9);
  GrowOptions o;
  try {
    grow_weber_penn(p, o);
    FAIL() << "an absurd tree was grown";
  } catch (const RuntimeFailure& err) {
    EXPECT_NE(std::string(err.what()).find("--force"), std::string::npos);
  }
  // The estimate of a paper species is near what actually grows (within a factor of a few).
  const WeberPennParams aspen = paper_species("quaking_aspen");
  const double grown = double(grow(aspen).stems.size());
  EXPECT_GE(estimate_size(aspen, 1.0).stems, grown);
  EXPECT_LT(estimate_size(aspen, 1.0).stems, 5.0 * grown);
  // Forced, a tree over the limit grows whole: the aspen under a limit of a tenth of its stems.
  GrowOptions small;
  small.seed = 1;
  small.max_stems = grown / 10.0;
  EXPECT_THROW(grow_weber_penn(aspen, small), RuntimeFailure);
  small.force = true;
  EXPECT_EQ(double(grow_weber_penn(aspen, small).stems.size()), grown);
}

}  // namespace arbor::generator
