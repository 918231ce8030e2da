// Tracer-side tests of tree geometry in Embree, through the world's instanced intersection (as the
// integrators see it): rays find the trunk's lobes and flare, curves are hit at their radius with
// radial normals and bark coordinates, leaves report their side, and rays leaving a placed tree
// (translated, rotated, scaled) do not hit it again.
#include "tracer/embree/world.h"
#include "test_world.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "generator/species.h"
#include "common/rng.h"
#include "generator/models/weber_penn/weber_penn.h"
#include "scene/scene.h"
#include "tracer/integrators/path.h"
#include "formats/species_file.h"
#include "common/math.h"

namespace arbor::tracer {

namespace {

// Centre of the trunk grid's ring nearest height z (lobes cancel in the mean of a full ring).
glm::vec2 ring_centre(const generator::TreeGeometry& g, float z) {
  const generator::DisplacedGrid& d = g.grids.grids[0];
  std::size_t best = 0;
  for (std::size_t j = 0; j < d.height; ++j) {
    if (std::fabs(g.grids.vertices[d.first_vertex + j * d.width].z - z) <
        std::fabs(g.grids.vertices[d.first_vertex + best * d.width].z - z)) {
      best = j;
    }
  }
  glm::vec2 c(0.0f);
  for (std::size_t i = 0; i + 1 < d.width; ++i) {
    c += glm::vec2(g.grids.vertices[d.first_vertex + best * d.width + i]) / float(d.width - 1);
  }
  return c;
}

// Radii of the trunk at height z seen by `n` horizontal rays aimed at the axis from all round.
std::vector<double> radii_at(const GeometryWorld& tree, glm::vec2 axis, float z, int n) {
  std::vector<glm::vec3> hits;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * kPi * k / n;
    const glm::vec3 dir(-std::cos(a), -std::sin(a), 0.0f);
    Ray ray;
    ray.origin = glm::vec3(axis.x, axis.y, z) - dir * 5.0f;
    ray.direction = dir;
    SurfaceHit hit;
    EXPECT_TRUE(tree.intersect(ray, hit)) << "ray " << k << " at z " << z;
    EXPECT_EQ(hit.kind, SurfaceKind::Grid);
    hits.push_back(hit.position);
  }
  std::vector<double> r;
  for (const glm::vec3& h : hits) r.push_back(std::hypot(h.x - axis.x, h.y - axis.y));
  return r;
}

int count_peaks(const std::vector<double>& r) {
  int peaks = 0;
  const std::size_t n = r.size();
  for (std::size_t k = 0; k < n; ++k) {
    if (r[k] > r[(k + n - 1) % n] && r[k] >= r[(k + 1) % n]) ++peaks;
  }
  return peaks;
}

// One straight stem along z: 3 m long, radius 0.1 (cylinder), no flare or lobes.
generator::Skeleton straight_stem() {
  generator::Skeleton sk;
  for (int i = 0; i <= 3; ++i) sk.points.push_back({glm::vec3(0.0f, 0.0f, float(i)), 0.1f});
  generator::Stem s;
  s.point_count = 4;
  s.length = 3.0f;
  s.base_radius = 0.1f;
  s.taper = 0.0f;
  sk.stems.push_back(s);
  return sk;
}

}  // namespace

TEST(TreePrototype, RaysFindTheTrunkLobesAndFlare) {
  const generator::Species aspen =
      formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml");
  generator::GrowOptions o;
  o.quality = 0.1;
  generator::WeberPennParams calm = aspen.weber_penn();
  calm.wind_speed = calm.wind_gust = 0.0;  // a straight trunk: its rings are horizontal
  const generator::Skeleton sk = generator::grow_weber_penn(calm, o);
  const generator::TreeGeometry g = generator::build_tree_geometry(sk);
  EmbreeDevice device("threads=1");
  const GeometryWorld tree(g, device);
  const float r0 = sk.stems[0].base_radius;
  double mean_low = 0.0, mean_high = 0.0;
  for (float z : {1.0f, 2.0f, 3.0f}) {
    const std::vector<double> r = radii_at(tree, ring_centre(g, z), z, 360);
    EXPECT_EQ(count_peaks(r), 5) << "z " << z;  // Lobes = 5
    const double hi = *std::max_element(r.begin(), r.end());
    const double lo = *std::min_element(r.begin(), r.end());
    EXPECT_NEAR(hi / lo, 1.07 / 0.93, 0.02) << "z " << z;  // LobeDepth = 0.07
    if (z == 3.0f)
      for (double v : r) mean_high += v / r.size();
  }
  for (double v : radii_at(tree, ring_centre(g, 0.02f), 0.02f, 360)) mean_low += v / 360.0;
  // Flare 0.6 near the ground: 1 + 0.6 (100^(1 - 8z) - 1) / 100 at z = 0.02 / 12 m.
  EXPECT_GT(mean_low / mean_high, 1.4);
  EXPECT_GT(mean_low, r0 * 1.4);
}

