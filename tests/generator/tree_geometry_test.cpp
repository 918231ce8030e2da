// Tests of TreeGeometry: Embree's radius rule, continuity of the curve segments, the displaced
// trunk, bark coordinates, leaves.
#include "generator/geometry/tree_geometry.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/rng.h"
#include "generator/geometry/geometry_plan.h"
#include "generator/geometry/leaf_shapes.h"
#include "generator/geometry/limbs.h"
#include "generator/grow.h"
#include "generator/geometry/tree_mesh.h"
#include "generator/species.h"
#include "generator/models/weber_penn/weber_penn.h"
#include "generator/models/weber_penn/weber_penn_formulas.h"
#include "formats/species_file.h"

namespace arbor::generator {

namespace {

Skeleton grow_species(const char* name, std::uint64_t seed = 1, double quality = 0.2) {
  const Species s =
      formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/" + name + ".toml");
  GrowOptions o;
  o.seed = seed;
  o.quality = quality;
  return grow_weber_penn(s.weber_penn(), o);
}

TEST(TreeGeometry, SecondDerivativeMatchesFiniteDifferences) {
  CurveSet c;
  c.points = {glm::vec4(0, 0, 0, 0.3f), glm::vec4(1, 2, 3, 0.1f)};
  c.tangents = {glm::vec4(0.5f, -1, 2, -0.1f), glm::vec4(-2, 1, 0.5f, 0.05f)};
  for (float u : {0.0f, 0.3f, 0.7f, 1.0f}) {
    const float h = 1e-3f;
    const glm::vec4 fd = (c.derivative(0, u + h) - c.derivative(0, u - h)) / (2 * h);
    const glm::vec4 d2 = c.second_derivative(0, u);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(d2[k], fd[k], 1e-2) << "u " << u << " component " << k;
  }
}

double curvature(const CurveSet& c, std::size_t i, float u) {
  const glm::dvec3 d1(c.derivative(i, u)), d2(c.second_derivative(i, u));
  const double speed = glm::length(d1);
  return glm::length(glm::cross(d1, d2)) / (speed * speed * speed);
}

}  // namespace

TEST(TreeGeometry, RadiusStaysBelowTheRadiusOfCurvature) {
  for (const char* name : {"quaking_aspen", "black_tupelo", "weeping_willow", "ca_black_oak"}) {
    for (std::uint64_t seed : {1u, 2u}) {
      const TreeGeometry g = build_tree_geometry(grow_species(name, seed));
      double worst = 0.0;
      for (std::size_t i = 0; i < g.curves.size(); ++i) {
        for (int k = 0; k <= 40; ++k) {
          const float u = k / 40.0f;
          worst = std::max(worst, g.curves.position(i, u).w * curvature(g.curves, i, u));
        }
      }
      EXPECT_LT(worst, 1.0) << name << " seed " << seed;
    }
  }
}

TEST(TreeGeometry, ConsecutiveSegmentsOfALimbJoinWithContinuousTangentAndCurvature) {
  const TreeGeometry g = build_tree_geometry(grow_species("black_tupelo"));
  int joints = 0;
  for (std::size_t i = 0; i + 1 < g.curves.size(); ++i) {
    if (g.curves.segments[i].limb != g.curves.segments[i + 1].limb) continue;
    const glm::vec4 end = g.curves.position(i, 1.0f), start = g.curves.position(i + 1, 0.0f);
    ASSERT_LT(glm::length(glm::vec3(end - start)), 1e-5f);
    ASSERT_NEAR(end.w, start.w, 1e-6f);  // radius continuous
    const glm::vec3 t0 = glm::normalize(glm::vec3(g.curves.derivative(i, 1.0f)));
    const glm::vec3 t1 = glm::normalize(glm::vec3(g.curves.derivative(i + 1, 0.0f)));
    ASSERT_GT(glm::dot(t0, t1), 1.0f - 1e-5f);
    // Curvature is continuous too (C2 splines); the Hermite data are floats, and the second
    // derivative of a short segment amplifies their rounding, so the tolerance includes it.
    const double k0 = curvature(g.curves, i, 1.0f), k1 = curvature(g.curves, i + 1, 0.0f);
    const double speed = glm::length(glm::vec3(g.curves.derivative(i + 1, 0.0f)));
    const double rounding = 64.0 * 1.2e-7 * glm::length(glm::vec3(start)) / (speed * speed);
    ASSERT_NEAR(k0, k1, 1e-3 * (1.0 + k0) + rounding) << "segment " << i;
    EXPECT_EQ(g.curves.segments[i].arc1, g.curves.segments[i + 1].arc0);
    ++joints;
  }
  EXPECT_GT(joints, 5000);
}

TEST(TreeGeometry, TrunkIsADisplacedGridWithFlareAndLobes) {
  const Skeleton sk = grow_species("quaking_aspen");  // Flare 0.6, 5 lobes of depth 0.07
  const TreeGeometry g = build_tree_geometry(sk);
  ASSERT_EQ(g.grids.grids.size(), 1u);
  const DisplacedGrid& d = g.grids.grids[0];
  const double r0 = sk.stems[0].base_radius;
  double lo = 1e9, hi = 0.0;
  for (std::uint32_t j = 0; j + 1 < d.width; ++j) {
    const glm::vec3 v = g.grids.vertices[d.first_vertex + j];
    const double r = std::hypot(v.x, v.y);
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  const double flare = wp::flare_scale(0.6, 0.0);
  EXPECT_NEAR(hi, r0 * flare * 1.07, 1e-3 * r0);
  EXPECT_NEAR(lo, r0 * flare * 0.93, 1e-3 * r0);
  // The seam column repeats the first one.
  for (std::uint32_t i = 0; i < d.height; i += 50) {
    const std::size_t row = d.first_vertex + static_cast<std::size_t>(i) * d.width;
    EXPECT_LT(glm::length(g.grids.vertices[row] - g.grids.vertices[row + d.width - 1]), 1e-5f);
  }
  // Shading normals point outward.
  for (std::size_t v = d.first_vertex; v < d.first_vertex + 2000; ++v) {
    const glm::vec3 radial = glm::vec3(g.grids.vertices[v].x, g.grids.vertices[v].y, 0.0f);
    EXPECT_GT(glm::dot(g.grids.normals[v], glm::normalize(radial)), 0.3f);
  }
  EXPECT_EQ(g.stats.grid_triangles, 2u * (d.width - 1u) * (d.height - 1u));
  // Without flare or lobes the trunk is a curve like every other limb.
  Skeleton plain = sk;
  plain.trunk = {};
  EXPECT_TRUE(build_tree_geometry(plain).grids.grids.empty());
}

TEST(TreeGeometry, BarkCoordinatesAreContinuousAlongALimb) {
  const TreeGeometry g = build_tree_geometry(grow_species("black_tupelo"));
  int checked = 0;
  for (std::size_t i = 0; i + 1 < g.curves.size() && checked < 500; ++i) {
    if (g.curves.segments[i].limb != g.curves.segments[i + 1].limb) continue;
    const glm::vec4 p = g.curves.position(i, 1.0f);
    const glm::vec3 t = glm::normalize(glm::vec3(g.curves.derivative(i, 1.0f)));
    const glm::vec3 n = g.curves.segments[i].normal1;
    const glm::vec3 b = glm::cross(t, n);
    const float angle = 2.0f;  // radians round from the frame normal
    const glm::vec3 surface = glm::vec3(p) + (n * std::cos(angle) + b * std::sin(angle)) * p.w;
    const BarkCoordinates end = curve_bark(g.curves, i, 1.0f, surface);
    const BarkCoordinates start = curve_bark(g.curves, i + 1, 0.0f, surface);
    ASSERT_NEAR(end.along, start.along, 1e-5f);
    ASSERT_NEAR(end.azimuth, angle, 1e-3f);
    ASSERT_NEAR(start.azimuth, angle, 1e-3f);
    ASSERT_NEAR(end.around, p.w * angle, 1e-4f);
    ++checked;
  }
  EXPECT_EQ(checked, 500);
}

TEST(TreeGeometry, GridBarkCoordinatesUseDistanceNotFraction) {
  const Skeleton sk = grow_species("quaking_aspen");
  const TreeGeometry g = build_tree_geometry(sk);
  const BarkCoordinates halfway = grid_bark(g.grids, 0, 0.5f, 0.0f);
  EXPECT_NEAR(halfway.azimuth, 3.14159265f, 1e-5f);
  EXPECT_NEAR(halfway.around, sk.stems[0].base_radius * 3.14159265f, 1e-4f);
  EXPECT_NEAR(grid_bark(g.grids, 0, 0.0f, 0.0f).along, 0.0f, 1e-6f);
  EXPECT_GT(grid_bark(g.grids, 0, 0.0f, 1.0f).along, sk.stems[0].length * 0.99f);
}

TEST(TreeGeometry, LeavesAreCardsWhoseTrianglesAreTwoSidedAndHingedLeavesFold) {
  const Skeleton sk = grow_species("quaking_aspen");
  const TreeGeometry flat_geometry = build_tree_geometry(sk);
  // One card a flat leaf, no triangles besides (the aspen has no free-form elements).
  ASSERT_EQ(flat_geometry.cards.size(), sk.leaves.size());
  ASSERT_EQ(flat_geometry.cards.corners.size(), 4 * sk.leaves.size());
  EXPECT_EQ(flat_geometry.leaves.triangle_count(), 0u);
  const LeafMesh flat = leaf_triangles(flat_geometry);
  // As triangles: the shape's triangulation, every leaf.
  std::size_t expected = 0;
  for (const Leaf& l : sk.leaves)
    expected += leaf_shapes()[static_cast<std::size_t>(l.shape)].triangles.size();
  ASSERT_EQ(flat.triangle_count(), expected);
  ASSERT_EQ(flat.triangle_count(), flat.front_material.size());
  for (std::size_t t = 0; t < flat.triangle_count(); ++t) {
    ASSERT_EQ(flat.front_material[t], kMaterialLeafFront);
    ASSERT_EQ(flat.back_material[t], kMaterialLeafBack);
  }
  // Front faces along the leaf normal, for the triangles and the card (Embree's quad normal).
  const std::uint32_t* idx = flat.indices.data();
  const glm::vec3 a = flat.positions[idx[0]], b = flat.positions[idx[1]],
                  c = flat.positions[idx[2]];
  EXPECT_GT(glm::dot(glm::cross(b - a, c - a), sk.leaves[0].normal), 0.0f);
  const glm::vec3* q = flat_geometry.cards.corners.data();
  EXPECT_GT(glm::dot(glm::cross(q[1] - q[0], q[3] - q[0]), sk.leaves[0].normal), 0.0f);
  // The triangles' vertices are where the leaf puts its outline's points.
  const Leaf& l0 = sk.leaves[0];
  const glm::vec2 tip = leaf_shapes()[static_cast<std::size_t>(l0.shape)].vertices[1];
  const glm::vec3 expect_tip = l0.position + l0.axis * (tip.y * l0.length) +
                               glm::cross(l0.axis, l0.normal) * (tip.x * l0.width);
  EXPECT_LT(glm::length(flat.positions[1] - expect_tip), 1e-5f * (1.0f + glm::length(expect_tip)));

  GeometryOptions hinged;
  hinged.leaf_style = LeafStyle::Hinged;
  hinged.hinge_angle = 30.0;
  const TreeGeometry folded_geometry = build_tree_geometry(sk, hinged);
  EXPECT_EQ(folded_geometry.cards.size(),
            3 * sk.leaves.size());  // the aspen's ovals span both hinges
  const LeafMesh folded = leaf_triangles(folded_geometry);
  EXPECT_GT(folded.triangle_count(), flat.triangle_count());
  // Folding keeps the area; the side panels rise off the leaf plane; the panels share the hinge
  // vertices (one vertex each, so a mesh's normals smooth the crease).
  auto area = [](const LeafMesh& m, std::int32_t leaf) {
    double sum = 0.0;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      if (m.leaf[t] != leaf) continue;
      const glm::dvec3 p(m.positions[m.indices[3 * t]]), q(m.positions[m.indices[3 * t + 1]]),
          r(m.positions[m.indices[3 * t + 2]]);
      sum += 0.5 * glm::length(glm::cross(q - p, r - p));
    }
    return sum;
  };
  EXPECT_NEAR(area(folded, 0), area(flat, 0), 1e-4 * area(flat, 0));
  double lift = 0.0;
  for (std::size_t t = 0; t < folded.triangle_count(); ++t) {
    if (folded.leaf[t] != 0) continue;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 v = folded.positions[folded.indices[3 * t + static_cast<size_t>(k)]];
      lift = std::max(lift, double(glm::dot(v - sk.leaves[0].position, sk.leaves[0].normal)));
    }
  }
  EXPECT_GT(lift, 0.1 * sk.leaves[0].width);
  const TreeMesh mesh = tessellate(folded_geometry, 0.01);
  EXPECT_EQ(mesh.triangle_count() - mesh.bark_triangles, folded.triangle_count());
}

