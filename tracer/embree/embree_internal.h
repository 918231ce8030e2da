// Internal to tracer/embree/: arbor's rays as Embree's, and attaching geometry.
#pragma once

#include <cstddef>
#include <cstring>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include "tracer/ray.h"

namespace arbor::tracer {

inline RTCRay embree_ray(const Ray& ray) {
  RTCRay r{};
  r.org_x = ray.origin.x;
  r.org_y = ray.origin.y;
  r.org_z = ray.origin.z;
  r.dir_x = ray.direction.x;
  r.dir_y = ray.direction.y;
  r.dir_z = ray.direction.z;
  r.tnear = ray.t_min;
  r.tfar = ray.t_max;
  r.mask = ~0u;
  return r;
}

// A closest-hit query: the ray, and no hit yet.
inline RTCRayHit embree_ray_hit(const Ray& ray) {
  RTCRayHit rh{};
  rh.ray = embree_ray(ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// Copies `count` elements of `stride` bytes into a new Embree buffer (Embree pads it as needed).
inline void fill(RTCGeometry g, RTCBufferType type, RTCFormat format, const void* data,
                 std::size_t stride, std::size_t count) {
  void* dst = rtcSetNewGeometryBuffer(g, type, 0, format, stride, count);
  if (dst && count > 0) std::memcpy(dst, data, stride * count);
}

// The side of triangle (a, b, c) a ray going `direction` sees: the front is the side its
// counter-clockwise normal faces; `normal` is the unit normal on the side the ray came from.
struct TriangleSide {
  bool front = true;
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
};
inline TriangleSide side_seen(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                              const glm::vec3& direction) {
  const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  const bool front = glm::dot(n, direction) < 0.0f;
  return {front, front ? n : -n};
}

// Commits a geometry, attaches it to the scene, releases the caller's reference; returns its id.
inline unsigned attach(RTCScene scene, RTCGeometry g) {
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  return id;
}

}  // namespace arbor::tracer
