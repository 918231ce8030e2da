// Tests of the shaped leaf (issue 45): its bend keeps the blade's size, its panels meet without
// gaps, its shading normals are continuous across them, and its stalk reaches the blade.
#include "generator/geometry/leaf_cards.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "formats/species_file.h"
#include "generator/geometry/geometry_plan.h"
#include "generator/geometry/leaf_bend.h"
#include "generator/grow.h"

namespace arbor::generator {

namespace {

const LeafBend kAspen = LeafBend::from_degrees(12.0, 18.0, 20.0, 10.0);

Skeleton one_leaf(int shape) {
  Skeleton sk;
  Leaf leaf;
  leaf.position = {1.0f, 2.0f, 3.0f};
  leaf.axis = glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f));
  leaf.normal = glm::normalize(glm::cross(leaf.axis, glm::vec3(1.0f, 0.0f, 0.0f)));
  leaf.length = 0.08f;
  leaf.width = 0.07f;
  leaf.shape = shape;
  sk.leaves.push_back(leaf);
  return sk;
}

GeometryOptions shaped(const LeafBend& bend) {
  GeometryOptions o;
  o.leaf_style = LeafStyle::Shaped;
  o.leaf_bend = bend;
  return o;
}

// The area of a card's two Embree triangles (0, 1, 3) and (2, 3, 1).
double card_area(const glm::vec3* q) {
  return 0.5 * (glm::length(glm::cross(q[1] - q[0], q[3] - q[0])) +
                glm::length(glm::cross(q[3] - q[2], q[1] - q[2])));
}

}  // namespace

// The bend does not stretch the blade: across, the cross-section's arc from the midrib to the
// margin keeps its length; along, the midrib keeps its length; the normal is unit and faces the
// leaf's front. Power: a cup arc of curvature cup / w (not cup / (w/2)) or a curl of curl / l²
// fails the lengths.
TEST(LeafBend, KeepsTheBladesLengthsAndFacesFront) {
  const float w = 0.07f, l = 0.08f;
  for (const LeafBend& b : {kAspen, LeafBend::from_degrees(40.0, -30.0, 90.0, 60.0)}) {
    double across = 0.0, along = 0.0;
    const int n = 400;
    for (int k = 0; k < n; ++k) {
      across +=
          glm::length(b.place(0.5f * (k + 1) / n, 0.5f, w, l) - b.place(0.5f * k / n, 0.5f, w, l));
      along += glm::length(b.place(0.0f, (k + 1.0f) / n, w, l) - b.place(0.0f, k * 1.0f / n, w, l));
    }
    EXPECT_NEAR(across, 0.5 * w, 1e-3 * w);
    EXPECT_NEAR(along, l, 1e-3 * l);
    // The normal is perpendicular to the surface's tangents there, on the front's side.
    for (float x : {-0.5f, -0.2f, 0.3f, 0.5f}) {
      for (float y : {0.01f, 0.4f, 0.99f}) {
        const glm::vec3 nrm = b.normal(x, y, w, l);
        const float e = 1e-3f;
        const glm::vec3 tx = glm::normalize(b.place(x + e, y, w, l) - b.place(x - e, y, w, l));
        const glm::vec3 ty = glm::normalize(b.place(x, y + e, w, l) - b.place(x, y - e, w, l));
        EXPECT_NEAR(glm::length(nrm), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(nrm, tx), 0.0f, 2e-3f) << x << " " << y;
        EXPECT_NEAR(glm::dot(nrm, ty), 0.0f, 2e-3f) << x << " " << y;
        EXPECT_GT(glm::dot(nrm, glm::normalize(glm::cross(tx, ty))), 0.999f) << x << " " << y;
      }
    }
    // At the midrib, the mean of the halves' normals; for the aspen's mild bend, nearly up.
    EXPECT_GT(kAspen.normal(0.0f, 0.5f, w, l).z, 0.9f);
  }
  // Flat: the flat card's placement exactly.
  const LeafBend flat;
  EXPECT_TRUE(flat.flat());
  EXPECT_EQ(flat.place(0.25f, 0.5f, w, l), glm::vec3(0.25f * w, 0.5f * l, 0.0f));
}

// A shaped leaf's panels meet without gaps (every corner a neighbour shares is the same point,
// bit for bit) and shade continuously (the same normal there); their area is the flat card's
// within 3 %. Power: cutting the columns at x = lo.x · k / n for the right half too (a gap at the
// midrib) or giving corners the face normal fails it.
TEST(LeafCards, PanelsMeetWithoutGapsAndShadeContinuously) {
  for (int shape = 0; shape < static_cast<int>(leaf_shape_count()); ++shape) {
    const Skeleton sk = one_leaf(shape);
    TreeGeometry flat, bent;
    add_leaf_cards(sk, GeometryOptions{}, flat);
    add_leaf_cards(sk, shaped(kAspen), bent);
    const LeafPanels panels =
        leaf_panels(leaf_outline(static_cast<std::size_t>(shape)), shaped(kAspen));
    ASSERT_EQ(bent.cards.size(), panels.cards());
    ASSERT_EQ(bent.cards.normals.size(), bent.cards.corners.size());
    EXPECT_GE(bent.cards.size(), 2u);
    EXPECT_TRUE(flat.cards.normals.empty());
    // Corners by their leaf point: every occurrence the same position and normal.
    std::map<std::tuple<float, float>, std::pair<glm::vec3, glm::vec3>> seen;
    std::size_t shared = 0;
    double area = 0.0;
    for (std::size_t i = 0; i < bent.cards.size(); ++i) {
      const LeafCard& c = bent.cards.cards[i];
      const float xs[4] = {c.x0, c.x1, c.x1, c.x0}, ys[4] = {c.y0, c.y0, c.y1, c.y1};
      for (int k = 0; k < 4; ++k) {
        const glm::vec3 p = bent.cards.corners[4 * i + k], n = bent.cards.normals[4 * i + k];
        const auto [it, fresh] = seen.try_emplace({xs[k], ys[k]}, p, n);
        if (!fresh) {
          ++shared;
          EXPECT_EQ(it->second.first, p) << shape;
          EXPECT_EQ(it->second.second, n) << shape;
        }
      }
      area += card_area(&bent.cards.corners[4 * i]);
    }
    EXPECT_GT(shared, 0u);
    EXPECT_NEAR(area, card_area(flat.cards.corners.data()), 0.03 * area) << shape;
  }
}