TEST(LeafOutline, ContainsIsTheShapesTriangulation) {
  // Random points over each shape's box and a margin: inside the outline exactly when inside one
  // of its triangles (points within 1e-5 of an edge left out: either answer is right there).
  Rng rng(11);
  for (std::size_t s = 0; s < leaf_shape_count(); ++s) {
    const LeafShape& shape = leaf_shapes()[s];
    const LeafOutline& outline = leaf_outline(s);
    int inside = 0, checked = 0;
    for (int i = 0; i < 20000; ++i) {
      const glm::vec2 p(static_cast<float>(rng.uniform() * 1.2 - 0.6),
                        static_cast<float>(rng.uniform() * 1.2 - 0.1));
      bool in = false, near_edge = false;
      for (const auto& t : shape.triangles) {
        const glm::vec2 v[3] = {shape.vertices[t[0]], shape.vertices[t[1]], shape.vertices[t[2]]};
        bool all = true;
        for (int k = 0; k < 3; ++k) {
          const glm::vec2 e = v[(k + 1) % 3] - v[k], d = p - v[k];
          const float side = (e.x * d.y - e.y * d.x) / glm::length(e);
          if (std::fabs(side) < 1e-5f) near_edge = true;
          if (side < 0.0f) all = false;
        }
        in = in || all;
      }
      if (near_edge) continue;
      ++checked;
      inside += in ? 1 : 0;
      ASSERT_EQ(outline.contains(p), in) << shape.name << " at (" << p.x << ", " << p.y << ")";
      ASSERT_TRUE(!in || (p.x >= outline.lo.x && p.x <= outline.hi.x && p.y >= outline.lo.y &&
                          p.y <= outline.hi.y));
    }
    EXPECT_GT(checked, 19000) << shape.name;
    EXPECT_GT(inside, 2000) << shape.name;
  }
}

