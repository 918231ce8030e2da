// Tessellation of TreeGeometry for export: curve segments as tubes, grids as they are, leaves.
#include "generator/geometry/tree_mesh.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include "common/math.h"

namespace arbor::generator {

namespace {

int sides_for(float radius) {
  return std::clamp(static_cast<int>(std::ceil(2.0 * kPi * radius / 0.01)), 5, 24);
}

// Appends quads between consecutive rings of `row` vertices each.
void stitch_rings(TreeMesh& mesh, std::uint32_t first, std::uint32_t rings, std::uint32_t row) {
  for (std::uint32_t r = 0; r + 1 < rings; ++r) {
    for (std::uint32_t k = 0; k + 1 < row; ++k) {
      const std::uint32_t a = first + r * row + k, b = a + 1, c = a + row, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  }
}

void add_curve_segment(const CurveSet& curves, std::size_t i, double tolerance, TreeMesh& mesh) {
  const glm::vec4 p0 = curves.points[2 * i], p1 = curves.points[2 * i + 1];
  const glm::vec4 m0 = curves.tangents[2 * i], m1 = curves.tangents[2 * i + 1];
  // Second derivative of a cubic Hermite is linear in u: its maximum is at u = 0 or 1.
  const glm::vec3 a0 = glm::vec3(-6.0f * p0 - 4.0f * m0 + 6.0f * p1 - 2.0f * m1);
  const glm::vec3 a1 = glm::vec3(6.0f * p0 + 2.0f * m0 - 6.0f * p1 + 4.0f * m1);
  const double sum = std::max(std::fabs(a0.x), std::fabs(a1.x)) +
                     std::max(std::fabs(a0.y), std::fabs(a1.y)) +
                     std::max(std::fabs(a0.z), std::fabs(a1.z));
  const double error = std::max(5e-4, tolerance * std::max(p0.w, p1.w));
  const int n = std::min(64, lane_subdivisions(sum, error));
  const int sides = sides_for(std::max(p0.w, p1.w));
  const CurveSegment& seg = curves.segments[i];
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  for (int k = 0; k <= n; ++k) {
    const float u = static_cast<float>(k) / n;
    const glm::vec4 p = curves.position(i, u);
    const glm::vec4 d = curves.derivative(i, u);
    const glm::vec3 t = glm::normalize(glm::vec3(d));
    glm::vec3 normal = seg.normal0 + (seg.normal1 - seg.normal0) * u;
    normal = glm::normalize(normal - t * glm::dot(normal, t));
    const glm::vec3 binormal = glm::cross(t, normal);
    // The sweep surface's normal tilts with the radius slope dr/ds.
    const float slope = d.w / std::max(1e-12f, glm::length(glm::vec3(d)));
    for (int j = 0; j <= sides; ++j) {
      const float angle = 2.0f * static_cast<float>(kPi) * j / sides;
      const glm::vec3 radial = normal * std::cos(angle) + binormal * std::sin(angle);
      mesh.positions.push_back(glm::vec3(p) + radial * p.w);
      mesh.normals.push_back(glm::normalize(radial - t * slope));
      mesh.uvs.emplace_back(static_cast<float>(j) / sides, seg.arc0 + (seg.arc1 - seg.arc0) * u);
    }
  }
  stitch_rings(mesh, first, static_cast<std::uint32_t>(n + 1),
               static_cast<std::uint32_t>(sides + 1));
}

void add_grid(const GridSet& grids, const DisplacedGrid& g, TreeMesh& mesh) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  for (std::uint32_t j = 0; j < g.height; ++j) {
    for (std::uint32_t i = 0; i < g.width; ++i) {
      const std::size_t v = g.first_vertex + j * g.width + i;
      mesh.positions.push_back(grids.vertices[v]);
      mesh.normals.push_back(grids.normals[v]);
      mesh.uvs.emplace_back(static_cast<float>(i) / (g.width - 1), grids.bark[v].x);
    }
  }
  stitch_rings(mesh, first, g.height, g.width);
}

// The ramiform's collars as they are (RamiformSet): their normals, and uv from their bark
// coordinates as the tubes have them (u the azimuth's fraction of the way round, v the arc length).
void add_ramiforms(const RamiformSet& r, TreeMesh& mesh) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), r.positions.begin(), r.positions.end());
  mesh.normals.insert(mesh.normals.end(), r.normals.begin(), r.normals.end());
  for (const glm::vec3& b : r.bark)
    mesh.uvs.emplace_back(b.y / (2.0f * static_cast<float>(kPi)), b.x);
  for (std::uint32_t i : r.indices) mesh.indices.push_back(first + i);
}

void add_leaves(const LeafMesh& leaves, TreeMesh& mesh) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), leaves.positions.begin(), leaves.positions.end());
  mesh.uvs.insert(mesh.uvs.end(), leaves.uvs.begin(), leaves.uvs.end());
  // Area-weighted vertex normals: a hinged leaf's crease is smoothed, as Bloomenthal notes.
  std::vector<glm::vec3> normals(leaves.positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t < leaves.triangle_count(); ++t) {
    const std::uint32_t a = leaves.indices[3 * t], b = leaves.indices[3 * t + 1],
                        c = leaves.indices[3 * t + 2];
    const glm::vec3 n = glm::cross(leaves.positions[b] - leaves.positions[a],
                                   leaves.positions[c] - leaves.positions[a]);
    normals[a] += n;
    normals[b] += n;
    normals[c] += n;
  }
  for (const glm::vec3& n : normals) {
    mesh.normals.push_back(glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 0, 1));
  }
  for (std::uint32_t i : leaves.indices) mesh.indices.push_back(first + i);
}

}  // namespace

int lane_subdivisions(double sum, double error) {
  if (sum <= 0.0 || error <= 0.0) return 1;
  return std::max(1, static_cast<int>(std::ceil(std::sqrt(sum / (8.0 * error)))));
}

TreeMesh tessellate(const TreeGeometry& geometry, double tolerance) {
  TreeMesh mesh;
  // Bark first (limbs, trunk grids, collars), then the leaves' (petioles and blades).
  const CurveSet& c = geometry.curves;
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c.segments[i].material == kMaterialBark) add_curve_segment(c, i, tolerance, mesh);
  }
  for (const DisplacedGrid& g : geometry.grids.grids) add_grid(geometry.grids, g, mesh);
  add_ramiforms(geometry.ramiforms, mesh);
  mesh.bark_triangles = mesh.triangle_count();
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c.segments[i].material != kMaterialBark) add_curve_segment(c, i, tolerance, mesh);
  }
  add_leaves(leaf_triangles(geometry), mesh);
  return mesh;
}

}  // namespace arbor::generator
