// Leaf cards and their triangles (leaf_cards.h): flat, hinged (Bloomenthal §10) or shaped
// (leaf_bend.h), and the leaves' petioles.
#include "generator/geometry/leaf_cards.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/math.h"
#include "generator/geometry/leaf_bend.h"

namespace arbor::generator {

namespace {

// A leaf outline in 3D leaf space (x across, y along, h lifted along the normal), flat or
// folded along two hinges (Bloomenthal's three-polygon leaf, §10).
struct LeafTemplate {
  std::vector<glm::vec3> vertices;  // (x, y, h)
  std::vector<glm::vec2> uvs;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// Splits triangles by the line x = c (axis 0) or y = c (axis 1) so that no triangle straddles it.
void split_at(LeafTemplate& t, float c, int axis = 0) {
  std::vector<std::array<std::uint32_t, 3>> out;
  auto add_vertex = [&](const glm::vec3& p) {
    t.vertices.push_back(p);
    t.uvs.emplace_back(p.x + 0.5f, p.y);
    return static_cast<std::uint32_t>(t.vertices.size() - 1);
  };
  for (const auto& tri : t.triangles) {
    std::vector<std::uint32_t> left, right;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[static_cast<size_t>(k)],
                          b = tri[static_cast<size_t>((k + 1) % 3)];
      const glm::vec3 pa = t.vertices[a], pb = t.vertices[b];
      const float ca = pa[axis], cb = pb[axis];
      // A vertex on the line belongs to both sides (the midrib's vertices, at x = 0).
      if (ca <= c) left.push_back(a);
      if (ca >= c) right.push_back(a);
      if ((ca < c && cb > c) || (ca > c && cb < c)) {
        const float f = (c - ca) / (cb - ca);
        const std::uint32_t m = add_vertex(pa + (pb - pa) * f);
        left.push_back(m);
        right.push_back(m);
      }
    }
    for (const auto* poly : {&left, &right}) {
      for (std::size_t k = 1; k + 1 < poly->size(); ++k) {
        out.push_back({(*poly)[0], (*poly)[k], (*poly)[k + 1]});
      }
    }
  }
  t.triangles = std::move(out);
}

// The shape's outline in flat leaf space, split at the given x (the hinges) and y so that no
// triangle straddles a panel boundary.
LeafTemplate leaf_template(const LeafShape& shape, const std::vector<float>& splits,
                           const std::vector<float>& rows = {}) {
  LeafTemplate t;
  for (const glm::vec2& v : shape.vertices) {
    t.vertices.emplace_back(v.x, v.y, 0.0f);
    t.uvs.emplace_back(v.x + 0.5f, v.y);
  }
  t.triangles = shape.triangles;
  for (float x : splits) split_at(t, x);
  for (float y : rows) split_at(t, y, 1);
  return t;
}

// The petiole's radius: half its width (a fraction of the blade's), at least 0.2 mm.
float petiole_radius(const Leaf& leaf, const GeometryOptions& o) {
  return std::max(2e-4f, 0.5f * static_cast<float>(o.petiole_width) * leaf.width);
}

// A petiole long enough to draw: more than its own diameter.
bool drawn_petiole(const Leaf& leaf, const GeometryOptions& o) {
  return o.petiole_length > 0.0 &&
         static_cast<float>(o.petiole_length) * leaf.length > 2.0f * petiole_radius(leaf, o);
}

// The petiole: a straight round curve from the leaf's point on its stem to the blade's base, of
// the leaf's material (a green stalk: the tracer shades a curve of kMaterialLeafFront as its
// leaf), thinned with its leaf at range (its level of detail item is the leaf's index).
void add_petiole(const Leaf& leaf, std::int32_t index, const GeometryOptions& o, CurveSet& c) {
  const float r = petiole_radius(leaf, o);
  const glm::vec3 d = leaf.axis * (static_cast<float>(o.petiole_length) * leaf.length);
  c.points.emplace_back(leaf.position, r);
  c.points.emplace_back(leaf.position + d, r);
  c.tangents.emplace_back(d, 0.0f);
  c.tangents.emplace_back(d, 0.0f);
  CurveSegment seg;
  seg.limb = -1;
  seg.lod_level = 3;  // scene::kLodLeaves
  seg.lod_item = static_cast<std::uint32_t>(index);
  seg.arc1 = glm::length(d);
  seg.normal0 = seg.normal1 = leaf.normal;
  seg.material = kMaterialLeafFront;
  c.segments.push_back(seg);
}

}  // namespace

LeafPanels leaf_panels(const LeafOutline& outline, const GeometryOptions& o) {
  LeafPanels p;
  p.xs.push_back(outline.lo.x);
  if (o.leaf_style == LeafStyle::Hinged) {
    const float hinge = static_cast<float>(o.hinge_position);
    for (float x : {-hinge, hinge}) {
      if (x > outline.lo.x && x < outline.hi.x) p.xs.push_back(x);
    }
  } else if (o.leaf_style == LeafStyle::Shaped) {
    // Each half in equal columns from the midrib out, the midrib always a cut (the fold).
    const int n = o.leaf_bend.columns_per_half();
    for (int k = n - 1; k >= 1; --k) {
      const float x = outline.lo.x * static_cast<float>(k) / static_cast<float>(n);
      if (x > outline.lo.x) p.xs.push_back(x);
    }
    if (outline.lo.x < 0.0f && outline.hi.x > 0.0f) p.xs.push_back(0.0f);
    for (int k = 1; k < n; ++k) {
      const float x = outline.hi.x * static_cast<float>(k) / static_cast<float>(n);
      if (x < outline.hi.x) p.xs.push_back(x);
    }
  }
  p.xs.push_back(outline.hi.x);
  const int rows = o.leaf_style == LeafStyle::Shaped ? o.leaf_bend.rows() : 1;
  p.ys.push_back(outline.lo.y);
  for (int k = 1; k < rows; ++k) {
    p.ys.push_back(outline.lo.y + (outline.hi.y - outline.lo.y) * static_cast<float>(k) /
                                      static_cast<float>(rows));
  }
  p.ys.push_back(outline.hi.y);
  return p;
}

std::size_t petiole_segments(const Skeleton& sk, const GeometryOptions& o) {
  std::size_t n = 0;
  for (const Leaf& leaf : sk.leaves) n += drawn_petiole(leaf, o) ? 1u : 0u;
  return n;
}

std::vector<std::size_t> drawn_leaf_shapes(const Skeleton& sk, const GeometryOptions& o) {
  std::vector<std::size_t> drawn(leaf_shape_count());
  for (std::size_t shape = 0; shape < drawn.size(); ++shape) drawn[shape] = shape;
  if (o.leaf_margin.entire()) return drawn;
  std::vector<double> aspect(drawn.size(), 0.0);
  std::vector<std::size_t> leaves(drawn.size(), 0);
  for (const Leaf& leaf : sk.leaves) {
    if (!(leaf.length > 0.0f)) continue;
    const auto shape = static_cast<std::size_t>(leaf.shape);
    aspect[shape] += static_cast<double>(leaf.width) / static_cast<double>(leaf.length);
    ++leaves[shape];
  }
  for (std::size_t shape = 0; shape < drawn.size(); ++shape) {
    if (leaves[shape] > 0)
      drawn[shape] = margined_shape_index(shape, o.leaf_margin, aspect[shape] / leaves[shape]);
  }
  return drawn;
}

std::size_t leaf_outline_triangles(const Skeleton& sk, const GeometryOptions& o) {
  const std::vector<std::size_t> drawn = drawn_leaf_shapes(sk, o);
  std::size_t n = 0;
  for (const Leaf& leaf : sk.leaves)
    n += leaf_shape(drawn[static_cast<std::size_t>(leaf.shape)]).triangles.size();
  return n;
}

void add_leaf_cards(const Skeleton& sk, const GeometryOptions& o, TreeGeometry& g) {
  const bool hinged = o.leaf_style == LeafStyle::Hinged;
  const bool shaped = o.leaf_style == LeafStyle::Shaped;
  const float hinge = static_cast<float>(o.hinge_position);
  const float angle = static_cast<float>(o.hinge_angle * kPi / 180.0);
  LeafCards& cards = g.cards;
  const std::vector<std::size_t> drawn = drawn_leaf_shapes(sk, o);
  for (std::size_t li = 0; li < sk.leaves.size(); ++li) {
    const Leaf& leaf = sk.leaves[li];
    const std::size_t shape = drawn[static_cast<std::size_t>(leaf.shape)];
    const LeafOutline& outline = leaf_outline(shape);
    const glm::vec3 across = glm::cross(leaf.axis, leaf.normal);
    glm::vec3 base = leaf.position;
    if (drawn_petiole(leaf, o)) {
      add_petiole(leaf, static_cast<std::int32_t>(li), o, g.curves);
      base += leaf.axis * (static_cast<float>(o.petiole_length) * leaf.length);
    }
    // Leaf space (x across, y along) to the tree: flat, the side panels folded, or bent.
    auto place = [&](float x, float y) {
      if (shaped) {
        const glm::vec3 p = o.leaf_bend.place(x, y, leaf.width, leaf.length);
        return base + across * p.x + leaf.axis * p.y + leaf.normal * p.z;
      }
      float lift = 0.0f;
      const float beyond = std::fabs(x) - hinge;
      if (hinged && beyond > 0.0f) {
        x = (x < 0.0f ? -1.0f : 1.0f) * (hinge + beyond * std::cos(angle));
        lift = beyond * std::sin(angle);
      }
      return base + leaf.axis * (y * leaf.length) + across * (x * leaf.width) +
             leaf.normal * (lift * leaf.width);
    };
    auto normal = [&](float x, float y) {
      const glm::vec3 n = o.leaf_bend.normal(x, y, leaf.width, leaf.length);
      return glm::normalize(across * n.x + leaf.axis * n.y + leaf.normal * n.z);
    };
    const LeafPanels panels = leaf_panels(outline, o);
    for (std::size_t r = 0; r + 1 < panels.ys.size(); ++r) {
      for (std::size_t k = 0; k + 1 < panels.xs.size(); ++k) {
        LeafCard c;
        c.leaf = static_cast<std::int32_t>(li);
        c.shape = static_cast<std::uint16_t>(shape);
        c.x0 = panels.xs[k];
        c.x1 = panels.xs[k + 1];
        c.y0 = panels.ys[r];
        c.y1 = panels.ys[r + 1];
        const std::array<glm::vec2, 4> corner = {glm::vec2(c.x0, c.y0), glm::vec2(c.x1, c.y0),
                                                 glm::vec2(c.x1, c.y1), glm::vec2(c.x0, c.y1)};
        for (const glm::vec2& q : corner) {
          cards.corners.push_back(place(q.x, q.y));
          if (shaped) cards.normals.push_back(normal(q.x, q.y));
        }
        cards.cards.push_back(c);
      }
    }
  }
}

LeafMesh leaf_triangles(const TreeGeometry& geometry) {
  LeafMesh m;
  const LeafCards& lc = geometry.cards;
  for (std::size_t i = 0; i < lc.size();) {
    std::size_t end = i + 1;  // the leaf's panels are consecutive cards
    while (end < lc.size() && lc.cards[end].leaf == lc.cards[i].leaf) ++end;
    // The cards' cuts across (the first row's) and along (each row's first card's).
    std::vector<float> splits, rows;
    for (std::size_t k = i; k + 1 < end && lc.cards[k].y0 == lc.cards[i].y0; ++k) {
      if (lc.cards[k + 1].y0 == lc.cards[i].y0) splits.push_back(lc.cards[k].x1);
    }
    for (std::size_t k = i + 1; k < end; ++k) {
      if (lc.cards[k].y0 != lc.cards[k - 1].y0) rows.push_back(lc.cards[k].y0);
    }
    const LeafTemplate t = leaf_template(leaf_shape(lc.cards[i].shape), splits, rows);
    const bool bent = !lc.normals.empty();
    const auto first = static_cast<std::uint32_t>(m.positions.size());
    for (std::size_t k = 0; k < t.vertices.size(); ++k) {
      const glm::vec3 v = t.vertices[k];
      // The panel that holds (x, y) (a vertex on a cut: the first, both agree).
      std::size_t c = i;
      while (c + 1 < end && (v.y > lc.cards[c].y1 || v.x > lc.cards[c].x1)) ++c;
      const LeafCard& card = lc.cards[c];
      const glm::vec3* q = &lc.corners[4 * c];
      const float u = (v.x - card.x0) / (card.x1 - card.x0),
                  w = (v.y - card.y0) / (card.y1 - card.y0);
      if (bent) {  // a panel of a shaped leaf need not be flat: bilinear over its corners
        m.positions.push_back((q[0] * (1 - u) + q[1] * u) * (1 - w) +
                              (q[3] * (1 - u) + q[2] * u) * w);
      } else {
        m.positions.push_back(q[0] + (q[1] - q[0]) * u + (q[3] - q[0]) * w);
      }
      m.uvs.push_back(t.uvs[k]);
    }
    for (const auto& tri : t.triangles) {
      m.indices.insert(m.indices.end(), {first + tri[0], first + tri[1], first + tri[2]});
      m.front_material.push_back(kMaterialLeafFront);
      m.back_material.push_back(kMaterialLeafBack);
      m.leaf.push_back(lc.cards[i].leaf);
      m.color.emplace_back(1.0f);
    }
    i = end;
  }
  const LeafMesh& free = geometry.leaves;
  const auto first = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), free.positions.begin(), free.positions.end());
  m.uvs.insert(m.uvs.end(), free.uvs.begin(), free.uvs.end());
  for (std::uint32_t k : free.indices) m.indices.push_back(first + k);
  m.front_material.insert(m.front_material.end(), free.front_material.begin(),
                          free.front_material.end());
  m.back_material.insert(m.back_material.end(), free.back_material.begin(),
                         free.back_material.end());
  m.leaf.insert(m.leaf.end(), free.leaf.begin(), free.leaf.end());
  m.color.insert(m.color.end(), free.color.begin(), free.color.end());
  return m;
}

}  // namespace arbor::generator
