// Tests of Ünal's fractal model: the basic recursion, pruning, the refined perturbations, and
// time-awareness (logarithmic growth, depth from age, the same tree over time).
#include "generator/models/fractal/fractal.h"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "generator/grow.h"
#include "generator/species.h"
#include "generator/export/tree_stats.h"
#include "formats/species_file.h"

namespace arbor::generator {

namespace {

FractalParams basic() {
  FractalParams p;
  p.depth = 4;
  p.branches = 3;
  p.cone_angle = 60.0;
  p.size_ratio = 0.5;
  p.taper = 0.5;
  p.length = 2.0;
  p.radius = 0.1;
  p.discs = 3;
  p.twist = 0.0;
  return p;
}

Skeleton grow(const FractalParams& p, double time = 0.0, std::uint64_t seed = 1) {
  FractalOptions o;
  o.time = time;
  o.seed = seed;
  return grow_fractal(p, o);
}

glm::dvec3 direction(const Skeleton& sk, const Stem& s) {
  return glm::normalize(glm::dvec3(sk.points[s.first_point + s.point_count - 1].position -
                                   sk.points[s.first_point].position));
}

}  // namespace

TEST(Fractal, GrowthIsLogarithmicAsTheThesisStates) {
  // §3.3: with a level every n, 0.5 at n/2, 0.75 at n, 0.875 at 2n, 93.75 % at 4n.
  EXPECT_DOUBLE_EQ(fractal_growth(2.0, 4.0), 0.5);
  EXPECT_DOUBLE_EQ(fractal_growth(4.0, 4.0), 0.75);
  EXPECT_DOUBLE_EQ(fractal_growth(8.0, 4.0), 0.875);
  EXPECT_DOUBLE_EQ(fractal_growth(16.0, 4.0), 0.9375);
  EXPECT_DOUBLE_EQ(fractal_growth(0.0, 4.0), 0.0);
  EXPECT_DOUBLE_EQ(fractal_growth(1.0, 4.0), 0.25);
  // Continuous and increasing.
  for (double a = 0.1; a < 30.0; a += 0.1)
    EXPECT_LT(fractal_growth(a, 4.0), fractal_growth(a + 0.1, 4.0));
}

TEST(Fractal, BasicModelIsExactlySelfSimilar) {
  // Very old, so every level has reached its full size (growth 1 − n/4a ≈ 1).
  const Skeleton sk = grow(basic(), 1e7);
  const TreeStats st = compute_stats(sk);
  ASSERT_EQ(st.stems_per_level.size(), 4u);
  EXPECT_EQ(st.stems_per_level[1], 3);
  EXPECT_EQ(st.stems_per_level[3], 27);
  EXPECT_EQ(validate(sk), "");
  // Children start at their parent's tip, on the cone: 30° from its axis, half as long.
  for (const Stem& s : sk.stems) {
    if (s.parent < 0) continue;
    const Stem& p = sk.stems[static_cast<size_t>(s.parent)];
    EXPECT_EQ(s.parent_point, static_cast<int>(p.point_count) - 1);
    const double angle =
        std::acos(glm::dot(direction(sk, s), direction(sk, p))) * 180.0 / 3.14159265358979;
    EXPECT_NEAR(angle, 30.0, 1e-3);
    EXPECT_NEAR(s.length, 0.5 * p.length, 1e-5);
    EXPECT_NEAR(sk.points[s.first_point].radius,
                sk.points[p.first_point + p.point_count - 1].radius, 1e-6);
  }
}

TEST(Fractal, PruningRemovesChildrenAndTheirDescendants) {
  FractalParams p = basic();
  p.depth = 6;
  p.prune = 0.3;
  const Skeleton sk = grow(p, 0.0, 5);
  const TreeStats st = compute_stats(sk);
  EXPECT_LT(st.stems(), 364);  // 1 + 3 + … + 243 without pruning
  EXPECT_GT(st.stems(), 20);
  EXPECT_EQ(validate(sk), "");
  // Pruning is implicit downward: a level never has more than 3 × the level above.
  for (std::size_t l = 1; l < st.stems_per_level.size(); ++l) {
    EXPECT_LE(st.stems_per_level[l], 3 * st.stems_per_level[l - 1]);
  }
}

TEST(Fractal, RefinedModelWigglesAxesAndRadii) {
  FractalParams p = basic();
  p.discs = 8;
  p.wiggle = 0.05;
  p.radius_variation = 0.1;
  const Skeleton sk = grow(p);
  const Stem& trunk = sk.stems[0];
  const glm::dvec3 a(sk.points[trunk.first_point].position);
  const glm::dvec3 b(sk.points[trunk.first_point + trunk.point_count - 1].position);
  double off_axis = 0.0;
  for (std::uint32_t k = 1; k + 1 < trunk.point_count; ++k) {
    const glm::dvec3 q(sk.points[trunk.first_point + k].position);
    off_axis = std::max(off_axis, glm::length(glm::cross(q - a, glm::normalize(b - a))));
  }
  EXPECT_GT(off_axis, 0.005);
  EXPECT_LT(off_axis, 0.05 * 2.0 * std::sqrt(2.0) + 1e-9);
  // Radii never grow along a branch or past the parent at a joint.
  EXPECT_EQ(validate(sk), "");
  for (const Stem& s : sk.stems) {
    for (std::uint32_t k = 1; k < s.point_count; ++k) {
      EXPECT_LE(sk.points[s.first_point + k].radius, sk.points[s.first_point + k - 1].radius);
    }
  }
}

TEST(Fractal, TimeAddsLevelsAndGrowsTheSameTree) {
  FractalParams p = basic();
  p.depth = 5;
  p.prune = 0.2;
  p.angle_variation = 0.2;
  p.length_variation = 0.2;
  p.years_per_level = 4.0;
  // Depth from time: a level every 4 units.
  EXPECT_EQ(compute_stats(grow(p, 3.0)).stems_per_level.size(), 1u);
  EXPECT_EQ(compute_stats(grow(p, 9.0)).stems_per_level.size(), 3u);
  // The trunk grows by the growth factor.
  EXPECT_NEAR(grow(p, 2.0).stems[0].length, 0.5 * grow(p, 1e4).stems[0].length, 1e-3);
  // Every branch that exists at t exists at t + dt, pointing the same way, only longer.
  const Skeleton young = grow(p, 13.0), old = grow(p, 14.0);
  ASSERT_LE(young.stems.size(), old.stems.size());
  std::size_t matched = 0;
  for (std::size_t i = 0, j = 0; i < young.stems.size(); ++i, ++j) {
    while (j < old.stems.size() && (old.stems[j].level != young.stems[i].level)) ++j;
    ASSERT_LT(j, old.stems.size());
    EXPECT_GT(glm::dot(direction(young, young.stems[i]), direction(old, old.stems[j])), 0.95);
    EXPECT_LE(young.stems[i].length, old.stems[j].length + 1e-6f);
    ++matched;
  }
  EXPECT_EQ(matched, young.stems.size());
}

TEST(Fractal, ConeWidensAsChildrenGrow) {
  FractalParams p = basic();
  p.depth = 2;
  p.cone_widening = 0.5;
  auto child_angle = [&](double t) {
    const Skeleton sk = grow(p, t);
    return std::acos(glm::dot(direction(sk, sk.stems[1]), direction(sk, sk.stems[0]))) * 180.0 /
           3.14159265358979;
  };
  EXPECT_LT(child_angle(5.0), child_angle(50.0));
  EXPECT_NEAR(child_angle(1e5), 30.0, 0.01);
}

TEST(Fractal, SpeciesFilesLoadAndBadKeysAreErrors) {
  const Species s =
      formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/fractal_broadleaf.toml");
  EXPECT_EQ(s.model(), Model::Fractal);
  EXPECT_EQ(s.fractal().depth, 6);
  try {
    formats::parse_species_toml("model = \"fractal\"\nbranches = 2.5\n", "f.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 2);
    EXPECT_NE(e.message().find("whole number"), std::string::npos);
  }
  try {
    formats::parse_species_toml("model = \"fractal\"\nShape = 3\n", "f.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("unknown key 'Shape' for model = \"fractal\""), std::string::npos);
  }
  try {
    formats::parse_species_toml("model = \"fractal\"\ncone_angle = 200\n", "f.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().column, 14);
  }
}

TEST(Fractal, AbsurdSizesAreRefusedWithTheEstimate) {
  FractalParams p = basic();
  p.depth = 30;
  p.branches = 8;
  try {
    grow(p);
    FAIL();
  } catch (const RuntimeFailure& e) {
    EXPECT_NE(std::string(e.what()).find("branches"), std::string::npos);
  }
}

// Found by fuzzing (tests/fuzz/regressions/): size ratio 0.05 over seven levels makes twigs of
// 39 nm, whose splines are NaN in float; such a tree is refused, naming its file.
TEST(Fractal, TwigsShorterThanAMicrometreAreRefused) {
  const std::string path =
      std::string(ARBOR_SOURCE_DIR) + "/tests/fuzz/regressions/fractal_tiny_twigs.toml";
  const Species s = formats::load_species(path);
  try {
    grow_tree(s, GrowOptions{});
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().path, path);
    EXPECT_NE(e.message().find("shorter than 1 micrometre"), std::string::npos) << e.what();
  }
}

}  // namespace arbor::generator
