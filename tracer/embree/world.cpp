// The scene in Embree: instances of the tree prototypes, the meshes, the ground quad; world-space
// hits from instanced hits.
#include "tracer/embree/world.h"

#include <algorithm>
#include <stdexcept>
#include <chrono>
#include <cstring>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "tracer/embree/embree_internal.h"
#include "tracer/embree/embree_scene.h"
#include "tracer/embree/grass.h"
#include "tracer/embree/lod_calibration.h"

namespace arbor::tracer {

namespace {
constexpr float kGroundHalfSize = 1.0e4f;  // metres: the ground quad reaches past any horizon

// Records that Embree geometry `id` is item `index` of some list.
void map_id(std::vector<int>& map, unsigned id, std::size_t index) {
  if (map.size() <= id) map.resize(id + 1, -1);
  map[id] = static_cast<int>(index);
}
}  // namespace

World::World(const scene::Scene& scene, const EmbreeDevice& device)
    : scene_(scene), device_(device) {
  const auto start = std::chrono::steady_clock::now();
  top_ = new_scene(device);
  // Level of detail (scene/lod.h): what each prototype's filters need from its instances. The
  // instances are attached first, in order, so their Embree ids are their indices in lod_
  // (checked below).
  std::vector<PrototypeLod> lods(scene.prototypes.size());
  for (const scene::TreeInstance& inst : scene.instances) {
    PrototypeLod& l = lods[static_cast<std::size_t>(inst.prototype)];
    if (inst.lod.active) l.instances = &lod_;
    l.thin_limbs = l.thin_limbs || inst.lod.thins_stems();
    if (inst.lod.leaf_scale > 1.0f) {  // calibrated with the limbs thinned (lod_calibration.h)
      l.card_scale = scene::kLodMaxLeafScale;
      l.thin_limbs = true;
    }
    lod_.push_back(inst.lod);
  }
  for (std::size_t p = 0; p < scene.prototypes.size(); ++p) {
    prototypes_.push_back(
        std::make_unique<TreePrototype>(device, *scene.prototypes[p].geometry, lods[p]));
  }
  calibrate_leaves(lods);
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const scene::TreeInstance& inst = scene.instances[i];
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, prototypes_[static_cast<std::size_t>(inst.prototype)]->scene());
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &inst.to_world[0][0]);
    const unsigned id = attach(top_.get(), g);
    if (id != i) throw RuntimeFailure("Embree numbered the tree instances out of order");
    map_id(instance_of_geometry_, id, i);
  }
  for (const scene::GrassTile& tile : scene.meadow.tiles)
    grass_.push_back(std::make_unique<GrassPrototype>(device, tile));
  for (std::size_t i = 0; i < scene.meadow.placements.size(); ++i) {
    const scene::GrassPlacement& p = scene.meadow.placements[i];
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, grass_[static_cast<std::size_t>(p.tile)]->scene());
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &p.to_world[0][0]);
    map_id(grass_of_geometry_, attach(top_.get(), g), i);
  }
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const scene::MeshObject& mesh = scene.meshes[i];
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    fill(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, mesh.positions.data(), sizeof(glm::vec3),
         mesh.positions.size());
    fill(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, mesh.indices.data(), 3 * sizeof(std::uint32_t),
         mesh.indices.size() / 3);
    map_id(mesh_of_geometry_, attach(top_.get(), g), i);
  }
  if (!scene.terrain.empty()) attach_terrain(scene.terrain);
  if (!scene.rocks.empty()) attach_rocks(scene.rocks);
  if (scene.has_ground) {
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    const float s = kGroundHalfSize;
    // On a terrain, the plane is its lowest level around it (0, or its surround's lowest), a
    // hair below so that the terrain's edge, which falls to it, wins where they meet.
    const float z = scene.terrain.empty() ? 0.0f : ground_level();
    const float corners[12] = {-s, -s, z, s, -s, z, s, s, z, -s, s, z};
    const unsigned tris[6] = {0, 1, 2, 0, 2, 3};
    fill(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, corners, 3 * sizeof(float), 4);
    fill(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, tris, 3 * sizeof(unsigned), 2);
    attach(top_.get(), g);
  }
  rtcCommitScene(top_.get());
  device.check("building the scene");
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

