// Tests of the Weber & Penn §4 equations, one formula family at a time, against values worked
// out by hand from the paper.
#include "generator/models/weber_penn/weber_penn_formulas.h"

#include <cmath>

#include <gtest/gtest.h>
#include "common/math.h"

namespace arbor::generator::wp {

TEST(ShapeRatio, MatchesThePaperTable) {
  EXPECT_DOUBLE_EQ(shape_ratio(0, 0.5), 0.6);                      // conical: 0.2 + 0.8 r
  EXPECT_DOUBLE_EQ(shape_ratio(1, 0.5), 1.0);                      // spherical
  EXPECT_NEAR(shape_ratio(2, 1.0 / 3.0), 0.2 + 0.8 * 0.5, 1e-12);  // hemispherical
  EXPECT_DOUBLE_EQ(shape_ratio(3, 0.1), 1.0);                      // cylindrical
  EXPECT_DOUBLE_EQ(shape_ratio(4, 0.2), 0.6);                      // tapered cylindrical
  EXPECT_DOUBLE_EQ(shape_ratio(5, 0.35), 0.5);                     // flame, rising
  EXPECT_NEAR(shape_ratio(5, 0.85), 0.5, 1e-12);                   // flame, falling
  EXPECT_DOUBLE_EQ(shape_ratio(6, 0.5), 0.6);                      // inverse conical
  EXPECT_NEAR(shape_ratio(7, 0.7), 1.0, 1e-12);                    // tend flame peak
  EXPECT_NEAR(shape_ratio(7, 1.0), 0.5, 1e-12);
}

TEST(ShapeRatio, ConicalIsThePapersNotArbaros) {
  // The paper's conical shape is 0.2 + 0.8 r; Arbaro uses r (documented difference).
  EXPECT_DOUBLE_EQ(shape_ratio(0, 0.0), 0.2);
  EXPECT_DOUBLE_EQ(shape_ratio(0, 1.0), 1.0);
}

TEST(PruningEnvelope, IsContinuousAtThePeakAndZeroOutside) {
  const Envelope e{0.6, 0.001, 0.5};  // the Weeping Willow's envelope
  EXPECT_DOUBLE_EQ(envelope_ratio(1.0 - 0.6, e), 1.0);
  EXPECT_NEAR(envelope_ratio(0.4 - 1e-9, e), 1.0, 1e-6);
  EXPECT_NEAR(envelope_ratio(0.4 + 1e-9, e), 1.0, 1e-6);
  EXPECT_EQ(envelope_ratio(-0.01, e), 0.0);
  EXPECT_EQ(envelope_ratio(1.01, e), 0.0);
  // Above the peak: (ratio / (1 - peak))^PrunePowerHigh.
  EXPECT_NEAR(envelope_ratio(0.1, e), std::pow(0.1 / 0.4, 0.5), 1e-12);
  // Below the peak: ((1 - ratio) / peak)^PrunePowerLow.
  EXPECT_NEAR(envelope_ratio(0.7, e), std::pow(0.3 / 0.6, 0.001), 1e-12);
  EXPECT_DOUBLE_EQ(shape_ratio(8, 0.4, e), 1.0);
}

TEST(PruningEnvelope, InsideTestUsesHorizontalDistance) {
  const Envelope e{0.5, 1.0, 1.0};
  // scale 10, base 0.2: envelope from z = 2 to z = 10, widest (PruneWidth · 10 = 5 m) at z = 6.
  EXPECT_TRUE(inside_envelope(4.9, 0.0, 6.0, 10.0, 0.2, 0.5, e));
  EXPECT_FALSE(inside_envelope(5.1, 0.0, 6.0, 10.0, 0.2, 0.5, e));
  EXPECT_TRUE(inside_envelope(0.0, 2.4, 8.0, 10.0, 0.2, 0.5, e));  // half width at 3/4 height
  EXPECT_FALSE(inside_envelope(0.0, 2.6, 8.0, 10.0, 0.2, 0.5, e));
  EXPECT_FALSE(inside_envelope(0.0, 0.0, 10.5, 10.0, 0.2, 0.5, e));  // above the top
  EXPECT_FALSE(inside_envelope(0.1, 0.0, 1.0, 10.0, 0.2, 0.5, e));   // below the bottom
}

TEST(Taper, CylinderConeAndInBetween) {
  EXPECT_DOUBLE_EQ(taper_radius(0.0, 2.0, 10.0, 0.7), 2.0);
  EXPECT_DOUBLE_EQ(taper_radius(1.0, 2.0, 10.0, 0.25), 1.5);
  EXPECT_DOUBLE_EQ(taper_radius(1.0, 2.0, 10.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(taper_radius(0.5, 2.0, 10.0, 1.0), 1.0);  // unit_taper = nTaper
}

TEST(Taper, SphericalEndRoundsTheTip) {
  // nTaper = 2: a cylinder of radius 1 whose last metre is a hemisphere.
  EXPECT_DOUBLE_EQ(taper_radius(2.0, 1.0, 10.0, 0.5), 1.0);
  EXPECT_NEAR(taper_radius(2.0, 1.0, 10.0, 0.95), std::sqrt(1.0 - 0.25), 1e-12);  // 0.5 m left
  EXPECT_NEAR(taper_radius(2.0, 1.0, 10.0, 1.0), 0.0, 1e-12);
}

TEST(Taper, PeriodicMakesConcatenatedSpheres) {
  // nTaper = 3: spheres of radius 1 along a stem of length 10: radius 0 at each 2 m node.
  const double r = 1.0, L = 10.0;
  // (sqrt near zero amplifies rounding of z: 1e-15 in z is 3e-8 in radius)
  EXPECT_NEAR(taper_radius(3.0, r, L, 1.0 - 0.2), 0.0, 1e-6);   // 2 m from the tip
  EXPECT_NEAR(taper_radius(3.0, r, L, 1.0 - 0.1), 1.0, 1e-12);  // sphere centre
  EXPECT_NEAR(taper_radius(3.0, r, L, 1.0 - 0.15), std::sqrt(1 - 0.25), 1e-12);
  // nTaper = 2.5: halfway between cylinder and spheres away from the tip.
  EXPECT_NEAR(taper_radius(2.5, r, L, 1.0 - 0.2), 0.5, 1e-6);
}

TEST(Flare, IsOnePlusFlareAtTheBaseAndOneAboveAnEighth) {
  EXPECT_NEAR(flare_scale(0.6, 0.0), 1.0 + 0.6 * 99.0 / 100.0, 1e-12);
  EXPECT_DOUBLE_EQ(flare_scale(0.6, 0.125), 1.0);
  EXPECT_DOUBLE_EQ(flare_scale(0.6, 0.5), 1.0);
  EXPECT_NEAR(flare_scale(1.0, 1.0 / 16.0), 1.0 + 9.0 / 100.0, 1e-12);  // y = 0.5: 100^0.5 = 10
}

TEST(Lobes, FollowTheSineAboutTheAxis) {
  EXPECT_DOUBLE_EQ(lobe_scale(5, 0.07, 0.0), 1.0);
  EXPECT_NEAR(lobe_scale(5, 0.07, kPi / 10.0), 1.07, 1e-12);
  EXPECT_NEAR(lobe_scale(5, 0.07, 3.0 * kPi / 10.0), 0.93, 1e-12);
  EXPECT_DOUBLE_EQ(lobe_scale(5, 0.0, 1.234), 1.0);
}

TEST(SplitDiffusion, DistributesFractionalSplitsEvenly) {
  // nSegSplits = 1.2: 80 % of segments get one clone, 20 % two; never three in a row of twos.
  SplitDiffusion d;
  int ones = 0, twos = 0, run = 0, worst_run = 0, total = 0;
  for (int i = 0; i < 1000; ++i) {
    const int n = d.next(1.2);
    total += n;
    if (n == 1) ++ones;
    if (n == 2) ++twos;
    run = n == 2 ? run + 1 : 0;
    worst_run = std::max(worst_run, run);
  }
  EXPECT_EQ(ones, 800);
  EXPECT_EQ(twos, 200);
  EXPECT_EQ(total, 1200);
  EXPECT_EQ(worst_run, 1);
  EXPECT_LT(std::fabs(d.error), 1.0);
}

TEST(SplitDiffusion, SmallFractionsStillSplitSometimes) {
  SplitDiffusion d;
  int total = 0;
  for (int i = 0; i < 100; ++i) total += d.next(0.1);
  EXPECT_EQ(total, 10);
}

TEST(SplitAngle, SubtractsDeclinationAndStopsAtZero) {
  EXPECT_DOUBLE_EQ(split_angle(30.0, 0.0), 30.0);
  EXPECT_DOUBLE_EQ(split_angle(30.0, 20.0), 10.0);
  EXPECT_DOUBLE_EQ(split_angle(30.0, 45.0), 0.0);
}

TEST(SplitSpread, SpansTwentyToFiftyForHorizontalAndUpTo140ForVertical) {
  EXPECT_DOUBLE_EQ(split_spread(90.0, 0.0), 20.0);
  EXPECT_DOUBLE_EQ(split_spread(90.0, 1.0), 20.0 + 0.75 * 30.0);  // 42.5
  EXPECT_DOUBLE_EQ(split_spread(0.0, 1.0), 20.0 + 0.75 * 120.0);  // 110
  EXPECT_DOUBLE_EQ(split_spread(0.0, 0.5), 20.0 + 0.75 * 120.0 * 0.25);
}

TEST(ChildCounts, FollowThePaperFormulas) {
  // First level: stems_max · (0.2 + 0.8 · (L_child / L_parent) / L_child,max).
  EXPECT_DOUBLE_EQ(children_of_first_level(30.0, 3.0, 10.0, 0.3), 30.0);
  EXPECT_DOUBLE_EQ(children_of_first_level(30.0, 1.5, 10.0, 0.3), 30.0 * 0.6);
  // Deeper levels: stems_max · (1 - 0.5 · offset / L_parent).
  EXPECT_DOUBLE_EQ(children_of_deeper_level(10.0, 0.0, 4.0), 10.0);
  EXPECT_DOUBLE_EQ(children_of_deeper_level(10.0, 4.0, 4.0), 5.0);
  // Leaves: Leaves · ShapeRatio(4, offset / L_parent) · quality.
  EXPECT_DOUBLE_EQ(leaves_per_branch(25.0, 2.0, 4.0, 1.0), 25.0 * 0.75);
  EXPECT_DOUBLE_EQ(leaves_per_branch(25.0, 2.0, 4.0, 0.5), 25.0 * 0.75 * 0.5);
}

TEST(ChildLengths, FollowThePaperFormulas) {
  // First level: L_trunk · L_max · ShapeRatio(Shape, (L_trunk - offset) / (L_trunk - L_base)).
  EXPECT_DOUBLE_EQ(first_level_length(3, 10.0, 0.3, 5.0, 2.0, {}), 3.0);
  EXPECT_NEAR(first_level_length(0, 10.0, 0.3, 6.0, 2.0, {}), 10 * 0.3 * (0.2 + 0.8 * 0.5), 1e-12);
  // Deeper: L_max · (L_parent - 0.6 · offset).
  EXPECT_DOUBLE_EQ(deeper_level_length(0.5, 4.0, 2.0), 0.5 * (4.0 - 1.2));
}

TEST(DownAngle, NegativeVariationRunsAlongTheParent) {
  // nDownAngle 60, nDownAngleV -50 (Quaking Aspen): 110° at the base of the crown, 30° at the top.
  EXPECT_NEAR(down_angle_along_parent(60, -50, 13.0, 5.2, 5.2), 110.0, 1e-9);
  EXPECT_NEAR(down_angle_along_parent(60, -50, 13.0, 13.0, 5.2), 30.0, 1e-9);
  const double mid = down_angle_along_parent(60, -50, 13.0, 9.1, 5.2);
  EXPECT_NEAR(mid, 60.0 - 50.0 * (1.0 - 2.0 * 0.6), 1e-9);
}

TEST(Sway, IsZeroWithoutWindAndFollowsThePaper) {
  const Sway calm = sway_angles(0, 0, 10, 0.2, 0.1, 0.5, 5, 3.0, 0.4, 1.1);
  EXPECT_EQ(calm.x, 0.0);
  EXPECT_EQ(calm.y, 0.0);
  const double a0 = 4.0 * 10.0 * 0.5 / 0.1;
  const double a1 = 5.0 / 50.0 * a0, a2 = 2.0 / 50.0 * a0 + a1 / 2.0;
  // The phase rate as arbor reads it: length / radius × time / 15 (the paper prints radius /
  // length).
  const double b = 0.4 + 10.0 / 0.2 * 3.0 / 15.0;
  const Sway s = sway_angles(5, 2, 10, 0.2, 0.1, 0.5, 5, 3.0, 0.4, 1.1);
  EXPECT_NEAR(s.x, (a1 * std::sin(b) + a2 * std::sin(0.7 * b)) / 5.0, 1e-12);
  const double by = 1.1 + 10.0 / 0.2 * 3.0 / 15.0;
  EXPECT_NEAR(s.y, (a1 * std::sin(by) + a2 * std::sin(0.7 * by)) / 5.0, 1e-12);
}

TEST(Sway, PeriodsAreSecondsForATrunkAndLessForATwig) {
  // The slower of the two terms, sin(0.7 b), has period 2π / (0.7 rate): a 12 m trunk of radius
  // 0.25 m about 2.8 s, a 0.3 m twig of radius 3 mm about 1.3 s.
  auto period = [](double length, double radius) {
    return 2.0 * kPi / (0.7 * length / radius / 15.0);
  };
  EXPECT_NEAR(period(12.0, 0.25), 2.8, 0.1);
  EXPECT_NEAR(period(0.3, 0.003), 1.35, 0.05);
  // Half a period of the twig's faster term moves it by degrees.
  const double half = kPi / (0.3 / 0.003 / 15.0);
  const Sway a = sway_angles(5, 2, 0.3, 0.003, 0.002, 0.2, 3, 0.0, 0.0, 0.0);
  const Sway b = sway_angles(5, 2, 0.3, 0.003, 0.002, 0.2, 3, half, 0.0, 0.0);
  EXPECT_GT(std::fabs(a.x - b.x), 1.0);  // degrees
}

TEST(AttractionUp, IsLargestForHorizontalStemsFacingUp) {
  EXPECT_NEAR(attraction_up(1.0, 0.0, 1.0, 4), kPi / 2 / 4, 1e-12);  // horizontal, y up
  EXPECT_NEAR(attraction_up(1.0, 1.0, 0.0, 4), 0.0, 1e-12);          // already vertical
  EXPECT_NEAR(attraction_up(-3.0, 0.0, 1.0, 1), -3.0 * kPi / 2, 1e-12);
}

}  // namespace arbor::generator::wp
