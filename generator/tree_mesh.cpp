// Tube and leaf tessellation of a Skeleton. Limbs between skeleton points are straight here;
// the renderer uses exact curves instead.
#include "generator/tree_mesh.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "generator/leaf_shapes.h"
#include "generator/weber_penn_formulas.h"

namespace arbor::gen {

namespace {

constexpr double kPi = 3.14159265358979323846;

glm::vec3 any_perpendicular(const glm::vec3& t) {
  const glm::vec3 a = std::fabs(t.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
  return glm::normalize(glm::cross(a, t));
}

int sides_for(const Skeleton& sk, const Stem& s) {
  if (s.level == 0) return std::clamp(std::max(24, 8 * sk.trunk.lobes), 24, 96);
  const int by_size = static_cast<int>(std::ceil(2.0 * kPi * s.base_radius / 0.01));
  return std::clamp(by_size, 5, 24);
}

// Ring samples along a stem: each point, plus extra rings inside segments where the radius is
// not linear in z (taper > 1, or the flared base of the trunk).
struct RingSample {
  glm::vec3 centre;
  glm::vec3 tangent;
  float z;
  float arc;
};

std::vector<RingSample> ring_samples(const Skeleton& sk, const Stem& s) {
  std::vector<RingSample> rings;
  const auto n = s.point_count;
  const float z_step = (1.0f - s.z_start) / static_cast<float>(n - 1);
  float arc = 0.0f;
  for (std::uint32_t i = 0; i + 1 < n; ++i) {
    const glm::vec3 a = sk.points[s.first_point + i].position;
    const glm::vec3 b = sk.points[s.first_point + i + 1].position;
    const glm::vec3 d = b - a;
    const float len = glm::length(d);
    const glm::vec3 t = len > 0.0f ? d / len : glm::vec3(0, 0, 1);
    const float z0 = s.z_start + z_step * i;
    int sub = 1;
    if (s.taper > 1.0f) sub = 8;
    if (s.level == 0 && sk.trunk.flare > 0.0f && z0 < 0.125f) sub = std::max(sub, 8);
    for (int k = 0; k < sub; ++k) {
      const float f = static_cast<float>(k) / sub;
      rings.push_back({a + d * f, t, z0 + z_step * f, arc + len * f});
    }
    arc += len;
    if (i + 2 == n) rings.push_back({b, t, 1.0f, arc});
  }
  // Smooth tangents at joints between segments.
  for (size_t i = 1; i + 1 < rings.size(); ++i) {
    const glm::vec3 m = rings[i - 1].tangent + rings[i].tangent;
    if (glm::length(m) > 1e-6f) rings[i].tangent = glm::normalize(m);
  }
  return rings;
}

void add_tube(const Skeleton& sk, const Stem& s, TreeMesh& mesh) {
  if (s.point_count < 2) return;
  const std::vector<RingSample> rings = ring_samples(sk, s);
  const int sides = sides_for(sk, s);
  const float circumference = std::max(1e-6f, 2.0f * static_cast<float>(kPi) * s.base_radius);
  const auto first_vertex = static_cast<std::uint32_t>(mesh.positions.size());
  glm::vec3 normal = any_perpendicular(rings.front().tangent);
  for (size_t r = 0; r < rings.size(); ++r) {
    const RingSample& ring = rings[r];
    if (r > 0) {
      // Rotation-minimising frame by projection of the previous normal (small steps).
      normal = normal - ring.tangent * glm::dot(normal, ring.tangent);
      normal = glm::length(normal) > 1e-8f ? glm::normalize(normal) : any_perpendicular(ring.tangent);
    }
    const glm::vec3 binormal = glm::cross(ring.tangent, normal);
    const float radius = sk.radius_at(s, ring.z);
    const bool trunk = s.level == 0;
    const float flare = trunk ? static_cast<float>(wp::flare_scale(sk.trunk.flare, ring.z)) : 1.0f;
    for (int k = 0; k <= sides; ++k) {
      const double angle = 2.0 * kPi * k / sides;
      const float lobe = trunk ? static_cast<float>(wp::lobe_scale(sk.trunk.lobes,
                                                                   sk.trunk.lobe_depth, angle))
                               : 1.0f;
      const glm::vec3 radial = normal * static_cast<float>(std::cos(angle)) +
                               binormal * static_cast<float>(std::sin(angle));
      mesh.positions.push_back(ring.centre + radial * (radius * flare * lobe));
      mesh.normals.push_back(radial);
      mesh.uvs.emplace_back(static_cast<float>(k) / sides, ring.arc / circumference);
    }
  }
  const auto row = static_cast<std::uint32_t>(sides + 1);
  const size_t first_index = mesh.indices.size();
  for (std::uint32_t r = 0; r + 1 < rings.size(); ++r) {
    for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(sides); ++k) {
      const std::uint32_t a = first_vertex + r * row + k, b = a + 1, c = a + row, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  }
  // Normals from the surface itself (taper slope, flare and lobes included), area-weighted.
  const size_t vertex_count = mesh.positions.size() - first_vertex;
  std::vector<glm::vec3> accumulated(vertex_count, glm::vec3(0.0f));
  for (size_t i = first_index; i < mesh.indices.size(); i += 3) {
    const std::uint32_t ia = mesh.indices[i], ib = mesh.indices[i + 1], ic = mesh.indices[i + 2];
    const glm::vec3 n = glm::cross(mesh.positions[ib] - mesh.positions[ia],
                                   mesh.positions[ic] - mesh.positions[ia]);
    accumulated[ia - first_vertex] += n;
    accumulated[ib - first_vertex] += n;
    accumulated[ic - first_vertex] += n;
  }
  for (size_t v = 0; v < vertex_count; ++v) {
    // The seam's two copies share one normal: fold them together.
    const size_t k = v % row;
    glm::vec3 n = accumulated[v];
    if (k == 0) n += accumulated[v + row - 1];
    if (k + 1 == row) n += accumulated[v - row + 1];
    if (glm::length(n) > 1e-12f) mesh.normals[first_vertex + v] = glm::normalize(n);
  }
}

void add_leaf(const Leaf& leaf, TreeMesh& mesh) {
  const LeafShape& shape = leaf_shapes()[static_cast<size_t>(leaf.shape)];
  const glm::vec3 across = glm::cross(leaf.axis, leaf.normal);
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  for (const glm::vec2& v : shape.vertices) {
    mesh.positions.push_back(leaf.position + leaf.axis * (v.y * leaf.length) +
                             across * (v.x * leaf.width));
    mesh.normals.push_back(leaf.normal);
    mesh.uvs.emplace_back(v.x + 0.5f, v.y);
  }
  for (const auto& t : shape.triangles) {
    mesh.indices.insert(mesh.indices.end(), {first + t[0], first + t[1], first + t[2]});
  }
}

}  // namespace

TreeMesh tessellate(const Skeleton& skeleton) {
  TreeMesh mesh;
  for (const Stem& s : skeleton.stems) add_tube(skeleton, s, mesh);
  mesh.bark_triangles = mesh.triangle_count();
  for (const Leaf& l : skeleton.leaves) add_leaf(l, mesh);
  return mesh;
}

}  // namespace arbor::gen