TEST(TreeGeometry, StatsCountWhatIsThere) {
  const TreeGeometry g = build_tree_geometry(grow_species("weeping_willow"));
  const GeometryStats& s = g.stats;
  EXPECT_EQ(s.curve_segments, g.curves.segments.size());
  EXPECT_EQ(g.curves.points.size(), 2 * s.curve_segments);
  EXPECT_EQ(s.grids, 5u);  // three trunks from BaseSplits 2, and trunk clones from 0SegSplits
  EXPECT_EQ(s.leaf_triangles, g.leaves.triangle_count());
  EXPECT_EQ(s.leaf_cards, g.cards.size());
  EXPECT_GT(s.bytes, g.curves.points.size() * sizeof(glm::vec4));
  EXPECT_LE(g.bounds_min.z, 0.0f);
  EXPECT_GT(g.bounds_max.z, 3.0f);
}

TEST(TreeGeometry, PeriodicTaperKeepsTheCurvesWithinTheLimbsRadius) {
  // Weber & Penn's nTaper in (2, 3] (the Saguaro's 2.2) swells a limb periodically; its radius
  // law has unbounded slope where the swellings meet. No curve may grow past the thickest limb.
  const Skeleton sk = grow_species("saguaro_cactus");
  const TreeGeometry g = build_tree_geometry(sk);
  float thickest = 0.0f;
  for (const SkeletonPoint& p : sk.points) thickest = std::max(thickest, p.radius);
  float widest = 0.0f;
  for (std::size_t i = 0; i < g.curves.size(); ++i) {
    for (int k = 0; k <= 32; ++k) widest = std::max(widest, g.curves.position(i, k / 32.0f).w);
  }
  EXPECT_LT(widest, 1.05f * thickest) << "thickest skeleton radius " << thickest;
}

