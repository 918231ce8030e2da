// Tests of the limb splines: interpolation, C2 continuity, clamped ends, frames, dominance.
#include "generator/geometry/limb_splines.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "generator/geometry/limbs.h"
#include "generator/species.h"
#include "generator/models/weber_penn/weber_penn.h"
#include "formats/species_file.h"

namespace arbor::generator {

namespace {

std::vector<DVec3> wiggly_points() {
  return {{0, 0, 0},        {0.3, 0.1, 1.0},  {0.2, 0.5, 2.2},
          {-0.4, 0.6, 2.9}, {-0.5, 0.2, 4.5}, {0.1, -0.3, 5.0}};
}

Skeleton grow_species(const char* name, std::uint64_t seed = 1) {
  const Species s =
      formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/" + name + ".toml");
  GrowOptions o;
  o.seed = seed;
  o.quality = 0.2;
  return grow_weber_penn(s.weber_penn(), o);
}

}  // namespace

TEST(CubicSpline, InterpolatesEveryPointWithChordLengthParameters) {
  const std::vector<DVec3> pts = wiggly_points();
  const CubicSpline s = fit_c2_spline(pts, {0, 0, 1}, {0, 0, 1});
  for (std::size_t i = 0; i < pts.size(); ++i) {
    EXPECT_LT(glm::length(s.position(s.params[i]) - pts[i]), 1e-12);
  }
  for (std::size_t i = 1; i < pts.size(); ++i) {
    EXPECT_NEAR(s.params[i] - s.params[i - 1], glm::length(pts[i] - pts[i - 1]), 1e-12);
  }
}

TEST(CubicSpline, IsC2AtInteriorKnotsAndClampedAtTheEnds) {
  const std::vector<DVec3> pts = wiggly_points();
  const DVec3 start(0.2, 0.0, 0.9), end(0.0, -0.6, 0.5);
  const CubicSpline s = fit_c2_spline(pts, start, end);
  EXPECT_LT(glm::length(s.derivative(0.0) - start), 1e-12);
  EXPECT_LT(glm::length(s.derivative(s.params.back()) - end), 1e-12);
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const double t = s.params[i], e = 1e-9;
    EXPECT_LT(glm::length(s.position(t - e) - s.position(t + e)), 1e-7);      // C0
    EXPECT_LT(glm::length(s.derivative(t - e) - s.derivative(t + e)), 1e-6);  // C1
    EXPECT_LT(glm::length(s.second_derivative_at_knot(i, -1) - s.second_derivative_at_knot(i, +1)),
              1e-9);  // C2
  }
}

TEST(CubicSpline, StraightPointsGiveAStraightLine) {
  const std::vector<DVec3> pts{{0, 0, 0}, {0, 0, 1}, {0, 0, 3}, {0, 0, 3.5}};
  const CubicSpline s = fit_c2_spline(pts, {0, 0, 1}, {0, 0, 1});
  for (double t = 0.0; t <= 3.5; t += 0.05) {
    const DVec3 p = s.position(t);
    EXPECT_NEAR(p.x, 0.0, 1e-12);
    EXPECT_NEAR(p.y, 0.0, 1e-12);
    EXPECT_NEAR(p.z, t, 1e-9);  // unit speed: the parameter is arc length
    EXPECT_NEAR(s.curvature(t), 0.0, 1e-9);
  }
}

TEST(RotationMinimizingFrames, AreOrthonormalAndDoNotTwistOnStraightLimbs) {
  const std::vector<DVec3> straight{{0, 0, 0}, {0, 0, 1}, {0, 0, 2}, {0, 0, 3}};
  const CubicSpline s = fit_c2_spline(straight, {0, 0, 1}, {0, 0, 1});
  std::vector<double> ts;
  for (int i = 0; i <= 30; ++i) ts.push_back(0.1 * i);
  const auto frames = rotation_minimizing_frames(s, ts, {1, 0, 0});
  for (const FrameSample& f : frames) {
    EXPECT_NEAR(glm::length(f.normal), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(f.normal, f.tangent), 0.0, 1e-12);
    EXPECT_LT(glm::length(f.normal - DVec3(1, 0, 0)), 1e-12);  // no twist at all
  }
}

TEST(RotationMinimizingFrames, StayInPlaneOnPlanarCurvesThroughInflections) {
  // An S-curve in the xz plane: the binormal-free normal stays ⟂ the plane (no flips at the
  // inflection, where a Frenet frame would flip or be undefined).
  const std::vector<DVec3> s_curve{{0, 0, 0}, {0.5, 0, 1}, {0, 0, 2}, {-0.5, 0, 3}, {0, 0, 4}};
  const CubicSpline s = fit_c2_spline(s_curve, {0, 0, 1}, {0, 0, 1});
  std::vector<double> ts;
  for (int i = 0; i <= 100; ++i) ts.push_back(s.params.back() * i / 100.0);
  const auto frames = rotation_minimizing_frames(s, ts, {0, 1, 0});
  for (const FrameSample& f : frames) {
    EXPECT_NEAR(std::fabs(f.normal.y), 1.0, 1e-9);
    EXPECT_GT(f.normal.y, 0.0);
  }
}