// The petiole: a curve of the leaf's material from the leaf's point on its stem to the blade's
// base, which moves out by its length; thinned with its leaf (its item the leaf's index); counted
// as the build makes it. Power: leaving the blade where it was (the stalk through the blade)
// fails the base.
TEST(LeafCards, ThePetioleReachesTheBlade) {
  const Skeleton sk = one_leaf(0);
  GeometryOptions o = shaped(kAspen);
  o.petiole_length = 0.8;
  o.petiole_width = 0.04;
  TreeGeometry g;
  add_leaf_cards(sk, o, g);
  ASSERT_EQ(g.curves.size(), 1u);
  EXPECT_EQ(petiole_segments(sk, o), 1u);
  const Leaf& leaf = sk.leaves[0];
  const glm::vec3 base = leaf.position + leaf.axis * (0.8f * leaf.length);
  EXPECT_EQ(glm::vec3(g.curves.points[0]), leaf.position);
  EXPECT_LT(glm::length(glm::vec3(g.curves.points[1]) - base), 1e-6f);
  EXPECT_NEAR(g.curves.points[0].w, 0.5f * 0.04f * leaf.width, 1e-7f);
  EXPECT_EQ(g.curves.segments[0].material, kMaterialLeafFront);
  EXPECT_EQ(g.curves.segments[0].lod_level, 3);
  EXPECT_EQ(g.curves.segments[0].lod_item, 0u);
  // The blade's midrib at its base (x = 0, y = lo.y) starts at the stalk's end.
  const LeafCard& c = g.cards.cards[0];
  const glm::vec3 across = glm::cross(leaf.axis, leaf.normal);
  const glm::vec3 p = kAspen.place(0.0f, c.y0, leaf.width, leaf.length);
  const glm::vec3 start = base + across * p.x + leaf.axis * p.y + leaf.normal * p.z;
  bool found = false;
  for (std::size_t i = 0; i < g.cards.corners.size(); ++i)
    found = found || glm::length(g.cards.corners[i] - start) < 1e-6f;
  EXPECT_TRUE(found);
  o.petiole_length = 0.0;
  EXPECT_EQ(petiole_segments(sk, o), 0u);
}

// The shipped shaped aspen's leaves are shaped and stalked; its exported leaf triangles lie on the
// bent blade (each vertex within 5 % of the leaf's size of its leaf point's place on the bend: the
// panels' sag) and keep the flat blade's area within 2 %; the petioles are counted as built.
// Power: looking a vertex's panel up by x alone (ignoring the rows) moves the upper rows' vertices
// off the blade by centimetres.
TEST(LeafCards, TheAspensExportedLeavesLieOnTheBentBlade) {
  const Species s =
      formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen_shaped.toml");
  GrowOptions grow;
  grow.seed = 2;
  grow.quality = 0.05;
  const Skeleton sk = grow_tree(s, grow);
  const GeometryOptions o = geometry_options_for(s);
  EXPECT_EQ(o.leaf_style, LeafStyle::Shaped);
  EXPECT_GT(o.petiole_length, 0.0);
  const TreeGeometry g = build_tree_geometry(sk, o);
  const LeafMesh m = leaf_triangles(g);
  double worst = 0.0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    if (m.leaf[t] < 0) continue;
    const Leaf& leaf = sk.leaves[static_cast<std::size_t>(m.leaf[t])];
    const glm::vec3 across = glm::cross(leaf.axis, leaf.normal);
    const glm::vec3 base =
        leaf.position + leaf.axis * (static_cast<float>(o.petiole_length) * leaf.length);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = m.indices[3 * t + k];
      const glm::vec3 p = o.leaf_bend.place(m.uvs[v].x - 0.5f, m.uvs[v].y, leaf.width, leaf.length);
      const glm::vec3 expected = base + across * p.x + leaf.axis * p.y + leaf.normal * p.z;
      worst = std::max(worst, static_cast<double>(glm::length(m.positions[v] - expected) /
                                                  std::max(leaf.width, leaf.length)));
    }
  }
  EXPECT_LT(worst, 0.05);
  double mesh_area = 0.0, card_total = 0.0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                    c = m.positions[m.indices[3 * t + 2]];
    mesh_area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  GeometryOptions flat = o;
  flat.leaf_style = LeafStyle::Flat;
  flat.leaf_bend = LeafBend{};
  const LeafMesh f = leaf_triangles(build_tree_geometry(sk, flat));
  for (std::size_t t = 0; t < f.triangle_count(); ++t) {
    const glm::vec3 a = f.positions[f.indices[3 * t]], b = f.positions[f.indices[3 * t + 1]],
                    c = f.positions[f.indices[3 * t + 2]];
    card_total += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  ASSERT_GT(card_total, 0.0);
  EXPECT_NEAR(mesh_area / card_total, 1.0, 0.02);
  EXPECT_EQ(g.stats.curve_segments, count_tree_geometry(sk, o).curve_segments);
}

}  // namespace arbor::generator