TEST(TreeGeometry, RootButtressesWidenTheTrunksBaseAndMergeIntoIt) {
  Skeleton sk = grow_species("quaking_aspen");
  sk.trunk = {};  // no flare or lobes: only the buttresses displace the trunk
  GeometryOptions o;
  o.buttresses = 6;
  const TreeGeometry g = build_tree_geometry(sk, o);
  ASSERT_EQ(g.grids.grids.size(), 1u);
  const DisplacedGrid& d = g.grids.grids[0];
  const double r0 = sk.stems[0].base_radius;
  const glm::vec3 axis = sk.points[sk.stems[0].first_point].position;
  // Radii of ring i about the trunk's axis there (the spline; the trunk leans a little).
  auto ring = [&](std::uint32_t i) {
    const std::size_t row = d.first_vertex + static_cast<std::size_t>(i) * d.width;
    glm::dvec3 centre(0.0);
    for (std::uint32_t j = 0; j + 1 < d.width; ++j) centre += glm::dvec3(g.grids.vertices[row + j]);
    centre /= double(d.width - 1);
    if (i == 0) centre = glm::dvec3(axis);
    std::vector<double> r;
    for (std::uint32_t j = 0; j + 1 < d.width; ++j) {
      r.push_back(glm::length(glm::dvec3(g.grids.vertices[row + j]) - centre));
    }
    return r;
  };
  // At the ground: six ridges reaching well past the trunk, nowhere inside it.
  const std::vector<double> base = ring(0);
  int peaks = 0;
  for (std::size_t k = 0; k < base.size(); ++k) {
    const double prev = base[(k + base.size() - 1) % base.size()],
                 next = base[(k + 1) % base.size()];
    if (base[k] > prev && base[k] >= next && base[k] > 1.5 * r0) ++peaks;
  }
  EXPECT_EQ(peaks, 6);
  EXPECT_GT(*std::max_element(base.begin(), base.end()), 2.5 * r0);
  EXPECT_GE(*std::min_element(base.begin(), base.end()), 0.999 * r0);
  // Above 3 base radii (the default height) the trunk is round again, its own radius.
  int above = 0;
  for (std::uint32_t i = 0; i < d.height; ++i) {
    const glm::vec3 v = g.grids.vertices[d.first_vertex + static_cast<std::size_t>(i) * d.width];
    if (v.z - axis.z < 3.2 * r0 || v.z - axis.z > 6.0 * r0) continue;
    const std::vector<double> r = ring(i);
    const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
    EXPECT_LT(*hi - *lo, 1e-4 * r0) << "ring " << i;
    ++above;
  }
  EXPECT_GT(above, 3);
  // On the aspen's own flared, lobed trunk: every vertex at least as far out as without
  // buttresses (the same rings: ring spacing does not depend on them), and the same above.
  const Skeleton lobed = grow_species("quaking_aspen");
  GeometryOptions sides;
  sides.grid_sides = 192;
  const TreeGeometry plain = build_tree_geometry(lobed, sides);
  sides.buttresses = 6;
  const TreeGeometry rooted = build_tree_geometry(lobed, sides);
  const DisplacedGrid& pd = plain.grids.grids.at(0);
  ASSERT_EQ(rooted.grids.grids.at(0).height, pd.height);
  int widened = 0;
  for (std::uint32_t i = 0; i < pd.height; ++i) {
    const std::size_t row = pd.first_vertex + static_cast<std::size_t>(i) * pd.width;
    glm::dvec3 centre(0.0);
    for (std::uint32_t j = 0; j + 1 < pd.width; ++j)
      centre += glm::dvec3(plain.grids.vertices[row + j]);
    centre /= double(pd.width - 1);
    for (std::uint32_t j = 0; j + 1 < pd.width; ++j) {
      const double without = glm::length(glm::dvec3(plain.grids.vertices[row + j]) - centre);
      const double with = glm::length(glm::dvec3(rooted.grids.vertices[row + j]) - centre);
      ASSERT_GE(with, without * (1.0 - 1e-6)) << "ring " << i << " side " << j;
      if (plain.grids.vertices[row + j].z - axis.z > 3.2 * r0) {
        ASSERT_NEAR(with, without, 1e-6 * without);
      }
      widened += with > 1.01 * without ? 1 : 0;
    }
  }
  EXPECT_GT(widened, 1000);
  // Shading normals face outward at the base.
  for (std::uint32_t j = 0; j + 1 < d.width; ++j) {
    const glm::vec3 v = g.grids.vertices[d.first_vertex + j];
    EXPECT_GT(
        glm::dot(g.grids.normals[d.first_vertex + j], glm::vec3(v.x - axis.x, v.y - axis.y, 0.0f)),
        0.0f)
        << j;
  }
}