TEST(Limbs, DominantContinuationIsOneC2Spline) {
  // A trunk that splits: the dominant stem continues the incoming spline (C2 through the branch
  // point); the other starts its own spline with the parent's direction.
  const Skeleton sk = grow_species("ca_black_oak", 3);
  const std::vector<Limb> limbs = fit_limbs(sk);
  int chains_through_clones = 0;
  for (const Limb& l : limbs) {
    bool through_clone = false;
    for (std::size_t i = 1; i < l.knots.size(); ++i) {
      if (l.knots[i].stem != l.knots[i - 1].stem) through_clone = true;
    }
    if (!through_clone) continue;
    ++chains_through_clones;
    for (std::size_t i = 1; i + 1 < l.knots.size(); ++i) {
      const double scale = glm::length(l.spline.second_derivative_at_knot(i, -1)) + 1.0;
      EXPECT_LT(glm::length(l.spline.second_derivative_at_knot(i, -1) -
                            l.spline.second_derivative_at_knot(i, +1)) /
                    scale,
                1e-6);
    }
  }
  EXPECT_GT(chains_through_clones, 0);
}

TEST(Limbs, EveryStemPointIsOnSomeLimbAndLimbsInterpolateThem) {
  const Skeleton sk = grow_species("weeping_willow");
  const std::vector<Limb> limbs = fit_limbs(sk);
  std::vector<std::vector<bool>> covered(sk.stems.size());
  for (std::size_t s = 0; s < sk.stems.size(); ++s)
    covered[s].assign(sk.stems[s].point_count, false);
  for (const Limb& l : limbs) {
    for (std::size_t i = 0; i < l.knots.size(); ++i) {
      const KnotRef k = l.knots[i];
      covered[static_cast<size_t>(k.stem)][k.point] = true;
      const glm::vec3 p =
          sk.points[sk.stems[static_cast<size_t>(k.stem)].first_point + k.point].position;
      // A child limb's first knot is on its parent's spline at the branch point (the skeleton's
      // point there is on the chord between the parent's points); every other knot is its point.
      const DVec3 knot = i == 0 && l.parent >= 0
                             ? limbs[static_cast<size_t>(l.parent)].spline.position(l.parent_param)
                             : DVec3(p);
      ASSERT_LT(glm::length(l.spline.position(l.spline.params[i]) - knot), 1e-5);
    }
  }
  for (std::size_t s = 0; s < sk.stems.size(); ++s) {
    for (std::size_t k = 1; k < covered[s].size(); ++k) {
      ASSERT_TRUE(covered[s][k]) << "stem " << s << " point " << k;
    }
  }
}

TEST(Limbs, BranchesLeaveAlongTheParentScaledByTension) {
  const Skeleton sk = grow_species("quaking_aspen");
  const std::vector<Limb> limbs = fit_limbs(sk);
  int checked = 0;
  for (const Limb& l : limbs) {
    if (l.parent < 0) continue;
    const Limb& p = limbs[static_cast<size_t>(l.parent)];
    const DVec3 parent_dir = glm::normalize(p.spline.derivative(l.parent_param));
    const DVec3 start = l.spline.derivative(0.0);
    EXPECT_NEAR(glm::length(start), l.tension, 1e-9);
    EXPECT_GT(glm::dot(glm::normalize(start), parent_dir), 1.0 - 1e-9);
    EXPECT_GE(l.tension, kMinTension);
    EXPECT_LE(l.tension, 1.0);
    // Frames are propagated: the child's first normal is the parent's, made ⟂ its tangent.
    EXPECT_NEAR(glm::dot(l.knot_normals[0], glm::normalize(start)), 0.0, 1e-9);
    ++checked;
  }
  EXPECT_EQ(checked, 1250);
  EXPECT_DOUBLE_EQ(branch_tension(0.01, 0.1), 0.1);
  EXPECT_DOUBLE_EQ(branch_tension(0.001, 0.1), kMinTension);
  EXPECT_DOUBLE_EQ(branch_tension(0.2, 0.1), 1.0);
}

TEST(Limbs, BarkArcLengthIsContinuousAndIncreasing) {
  const Skeleton sk = grow_species("black_tupelo");
  for (const Limb& l : fit_limbs(sk)) {
    for (std::size_t i = 1; i < l.knot_arc.size(); ++i) {
      const double chord = glm::length(l.spline.points[i] - l.spline.points[i - 1]);
      ASSERT_GE(l.knot_arc[i] - l.knot_arc[i - 1], chord * (1.0 - 1e-9));  // arc ≥ chord
      ASSERT_LT(l.knot_arc[i] - l.knot_arc[i - 1], chord * 1.5);
    }
  }
}

}  // namespace arbor::generator