World::~World() = default;

void World::attach_terrain(const scene::Terrain& t) {
  // One grid over the whole terrain (Embree splits it into its own small patches), its vertex
  // buffer the terrain's own (shared, not copied), in a compact scene of its own (Embree's
  // compressed nodes: 12 bytes a vertex here and about 12 more in Embree, measured at 4 × 4 km
  // at 1 m; docs/landscape.md), placed by an identity instance.
  terrain_ = new_scene(device_);
  rtcSetSceneFlags(terrain_.get(), RTC_SCENE_FLAG_COMPACT);
  RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_GRID);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, t.vertices().data(),
                             0, sizeof(glm::vec3),
                             static_cast<std::size_t>(t.columns()) * t.rows());
  auto* grid = static_cast<RTCGrid*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, sizeof(RTCGrid), 1));
  grid->startVertexID = 0;
  grid->stride = static_cast<unsigned>(t.columns());
  grid->width = static_cast<unsigned short>(t.columns());
  grid->height = static_cast<unsigned short>(t.rows());
  attach(terrain_.get(), g);
  if (const scene::Terrain* around = t.surround()) {
    // The surround's grid (geometry 1) and the skirt (kSkirtGeometry) beside the square's.
    RTCGeometry s = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_GRID);
    rtcSetSharedGeometryBuffer(s, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                               around->vertices().data(), 0, sizeof(glm::vec3),
                               static_cast<std::size_t>(around->columns()) * around->rows());
    auto* sg = static_cast<RTCGrid*>(
        rtcSetNewGeometryBuffer(s, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, sizeof(RTCGrid), 1));
    sg->startVertexID = 0;
    sg->stride = static_cast<unsigned>(around->columns());
    sg->width = static_cast<unsigned short>(around->columns());
    sg->height = static_cast<unsigned short>(around->rows());
    attach(terrain_.get(), s);
    RTCGeometry w = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    fill(w, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, t.skirt_positions().data(),
         sizeof(glm::vec3), t.skirt_positions().size());
    fill(w, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, t.skirt_indices().data(),
         3 * sizeof(std::uint32_t), t.skirt_indices().size() / 3);
    if (attach(terrain_.get(), w) != kSkirtGeometry) throw std::logic_error("the skirt's id");
  }
  rtcCommitScene(terrain_.get());
  RTCGeometry inst = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(inst, terrain_.get());
  const glm::mat4 identity(1.0f);
  rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &identity[0][0]);
  terrain_geometry_ = attach(top_.get(), inst);
}

void World::attach_rocks(const scene::Rocks& rocks) {
  for (const scene::RockShape& shape : rocks.shapes) {
    SceneHandle one = new_scene(device_);
    RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    fill(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, shape.positions.data(), sizeof(glm::vec3),
         shape.positions.size());
    fill(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, shape.indices.data(),
         3 * sizeof(std::uint32_t), shape.indices.size() / 3);
    attach(one.get(), g);
    rtcCommitScene(one.get());
    rock_shapes_.push_back(std::move(one));
  }
  for (std::size_t i = 0; i < rocks.placements.size(); ++i) {
    const scene::RockPlacement& p = rocks.placements[i];
    RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, rock_shapes_[static_cast<std::size_t>(p.shape)].get());
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &p.to_world[0][0]);
    map_id(rock_of_geometry_, attach(top_.get(), g), i);
  }
}

void World::calibrate_leaves(const std::vector<PrototypeLod>& lods) {
  for (std::size_t p = 0; p < lods.size(); ++p) {
    if (lods[p].card_scale == 1.0f) continue;
    const generator::TreeGeometry& g = *scene_.prototypes[p].geometry;
    const double alpha = calibrate_leaf_area(device_, prototypes_[p]->scene(), g, lod_);
    const std::uint32_t leaves = g.lod_items[scene::kLodLeaves];
    for (std::size_t i = 0; i < lod_.size(); ++i) {
      if (scene_.instances[i].prototype != static_cast<int>(p)) continue;
      lod_[i].leaf_scale = calibrated_leaf_scale(
          alpha, scene::lod_kept(lod_[i].keep[scene::kLodLeaves], leaves), leaves);
    }
  }
}

