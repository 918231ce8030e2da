// The trunk continued below its base (GeometryOptions::sink_slope), so that a tree standing on a
// slope meets it with no gap under the downhill side of its flare (docs/landscape.md).
#include <cmath>
#include <cstddef>
#include <limits>

#include <glm/geometric.hpp>

#include "common/math.h"
#include "generator/geometry/tree_geometry.h"

namespace arbor::generator {

namespace {

// The root stem's first point: where the tree stands.
glm::vec3 tree_base(const Skeleton& sk) {
  for (const Stem& stem : sk.stems) {
    if (stem.parent < 0 && stem.point_count > 0) return sk.points[stem.first_point].position;
  }
  return glm::vec3(0.0f);
}

// The grid whose first ring is nearest the base (a displaced trunk), or -1.
int base_grid(const TreeGeometry& g, const glm::vec3& base, float& distance) {
  int best = -1;
  distance = std::numeric_limits<float>::infinity();
  for (std::size_t k = 0; k < g.grids.grids.size(); ++k) {
    const DisplacedGrid& d = g.grids.grids[k];
    glm::vec3 centre(0.0f);
    for (std::uint32_t j = 0; j + 1 < d.width; ++j) centre += g.grids.vertices[d.first_vertex + j];
    centre /= static_cast<float>(d.width - 1);
    const float e = glm::length(centre - base);
    if (e < distance) {
      distance = e;
      best = static_cast<int>(k);
    }
  }
  return best;
}

// The curve segment whose start is nearest the base, or -1.
int base_segment(const TreeGeometry& g, const glm::vec3& base, float& distance) {
  int best = -1;
  distance = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < g.curves.size(); ++i) {
    const float e = glm::length(glm::vec3(g.curves.points[2 * i]) - base);
    if (e < distance) {
      distance = e;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace

void sink_trunk(const Skeleton& sk, double slope_degrees, TreeGeometry& g) {
  if (slope_degrees <= 0.0) return;
  const glm::vec3 base = tree_base(sk);
  const auto rise = static_cast<float>(std::tan(slope_degrees * kPi / 180.0));
  float grid_distance, curve_distance;
  const int grid = base_grid(g, base, grid_distance);
  const int segment = base_segment(g, base, curve_distance);
  if (grid >= 0 && grid_distance <= curve_distance) {
    // The first ring repeated `depth` lower: a wall that continues the flare and lobes straight
    // down, its normals the ring's made horizontal.
    const DisplacedGrid d = g.grids.grids[static_cast<std::size_t>(grid)];
    float reach = 0.0f;
    for (std::uint32_t j = 0; j < d.width; ++j) {
      const glm::vec3 v = g.grids.vertices[d.first_vertex + j];
      reach = std::max(reach, glm::length(glm::vec2(v - base)));
    }
    const float depth = rise * reach + 0.01f;
    DisplacedGrid wall = d;
    wall.first_vertex = static_cast<std::uint32_t>(g.grids.vertices.size());
    wall.height = 2;
    for (int row = 0; row < 2; ++row) {
      for (std::uint32_t j = 0; j < d.width; ++j) {
        const std::size_t k = d.first_vertex + j;
        const glm::vec3 v = g.grids.vertices[k];
        glm::vec3 n = g.grids.normals[k];
        n.z = 0.0f;
        const float len = glm::length(n);
        const glm::vec3 out =
            len > 1e-6f
                ? n / len
                : glm::normalize(glm::vec3(glm::vec2(v - base), 0.0f) + glm::vec3(1e-6f, 0, 0));
        const glm::vec2 bark = g.grids.bark[k];
        g.grids.vertices.push_back(row == 0 ? v - glm::vec3(0, 0, depth) : v);
        g.grids.normals.push_back(out);
        g.grids.bark.emplace_back(row == 0 ? bark.x - depth : bark.x, bark.y);
      }
    }
    g.grids.grids.push_back(wall);
    return;
  }
  if (segment < 0) return;
  // A straight round segment from `depth` below the first segment's start up to it.
  const auto i = static_cast<std::size_t>(segment);
  const glm::vec4 start = g.curves.points[2 * i];
  const float depth = rise * start.w + 0.01f;
  CurveSegment seg = g.curves.segments[i];
  seg.arc1 = seg.arc0;
  seg.arc0 -= depth;
  seg.normal1 = seg.normal0;
  seg.lod_level = kNoLod;
  g.curves.points.push_back(start - glm::vec4(0, 0, depth, 0));
  g.curves.points.push_back(start);
  g.curves.tangents.emplace_back(0.0f, 0.0f, depth, 0.0f);
  g.curves.tangents.emplace_back(0.0f, 0.0f, depth, 0.0f);
  g.curves.segments.push_back(seg);
}

}  // namespace arbor::generator