TEST(TreePrototype, CurvesAreHitAtTheirRadiusWithBarkCoordinates) {
  const generator::Skeleton sk = straight_stem();
  const generator::TreeGeometry g = generator::build_tree_geometry(sk);
  ASSERT_TRUE(g.grids.grids.empty());
  EmbreeDevice device("threads=1");
  const GeometryWorld tree(g, device);
  const glm::vec3 frame_normal = g.curves.segments[0].normal0;
  const glm::vec3 frame_binormal = glm::cross(glm::vec3(0, 0, 1), frame_normal);
  for (float z : {0.3f, 1.5f, 2.7f}) {
    for (float angle : {0.5f, 2.0f, 4.0f}) {
      const glm::vec3 out = frame_normal * std::cos(angle) + frame_binormal * std::sin(angle);
      Ray ray;
      ray.origin = glm::vec3(0, 0, z) + out * 2.0f;
      ray.direction = -out;
      SurfaceHit hit;
      ASSERT_TRUE(tree.intersect(ray, hit));
      EXPECT_EQ(hit.kind, SurfaceKind::Curve);
      EXPECT_NEAR(hit.t, 1.9f, 1e-3f);                         // radius 0.1
      EXPECT_GT(glm::dot(hit.geometric_normal, out), 0.999f);  // radial, facing the ray
      EXPECT_NEAR(hit.bark.along, z, 1e-3f);                   // arc length from the base
      EXPECT_NEAR(hit.bark.azimuth, angle, 1e-2f);
      EXPECT_NEAR(hit.bark.around, 0.1f * angle, 1e-3f);  // radius × azimuth
      EXPECT_EQ(hit.material, generator::kMaterialBark);
    }
  }
}

TEST(TreePrototype, LeavesReportTheSideTheRayCameFrom) {
  generator::Skeleton sk = straight_stem();
  generator::Leaf leaf;
  leaf.position = glm::vec3(1.0f, 0.0f, 1.0f);
  leaf.axis = glm::vec3(1.0f, 0.0f, 0.0f);
  leaf.normal = glm::vec3(0.0f, 0.0f, 1.0f);
  leaf.length = 0.2f;
  leaf.width = 0.1f;
  leaf.stem = 0;
  sk.leaves.push_back(leaf);
  const generator::TreeGeometry g = generator::build_tree_geometry(sk);
  EmbreeDevice device("threads=1");
  const GeometryWorld tree(g, device);
  SurfaceHit hit;
  Ray down;
  down.origin = glm::vec3(1.1f, 0.0f, 2.0f);
  down.direction = glm::vec3(0, 0, -1);
  ASSERT_TRUE(tree.intersect(down, hit));
  EXPECT_EQ(hit.kind, SurfaceKind::Leaf);
  EXPECT_EQ(hit.material, generator::kMaterialLeafFront);
  EXPECT_NEAR(hit.geometric_normal.z, 1.0f, 1e-5f);
  EXPECT_NEAR(hit.t, 1.0f, 1e-5f);
  Ray up = down;
  up.origin.z = 0.0f;
  up.direction = glm::vec3(0, 0, 1);
  ASSERT_TRUE(tree.intersect(up, hit));
  EXPECT_EQ(hit.material, generator::kMaterialLeafBack);
  EXPECT_NEAR(hit.geometric_normal.z, -1.0f, 1e-5f);
  Ray miss = down;
  miss.origin.x = 1.5f;  // past the leaf's tip
  EXPECT_FALSE(tree.intersect(miss, hit));
  // The leaf is a card with its oval cut out: at the centre uv is (0.5, 0.5); by a corner of the
  // card, outside the oval (leaf point (0.45, 0.05)), rays pass, closest-hit and shadow alike.
  ASSERT_TRUE(tree.intersect(down, hit));
  EXPECT_NEAR(hit.uv.x, 0.5f, 1e-5f);
  EXPECT_NEAR(hit.uv.y, 0.5f, 1e-5f);
  Ray corner = down;
  corner.origin = glm::vec3(1.0f + 0.05f * 0.2f, -0.45f * 0.1f, 2.0f);
  EXPECT_FALSE(tree.intersect(corner, hit));
  EXPECT_FALSE(tree.world().occluded(corner));
  EXPECT_TRUE(tree.world().occluded(down));
  Ray edge = corner;  // leaf point (0.25, 0.15): inside the oval
  edge.origin = glm::vec3(1.0f + 0.15f * 0.2f, -0.25f * 0.1f, 2.0f);
  EXPECT_TRUE(tree.intersect(edge, hit));
  EXPECT_TRUE(tree.world().occluded(edge));
}