bool World::intersect(const Ray& ray, WorldHit& hit) const {
  if (log_) {
    const std::lock_guard<std::mutex> lock(log_->mutex);
    log_->closest.push_back(ray);
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = embree_ray_hit(ray);
  rtcIntersect1(top_.get(), &context, &rh);
  hit.grass = -1;  // a blade's describe_grass sets it
  hit.rock = false;
  SurfaceHit& s = hit.surface;
  s.terrain = glm::vec2(0.0f);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    const float t = plane_beyond(ray);
    if (!(t > 0.0f)) return false;
    describe_plane(ray, t, hit);
    return true;
  }
  if (terrain_ && rh.hit.instID[0] == terrain_geometry_) {
    describe_terrain(ray, rh.ray.tfar, glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z),
                     rh.hit.geomID == kSkirtGeometry, hit);
    return true;
  }
  if (rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID && rh.hit.geomID < mesh_of_geometry_.size() &&
      mesh_of_geometry_[rh.hit.geomID] >= 0) {
    const scene::MeshObject& mesh =
        scene_.meshes[static_cast<std::size_t>(mesh_of_geometry_[rh.hit.geomID])];
    const std::uint32_t* tri = &mesh.indices[3 * static_cast<std::size_t>(rh.hit.primID)];
    const glm::vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]],
                    c = mesh.positions[tri[2]];
    const TriangleSide side = side_seen(a, b, c, ray.direction);
    s.kind = SurfaceKind::None;
    s.t = rh.ray.tfar;
    s.primitive = rh.hit.primID;
    s.position = ray.origin + ray.direction * s.t;
    hit.mesh_front = side.front;
    s.geometric_normal = side.normal;
    s.shading_normal = s.geometric_normal;
    // The OBJ's vertex normals, interpolated (Embree's u, v weigh the second and third corner),
    // shade a smooth mesh smoothly; offsets and leak tests keep the geometric normal. Turned to
    // the side the ray sees.
    if (!mesh.normal_indices.empty()) {
      const std::uint32_t* ni = &mesh.normal_indices[3 * static_cast<std::size_t>(rh.hit.primID)];
      if (ni[0] != scene::MeshObject::kNoNormal && ni[1] != scene::MeshObject::kNoNormal &&
          ni[2] != scene::MeshObject::kNoNormal) {
        const float u = rh.hit.u, v = rh.hit.v;
        glm::vec3 n = (1.0f - u - v) * mesh.normals[ni[0]] + u * mesh.normals[ni[1]] +
                      v * mesh.normals[ni[2]];
        const float len = glm::length(n);
        if (len > 1e-6f) {
          n /= len;
          s.shading_normal = glm::dot(n, s.geometric_normal) < 0.0f ? -n : n;
        }
      }
    }
    s.tangent = glm::normalize(b - a);
    s.leaf = -1;
    hit.ground = false;
    hit.mesh = true;
    hit.instance = -1;
    hit.material = &mesh.materials[mesh.material[rh.hit.primID]];
    hit.object_id = mesh.object_id;
    hit.material_id = mesh.material_ids[mesh.material[rh.hit.primID]];
    return true;
  }
  if (rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID) {
    describe_plane(ray, rh.ray.tfar, hit);
    return true;
  }
  const unsigned inst_id = rh.hit.instID[0];
  if (inst_id < rock_of_geometry_.size() && rock_of_geometry_[inst_id] >= 0) {
    describe_rock(ray, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, rock_of_geometry_[inst_id],
                  hit);
    return true;
  }
  if (inst_id < grass_of_geometry_.size() && grass_of_geometry_[inst_id] >= 0) {
    describe_grass(ray, rh.hit.primID, rh.hit.u, rh.ray.tfar, grass_of_geometry_[inst_id], hit);
    return true;
  }
  const int instance = instance_of_geometry_[inst_id];
  const scene::TreeInstance& inst = scene_.instances[static_cast<std::size_t>(instance)];
  // The same ray in the prototype's space (t is unchanged by an affine map of the direction).
  Ray local;
  local.origin = glm::vec3(inst.to_object * glm::vec4(ray.origin, 1.0f));
  local.direction = glm::vec3(inst.to_object * glm::vec4(ray.direction, 0.0f));
  const glm::vec3 ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  prototypes_[static_cast<std::size_t>(inst.prototype)]->describe_hit(
      local, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, ng, s,
      lod_[static_cast<std::size_t>(instance)].leaf_scale);
  s.position = ray.origin + ray.direction * s.t;
  s.geometric_normal = glm::normalize(inst.normal_to_world * s.geometric_normal);
  s.shading_normal = glm::normalize(inst.normal_to_world * s.shading_normal);
  s.tangent = glm::normalize(glm::mat3(inst.to_world) * s.tangent);
  hit.ground = false;
  hit.mesh = false;
  hit.instance = instance;
  hit.material = s.kind == SurfaceKind::Leaf ? &inst.leaf : &inst.bark;
  hit.object_id = inst.object_id;
  hit.material_id = s.kind != SurfaceKind::Leaf                  ? inst.bark_id
                    : s.material == generator::kMaterialLeafBack ? inst.leaf_back_id
                                                                 : inst.leaf_front_id;
  return true;
}

