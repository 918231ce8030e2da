// Grass tiles in Embree: normal-oriented Bézier ribbons, and their hits.
#include "tracer/embree/grass.h"

#include <glm/geometric.hpp>

#include "tracer/embree/embree_internal.h"

namespace arbor::tracer {

GrassPrototype::GrassPrototype(const EmbreeDevice& device, const scene::GrassTile& tile)
    : tile_(tile) {
  scene_ = new_scene(device);
  if (tile.blades() > 0) {
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BEZIER_CURVE);
    auto* index = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(std::uint32_t), tile.blades()));
    if (index) {
      for (std::size_t i = 0; i < tile.blades(); ++i)
        index[i] = static_cast<std::uint32_t>(scene::GrassTile::kPointsPerBlade * i);
    }
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, tile.points.data(),
                               0, sizeof(glm::vec4), tile.points.size());
    // Copied: Embree reads a float3 buffer 16 bytes at a time, past a shared array's end.
    fill(g, RTC_BUFFER_TYPE_NORMAL, RTC_FORMAT_FLOAT3, tile.normals.data(), sizeof(glm::vec3),
         tile.normals.size());
    attach(scene_.get(), g);
  }
  rtcCommitScene(scene_.get());
  device.check("building a meadow tile's BVH");
}

GrassPrototype::~GrassPrototype() = default;

void GrassPrototype::describe_hit(const Ray& ray, unsigned blade, float u, float t,
                                  SurfaceHit& hit) const {
  const glm::vec4* p = &tile_.points[scene::GrassTile::kPointsPerBlade * std::size_t{blade}];
  const glm::vec3* n = &tile_.normals[scene::GrassTile::kPointsPerBlade * std::size_t{blade}];
  // The Bézier's derivative (a quadratic in the differences) and its interpolated normal.
  const float s = 1.0f - u;
  const glm::vec3 d =
      3.0f * (s * s * glm::vec3(p[1] - p[0]) + 2.0f * s * u * glm::vec3(p[2] - p[1]) +
              u * u * glm::vec3(p[3] - p[2]));
  const glm::vec3 nc =
      s * s * s * n[0] + 3.0f * s * s * u * n[1] + 3.0f * s * u * u * n[2] + u * u * u * n[3];
  const glm::vec3 tangent = glm::length(d) > 0.0f ? glm::normalize(d) : glm::vec3(0, 0, 1);
  glm::vec3 up = nc - glm::dot(nc, tangent) * tangent;
  up = glm::length(up) > 0.0f ? glm::normalize(up) : glm::vec3(0, 0, 1);
  const bool front = glm::dot(up, ray.direction) < 0.0f;
  hit.kind = SurfaceKind::Leaf;
  hit.t = t;
  hit.primitive = blade;
  hit.u = u;
  hit.v = 0.0f;
  hit.position = ray.origin + ray.direction * t;
  hit.material = front ? generator::kMaterialLeafFront : generator::kMaterialLeafBack;
  hit.geometric_normal = front ? up : -up;
  hit.shading_normal = hit.geometric_normal;
  hit.tangent = tangent;
  hit.leaf = static_cast<std::int32_t>(blade);
  hit.color = tile_.colors[blade];
  hit.crown_height = u;
  hit.uv = {0.5f, u};
}

}  // namespace arbor::tracer
