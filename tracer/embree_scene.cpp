// Embree geometry lifecycle for a tree prototype (new → buffers → commit → attach → release) and
// hit interpretation (normals, leaf sides, bark coordinates).
#include "tracer/embree_scene.h"

#include <chrono>
#include <cstring>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

namespace arbor::trace {

namespace {

template <typename T>
void fill(RTCGeometry g, RTCBufferType type, unsigned slot, RTCFormat format, const T* data,
          std::size_t count) {
  void* dst = rtcSetNewGeometryBuffer(g, type, slot, format, sizeof(T), count);
  if (dst && count > 0) std::memcpy(dst, data, sizeof(T) * count);
}

unsigned attach(RTCScene scene, RTCGeometry g) {
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  return id;
}

}  // namespace

TreePrototype::TreePrototype(const EmbreeDevice& device, const gen::TreeGeometry& geometry)
    : geometry_(geometry) {
  const auto start = std::chrono::steady_clock::now();
  scene_ = rtcNewScene(device.get());
  device.check("creating a scene");
  const gen::CurveSet& c = geometry.curves;
  if (c.size() > 0) {
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_ROUND_HERMITE_CURVE);
    std::vector<std::uint32_t> index(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) index[i] = static_cast<std::uint32_t>(2 * i);
    fill(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, index.data(), index.size());
    fill(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, c.points.data(), c.points.size());
    fill(g, RTC_BUFFER_TYPE_TANGENT, 0, RTC_FORMAT_FLOAT4, c.tangents.data(), c.tangents.size());
    curve_id_ = attach(scene_, g);
  }
  const gen::GridSet& gs = geometry.grids;
  if (!gs.grids.empty()) {
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_GRID);
    std::vector<RTCGrid> grids(gs.grids.size());
    for (std::size_t i = 0; i < grids.size(); ++i) {
      grids[i] = {gs.grids[i].first_vertex, gs.grids[i].width, gs.grids[i].width,
                  gs.grids[i].height};
    }
    fill(g, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, grids.data(), grids.size());
    fill(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, gs.vertices.data(), gs.vertices.size());
    grid_id_ = attach(scene_, g);
  }
  const gen::LeafMesh& lm = geometry.leaves;
  if (lm.triangle_count() > 0) {
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    fill(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, lm.indices.data(), lm.triangle_count());
    fill(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, lm.positions.data(), lm.positions.size());
    leaf_id_ = attach(scene_, g);
  }
  rtcCommitScene(scene_);
  device.check("building the tree's BVH");
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TreePrototype::~TreePrototype() {
  if (scene_) rtcReleaseScene(scene_);
}

bool TreePrototype::intersect(const Ray& ray, SurfaceHit& hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.direction.x;
  rh.ray.dir_y = ray.direction.y;
  rh.ray.dir_z = ray.direction.z;
  rh.ray.tnear = ray.t_min;
  rh.ray.tfar = ray.t_max;
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

  hit.t = rh.ray.tfar;
  hit.primitive = rh.hit.primID;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  hit.position = ray.origin + ray.direction * hit.t;
  const glm::vec3 ng = glm::normalize(glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
  if (rh.hit.geomID == curve_id_) {
    hit.kind = SurfaceKind::Curve;
    hit.material = geometry_.curves.segments[hit.primitive].material;
    hit.geometric_normal = glm::dot(ng, ray.direction) < 0.0f ? ng : -ng;
    hit.shading_normal = hit.geometric_normal;
    hit.bark = gen::curve_bark(geometry_.curves, hit.primitive, hit.u, hit.position);
  } else if (rh.hit.geomID == grid_id_) {
    hit.kind = SurfaceKind::Grid;
    hit.material = geometry_.grids.grids[hit.primitive].material;
    hit.geometric_normal = glm::dot(ng, ray.direction) < 0.0f ? ng : -ng;
    hit.shading_normal = gen::grid_normal(geometry_.grids, hit.primitive, hit.u, hit.v);
    hit.bark = gen::grid_bark(geometry_.grids, hit.primitive, hit.u, hit.v);
  } else {
    hit.kind = SurfaceKind::Leaf;
    const gen::LeafMesh& lm = geometry_.leaves;
    const std::uint32_t* tri = &lm.indices[3 * static_cast<std::size_t>(hit.primitive)];
    const glm::vec3 a = lm.positions[tri[0]], b = lm.positions[tri[1]], c = lm.positions[tri[2]];
    const glm::vec3 front = glm::normalize(glm::cross(b - a, c - a));  // counter-clockwise side
    const bool from_front = glm::dot(front, ray.direction) < 0.0f;
    hit.material = from_front ? lm.front_material[hit.primitive] : lm.back_material[hit.primitive];
    hit.geometric_normal = from_front ? front : -front;
    hit.shading_normal = hit.geometric_normal;
  }
  return true;
}

}  // namespace arbor::trace