// `grow --stats` counts the geometry without building it (issue 31): every count equals the
// build's, over curvature-limited pieces, periodic taper (the saguaro), a displaced lobed trunk
// (the aspen, the willow), hinged leaves, TREE-MAKER leaf lines (the dogwood) and the ramiform's
// collars (issue 45). Power: counting a grid's triangles over its rings rather than the gaps
// between them fails it on the displaced trunks; counting collars without the disks' soundness
// check (every tried fork kept) fails it on the ramiform aspen.
TEST(TreeGeometry, CountingWithoutBuildingGivesTheBuildsCounts) {
  for (const char* file :
       {"quaking_aspen.toml", "weeping_willow.toml", "saguaro_cactus.toml", "dogwood.tmpl",
        "lsystem_bush.lsys", "young_pine.tmpl", "quaking_aspen_ramiform.toml"}) {
    const Species species =
        formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/" + file);
    GrowOptions o;
    o.seed = 4;
    o.quality = 0.2;
    const Skeleton sk = grow_tree(species, o);
    const GeometryOptions options = geometry_options_for(species);
    const GeometryStats built = build_tree_geometry(sk, options).stats;
    const GeometryStats counted = count_tree_geometry(sk, options);
    EXPECT_TRUE(built.built);
    EXPECT_FALSE(counted.built);
    EXPECT_GT(counted.curve_segments, 0u) << file;
    EXPECT_EQ(counted.limbs, built.limbs) << file;
    EXPECT_EQ(counted.curve_segments, built.curve_segments) << file;
    EXPECT_EQ(counted.tension_raised_limbs, built.tension_raised_limbs) << file;
    EXPECT_EQ(counted.grids, built.grids) << file;
    EXPECT_EQ(counted.grid_vertices, built.grid_vertices) << file;
    EXPECT_EQ(counted.grid_triangles, built.grid_triangles) << file;
    EXPECT_EQ(counted.leaf_cards, built.leaf_cards) << file;
    EXPECT_EQ(counted.leaf_triangles, built.leaf_triangles) << file;
    EXPECT_EQ(counted.ramiform_forks, built.ramiform_forks) << file;
    EXPECT_EQ(counted.ramiforms, built.ramiforms) << file;
    EXPECT_EQ(counted.ramiform_triangles, built.ramiform_triangles) << file;
    EXPECT_EQ(counted.ramiforms_skipped, built.ramiforms_skipped) << file;
    EXPECT_EQ(counted.ramiform_trunk_forks, built.ramiform_trunk_forks) << file;
    EXPECT_EQ(counted.ramiform_trunk_collars, built.ramiform_trunk_collars) << file;
    EXPECT_EQ(built.ramiforms > 0, species.bark.ramiform) << file;
  }
}