TEST(TreePrototype, RaysLeavingLimbsAndLeavesDoNotHitThemAgain) {
  // Shadow acne check on the thinnest geometry: a whole Black Tupelo (twigs of a few mm), rays
  // from all round; from every hit a ray leaves into the hemisphere it came from (and through
  // leaves, behind them) with the integrator's offset rule. None may hit the same primitive at
  // once. Once with the tree where it grew, once placed as a forest places trees (moved far from
  // the origin, turned, scaled), where the hit is carried back from the instance's space.
  const generator::Species tupelo =
      formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/black_tupelo.toml");
  generator::GrowOptions o;
  o.quality = 0.3;
  const generator::TreeGeometry g =
      generator::build_tree_geometry(generator::grow_weber_penn(tupelo.weber_penn(), o));
  EmbreeDevice device("threads=1");
  spec::Placement placed;
  placed.position = {180.0, -140.0, 0.5};
  placed.rotation = 37.0;
  placed.scale = 1.3;
  for (const spec::Placement& placement : {spec::Placement{}, placed}) {
    const GeometryWorld tree(g, device, placement);
    const glm::mat4 m = scene::placement_matrix(placement);
    auto world = [&](const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); };
    Rng rng(5);
    int hits = 0, curve_hits = 0, acne = 0;
    for (int i = 0; i < 20000; ++i) {
      const double a = 2 * kPi * rng.uniform(), z = 4.0 + 16.0 * rng.uniform();
      Ray ray;
      ray.origin = world(glm::vec3(30.0 * std::cos(a), 30.0 * std::sin(a), z));
      const glm::vec3 target = world(
          glm::vec3(4.0 * rng.symmetric(), 4.0 * rng.symmetric(), 4.0 + 16.0 * rng.uniform()));
      ray.direction = glm::normalize(target - ray.origin);
      SurfaceHit hit;
      if (!tree.intersect(ray, hit)) continue;
      ++hits;
      curve_hits += hit.kind == SurfaceKind::Curve ? 1 : 0;
      // A random direction on the side the ray came from (and, for leaves, also behind).
      glm::vec3 d(rng.symmetric(), rng.symmetric(), rng.symmetric());
      d = glm::normalize(d);
      if (glm::dot(d, hit.geometric_normal) < 0.0f && hit.kind != SurfaceKind::Leaf) d = -d;
      const Ray out = spawn_ray(hit.position, hit.geometric_normal, d);
      SurfaceHit again;
      if (tree.intersect(out, again) && again.kind == hit.kind &&
          again.primitive == hit.primitive && again.t < 1e-3f) {
        ++acne;
      }
    }
    EXPECT_GT(hits, 5000) << "scale " << placement.scale;
    EXPECT_GT(curve_hits, 500) << "scale " << placement.scale;
    EXPECT_EQ(acne, 0) << "of " << hits << " hits, scale " << placement.scale;
  }
}

}  // namespace arbor::tracer
