// Internal to tracer/embree/: arbor's rays as Embree's, and attaching geometry.
#pragma once

#include <embree3/rtcore.h>

#include "tracer/ray.h"

namespace arbor::trace {

inline RTCRay embree_ray(const Ray& ray) {
  RTCRay r{};
  r.org_x = ray.origin.x; r.org_y = ray.origin.y; r.org_z = ray.origin.z;
  r.dir_x = ray.direction.x; r.dir_y = ray.direction.y; r.dir_z = ray.direction.z;
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

// Commits a geometry, attaches it to the scene, releases the caller's reference; returns its id.
inline unsigned attach(RTCScene scene, RTCGeometry g) {
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  return id;
}

}  // namespace arbor::trace