// The located variants give locate's segment and u, and the values computed from them are the
// same bits as from the parameter (a segment hint that is wrong falls back to the search). Power:
// taking the hint for t equal to its segment's end knot (<= for <) fails it.
TEST(TreeGeometry, LocatingFromASegmentAgreesWithTheSearch) {
  const Skeleton sk = grow_species("black_tupelo", 3);
  const std::vector<Limb> limbs = fit_limbs(sk);
  Rng rng(11);
  int checked = 0;
  for (const Limb& limb : limbs) {
    const CubicSpline& s = limb.spline;
    const double total = s.params.back();
    for (int k = 0; k < 8; ++k) {
      // Inside, at knots, beyond the ends.
      const double t = k < 2 ? s.params[static_cast<size_t>(k) % s.params.size()]
                             : (rng.uniform() * 1.2 - 0.1) * total;
      double u0 = 0.0;
      const std::size_t i0 = s.locate(t, u0);
      for (std::size_t hint = 0; hint < s.segment_count(); ++hint) {
        double u1 = -1.0;
        ASSERT_EQ(s.locate_from(hint, t, u1), i0) << "t " << t << " hint " << hint;
        ASSERT_EQ(u1, u0);
      }
      EXPECT_EQ(limb.radius_in(sk, i0, u0), limb.radius_at(sk, t));
      EXPECT_EQ(s.curvature_in(i0, u0), s.curvature(t));
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

}  // namespace arbor::generator