float World::plane_beyond(const Ray& ray) const {
  // The ground plane goes on past its quad (10 km each way) to the horizon: a ray that left the
  // quad going down meets it out there (seen from a hill, the gap between the quad's edge and
  // the horizon was black).
  if (!scene_.has_ground || !(ray.direction.z < 0.0f)) return -1.0f;
  const float level = scene_.terrain.empty() ? 0.0f : ground_level();
  const float t = (level - ray.origin.z) / ray.direction.z;
  if (!(t > ray.t_min && t < ray.t_max)) return -1.0f;
  // Only out there: a ray Embree let through inside the quad (one leaving the plane itself,
  // below its offset) is not the plane's to catch again.
  const glm::vec3 p = ray.origin + t * ray.direction;
  return std::max(std::abs(p.x), std::abs(p.y)) >= kGroundHalfSize ? t : -1.0f;
}

void World::describe_plane(const Ray& ray, float t, WorldHit& hit) const {
  SurfaceHit& s = hit.surface;
  hit.ground = true;
  hit.mesh = false;
  hit.instance = -1;
  hit.material = &scene_.ground;
  hit.object_id = scene_.ground_object_id;
  hit.material_id = scene_.ground_material_id;
  s.kind = SurfaceKind::None;
  s.t = t;
  s.position = ray.origin + ray.direction * s.t;
  s.position.z = scene_.terrain.empty() ? 0.0f : ground_level();
  s.geometric_normal = ray.direction.z < 0.0f ? glm::vec3(0, 0, 1) : glm::vec3(0, 0, -1);
  s.shading_normal = s.geometric_normal;
  s.tangent = glm::vec3(1, 0, 0);
  s.leaf = -1;
}

void World::describe_terrain(const Ray& ray, float t_hit, glm::vec3 ng, bool skirt,
                             WorldHit& hit) const {
  const scene::Terrain& t = scene_.terrain;
  SurfaceHit& s = hit.surface;
  s.kind = SurfaceKind::None;
  s.t = t_hit;
  s.position = ray.origin + ray.direction * s.t;
  // The facet's normal and the smooth one (both up, z > 0; the skirt's, a wall, its facet's),
  // turned to the side the ray came from.
  ng = glm::normalize(ng);
  if (ng.z < 0.0f) ng = -ng;
  glm::vec3 n = skirt ? ng : t.normal(s.position.x, s.position.y);
  if (glm::dot(ng, ray.direction) > 0.0f) {
    ng = -ng;
    n = -n;
  }
  s.geometric_normal = ng;
  s.shading_normal = n;
  s.tangent = glm::normalize(glm::cross(glm::vec3(0, 1, 0), n));
  s.leaf = -1;
  s.terrain = skirt ? glm::vec2(0.0f, 1.0f) : t.cover(s.position.x, s.position.y);
  hit.ground = true;
  hit.mesh = false;
  hit.instance = -1;
  hit.material = &scene_.ground;
  hit.object_id = scene_.terrain_object_id;
  hit.material_id = scene_.ground_material_id;
}

void World::describe_rock(const Ray& ray, unsigned primitive, float u, float v, float t, int rock,
                          WorldHit& hit) const {
  const scene::Rocks& rocks = scene_.rocks;
  const scene::RockPlacement& p = rocks.placements[static_cast<std::size_t>(rock)];
  const scene::RockShape& shape = rocks.shapes[static_cast<std::size_t>(p.shape)];
  const std::uint32_t* tri = &shape.indices[3 * static_cast<std::size_t>(primitive)];
  // A turn and a uniform scale: normals turn with the placement.
  const glm::mat3 turn(p.to_world);
  const glm::vec3 a = turn * shape.positions[tri[0]], b = turn * shape.positions[tri[1]],
                  c = turn * shape.positions[tri[2]];
  SurfaceHit& s = hit.surface;
  const TriangleSide side = side_seen(a, b, c, ray.direction);
  s.kind = SurfaceKind::None;
  s.t = t;
  s.primitive = primitive;
  s.position = ray.origin + ray.direction * t;
  s.geometric_normal = side.normal;
  glm::vec3 n = (1.0f - u - v) * shape.normals[tri[0]] + u * shape.normals[tri[1]] +
                v * shape.normals[tri[2]];
  n = glm::normalize(turn * n);
  s.shading_normal = glm::dot(n, s.geometric_normal) < 0.0f ? -n : n;
  s.tangent = glm::normalize(b - a);
  s.leaf = -1;
  // The rock's pattern in the plane the face is most nearly in (so it does not stretch down the
  // rock's sides), offset per rock so that two rocks of one shape differ.
  const glm::vec3 an = glm::abs(s.shading_normal), q = s.position;
  s.uv = an.z >= an.x && an.z >= an.y ? glm::vec2(q.x, q.y)
         : an.x >= an.y               ? glm::vec2(q.y + 17.0f, q.z)
                                      : glm::vec2(q.x - 29.0f, q.z);
  s.terrain = glm::vec2(0.0f, 1.0f);  // all rock
  hit.ground = false;
  hit.mesh = false;
  hit.rock = true;
  hit.instance = -1;
  hit.material = &rocks.material;
  hit.object_id = rocks.object_id;
  hit.material_id = rocks.material_id;
}

void World::describe_grass(const Ray& ray, unsigned blade, float u, float t, int placement,
                           WorldHit& hit) const {
  const scene::Meadow& m = scene_.meadow;
  const scene::GrassPlacement& p = m.placements[static_cast<std::size_t>(placement)];
  Ray local;
  local.origin = glm::vec3(p.to_object * glm::vec4(ray.origin, 1.0f));
  local.direction = glm::vec3(p.to_object * glm::vec4(ray.direction, 0.0f));
  SurfaceHit& s = hit.surface;
  grass_[static_cast<std::size_t>(p.tile)]->describe_hit(local, blade, u, t, s);
  // A turn about z and a translation: normals and tangents turn with the placement. Sheared
  // onto a terrain: tangents by the placement, normals by its inverse transpose.
  const glm::mat3 turn(p.to_world);
  s.position = ray.origin + ray.direction * t;
  if (p.sheared) {
    const glm::mat3 normals = glm::transpose(glm::mat3(p.to_object));
    s.geometric_normal = glm::normalize(normals * s.geometric_normal);
    s.shading_normal = glm::normalize(normals * s.shading_normal);
    s.tangent = glm::normalize(turn * s.tangent);
  } else {
    s.geometric_normal = turn * s.geometric_normal;
    s.shading_normal = turn * s.shading_normal;
    s.tangent = turn * s.tangent;
  }
  hit.ground = false;
  hit.mesh = false;
  hit.instance = -1;
  hit.grass = placement;
  hit.material = &m.grass;
  hit.object_id = m.object_id;
  hit.material_id = s.material == generator::kMaterialLeafBack ? m.back_id : m.front_id;
}

bool World::occluded(const Ray& ray) const {
  if (log_) {
    const std::lock_guard<std::mutex> lock(log_->mutex);
    log_->shadow.push_back(ray);
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = embree_ray(ray);
  rtcOccluded1(top_.get(), &context, &r);
  return r.tfar < 0.0f || plane_beyond(ray) > 0.0f;
}

}  // namespace arbor::tracer
