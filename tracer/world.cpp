// Building the world: species loaded once, trees grown once per (species, seed, time), Embree
// instances for placements, a ground quad; world-space hits from instanced hits.
#include "tracer/world.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <map>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "common/error.h"
#include "common/progress.h"
#include "common/rng.h"
#include "generator/grow.h"
#include "tracer/image_output.h"
#include "tracer/obj_mesh.h"

namespace arbor::trace {

namespace {
constexpr float kGroundHalfSize = 1.0e4f;  // metres: the ground quad reaches past any horizon
glm::vec3 to_vec3(const Rgb& c) { return glm::vec3(c[0], c[1], c[2]); }

// TREE-MAKER's h0 and r0 (§III) from the skeleton's points, measured from the root stem's first
// point. A tree whose points all lie on one vertical line (r0 = 0), or at one height (h0 = 0),
// takes that measure from its geometry's bounds instead, so h/h0 and r/r0 stay finite.
TreeExtent tree_extent(const gen::Skeleton& sk, const gen::TreeGeometry& g) {
  TreeExtent e;
  for (const gen::Stem& stem : sk.stems) {
    if (stem.parent < 0 && stem.point_count > 0) {
      e.base = sk.points[stem.first_point].position;
      break;
    }
  }
  float h0 = 0.0f, r0 = 0.0f;
  for (const gen::SkeletonPoint& p : sk.points) {
    h0 = std::max(h0, p.position.z - e.base.z);
    r0 = std::max(r0, glm::length(glm::vec2(p.position - e.base)));
  }
  if (h0 <= 1e-6f) h0 = std::max(g.bounds_max.z - e.base.z, 1e-3f);
  if (r0 <= 1e-6f) {
    const glm::vec2 far = glm::max(glm::abs(glm::vec2(g.bounds_min - e.base)),
                                   glm::abs(glm::vec2(g.bounds_max - e.base)));
    r0 = std::max(glm::length(far), 1e-3f);
  }
  e.height = h0;
  e.radius = r0;
  return e;
}
}  // namespace

const gen::Species& World::species(const std::string& path, const SourceLocation& where) {
  for (const auto& [p, s] : species_) {
    if (p == path) return *s;
  }
  (void)where;  // a species file's errors name the species file, line and column themselves
  species_.emplace_back(path, std::make_unique<gen::Species>(gen::load_species(path)));
  return *species_.back().second;
}

int World::prototype_for(const std::string& path, std::uint64_t seed, double time,
                         const SourceLocation& where) {
  const std::string key = path + "#" + std::to_string(seed) + "@" + std::to_string(time);
  for (const auto& [k, index] : prototype_keys_) {
    if (k == key) return index;
  }
  const gen::Species& sp = species(path, where);
  gen::GrowOptions options;
  options.seed = seed;
  options.time = time;
  gen::Skeleton skeleton;
  try {
    skeleton = gen::grow_tree(sp, options);
  } catch (const RuntimeFailure& e) {
    throw InputError(where, std::string(e.what()));
  }
  Prototype p;
  p.geometry = std::make_unique<gen::TreeGeometry>(
      gen::build_tree_geometry(skeleton, gen::geometry_options_for(sp.leaf)));
  p.embree = std::make_unique<TreePrototype>(device_, *p.geometry);
  p.extent = tree_extent(skeleton, *p.geometry);
  stats_.curve_segments += p.geometry->stats.curve_segments;
  stats_.triangles += p.geometry->stats.leaf_triangles + p.geometry->stats.grid_triangles;
  stats_.geometry_bytes += p.geometry->stats.bytes;
  prototypes_.push_back(std::move(p));
  const int index = static_cast<int>(prototypes_.size()) - 1;
  prototype_keys_.emplace_back(key, index);
  return index;
}

const mat::ColorMap* World::albedo_map(const std::string& path) {
  for (const auto& [p, map] : albedo_maps_) {
    if (p == path) return map.get();
  }
  albedo_maps_.emplace_back(path, std::make_unique<mat::ColorMap>(path, ocio_config_path()));
  return albedo_maps_.back().second.get();
}

TreeLook World::look_for(const gen::Species& sp, const BarkOverride& bark,
                         const LeafOverride& leaf, const TreemakerOverride& tm,
                         const SourceLocation& where) {
  TreeLook look;
  // A template's own light {} weights, else arbor's defaults (treemaker-format.md), then the
  // scene's [tree.treemaker] / [forest.treemaker].
  if (sp.model == gen::Model::TreeMaker && sp.treemaker.has_light) look.treemaker = sp.treemaker.light;
  look.treemaker.ambient = tm.ambient.value_or(look.treemaker.ambient);
  look.treemaker.lambert = tm.lambert.value_or(look.treemaker.lambert);
  look.treemaker.height = tm.height.value_or(look.treemaker.height);
  look.treemaker.radius = tm.radius.value_or(look.treemaker.radius);
  look.treemaker.angle = tm.angle.value_or(look.treemaker.angle);
  look.bark_albedo = to_vec3(bark.albedo.value_or(sp.bark.albedo));
  look.bump_height = static_cast<float>(bark.bump_height.value_or(sp.bark.bump_height));
  look.bark_roughness =
      static_cast<float>(bark.roughness.value_or(sp.bark.roughness) * 3.14159265358979323846 / 180.0);
  look.bump_tile = static_cast<float>(bark.bump_tile);
  if (!bark.albedo_map.empty()) look.bark_albedo_map = albedo_map(bark.albedo_map);
  if (!leaf.albedo_map.empty()) look.leaf_albedo_map = albedo_map(leaf.albedo_map);
  if (!bark.bump_map.empty()) {
    for (const auto& [p, map] : bump_maps_) {
      if (p == bark.bump_map) look.bump_map = map.get();
    }
    if (!look.bump_map) {
      bump_maps_.emplace_back(bark.bump_map, std::make_unique<mat::HeightMap>(bark.bump_map));
      look.bump_map = bump_maps_.back().second.get();
    }
  }
  look.leaf_front = to_vec3(leaf.reflectance.value_or(sp.leaf.reflectance));
  look.leaf_back = to_vec3(leaf.back_reflectance.value_or(sp.leaf.back_reflectance));
  look.leaf_transmittance = to_vec3(leaf.transmittance.value_or(sp.leaf.transmittance));
  for (int i = 0; i < 3; ++i) {
    if (look.leaf_front[i] + look.leaf_transmittance[i] > 1.0f + 1e-6f ||
        look.leaf_back[i] + look.leaf_transmittance[i] > 1.0f + 1e-6f) {
      throw InputError(where, "leaf reflectance + transmittance must be at most 1 in every "
                              "channel, front and back (species values with this tree's overrides)");
    }
  }
  return look;
}

void World::add_instance(int prototype, const Placement& pl, const TreeLook& look) {
  Instance inst;
  inst.prototype = prototype;
  glm::mat4 m(1.0f);
  m = glm::translate(m, glm::vec3(pl.position[0], pl.position[1], pl.position[2]));
  m = glm::rotate(m, static_cast<float>(pl.rotation * 3.14159265358979323846 / 180.0), glm::vec3(0, 0, 1));
  m = glm::scale(m, glm::vec3(static_cast<float>(pl.scale)));
  inst.to_world = m;
  inst.to_object = glm::inverse(m);
  inst.normal_to_world = glm::inverseTranspose(glm::mat3(m));
  inst.look = look;
  // Rotation about z and uniform scale: heights and horizontal distances scale by `scale`.
  const TreeExtent& pe = prototypes_[static_cast<size_t>(prototype)].extent;
  inst.extent.base = glm::vec3(m * glm::vec4(pe.base, 1.0f));
  inst.extent.height = pe.height * static_cast<float>(pl.scale);
  inst.extent.radius = pe.radius * static_cast<float>(pl.scale);
  RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(g, prototypes_[static_cast<size_t>(prototype)].embree->scene());
  rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &m[0][0]);
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene_.get(), g);
  rtcReleaseGeometry(g);
  if (instance_of_geometry_.size() <= id) instance_of_geometry_.resize(id + 1, -1);
  instance_of_geometry_[id] = static_cast<int>(instances_.size());
  instances_.push_back(inst);
}

void World::add_mesh(const MeshDesc& d) {
  const ObjMesh obj = load_obj(d.path);
  Mesh mesh;
  // Placement: the file's up axis to z, then scale, rotation about z, position.
  glm::mat4 m(1.0f);
  m = glm::translate(m, glm::vec3(d.placement.position[0], d.placement.position[1], d.placement.position[2]));
  m = glm::rotate(m, static_cast<float>(d.placement.rotation * 3.14159265358979323846 / 180.0), glm::vec3(0, 0, 1));
  m = glm::scale(m, glm::vec3(static_cast<float>(d.placement.scale)));
  if (d.up == "y") m = glm::rotate(m, 1.5707963f, glm::vec3(1, 0, 0));  // y up → z up
  mesh.positions.reserve(obj.positions.size());
  for (const glm::vec3& p : obj.positions) mesh.positions.emplace_back(m * glm::vec4(p, 1.0f));
  std::map<std::string, std::uint16_t> look_index;
  auto look_of = [&](const std::string& name) -> std::uint16_t {
    const auto found = look_index.find(name);
    if (found != look_index.end()) return found->second;
    if (mesh.looks.size() >= 65535) {
      throw InputError(d.where, "mesh " + d.path + ": more than 65535 materials");
    }
    MeshLook look;
    const auto it = d.materials.find(name);
    if (it != d.materials.end()) {
      const MeshMaterialDesc& md = it->second;
      look.kind = md.kind == "bark" ? MeshLook::Kind::Bark
                                    : md.kind == "leaf" ? MeshLook::Kind::Leaf : MeshLook::Kind::Diffuse;
      look.albedo = to_vec3(md.albedo);
      look.leaf_front = to_vec3(md.reflectance);
      look.leaf_back = to_vec3(md.back_reflectance);
      look.leaf_transmittance = to_vec3(md.transmittance);
    }
    mesh.looks.push_back(look);
    return look_index[name] = static_cast<std::uint16_t>(mesh.looks.size() - 1);
  };
  // [mesh.material.NAME] by the faces' material name, else by their group; with no table at all
  // every face is diffuse grey.
  std::vector<std::uint16_t> look_of_part(obj.parts.size());
  for (std::size_t i = 0; i < obj.parts.size(); ++i) {
    const ObjMesh::Part& part = obj.parts[i];
    std::string key;
    if (!d.materials.empty()) {
      if (!part.material.empty() && d.materials.count(part.material)) key = part.material;
      else if (d.materials.count(part.group)) key = part.group;
      else {
        throw InputError(d.where, "mesh " + d.path + ": faces of group '" + part.group + "' (material '" +
                                      part.material + "', from line " + std::to_string(obj.part_line[i]) +
                                      ") have no [mesh.material.*] entry; name the group or the material");
      }
    }
    look_of_part[i] = look_of(key);
  }
  mesh.indices = obj.indices;
  mesh.material.reserve(obj.part.size());
  for (const std::uint32_t p : obj.part) mesh.material.push_back(look_of_part[p]);
  if (mesh.indices.empty()) throw InputError({d.path, 0, 0}, "the OBJ mesh has no faces");
  RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(glm::vec3), mesh.positions.size());
  std::memcpy(v, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
  auto* ix = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), mesh.indices.size() / 3);
  std::memcpy(ix, mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene_.get(), g);
  rtcReleaseGeometry(g);
  if (mesh_of_geometry_.size() <= id) mesh_of_geometry_.resize(id + 1, -1);
  mesh_of_geometry_[id] = static_cast<int>(meshes_.size());
  stats_.triangles += mesh.indices.size() / 3;
  meshes_.push_back(std::move(mesh));
}

World::World(const SceneDesc& scene, const EmbreeDevice& device, Progress* progress)
    : device_(device) {
  const auto start = std::chrono::steady_clock::now();
  scene_ = new_scene(device);
  std::size_t total = scene.trees.size(), done = 0;
  for (const ForestDesc& f : scene.forests) total += static_cast<std::size_t>(f.variants);
  if (progress) progress->set_total(total);
  for (const TreeDesc& t : scene.trees) {
    const int p = prototype_for(t.species, t.seed, t.time, t.where);
    add_instance(p, t.placement, look_for(species(t.species, t.where), t.bark, t.leaf, t.treemaker, t.where));
    if (progress) progress->update(++done);
  }
  for (const ForestDesc& f : scene.forests) {
    const TreeLook look = look_for(species(f.species, f.where), f.bark, f.leaf, f.treemaker, f.where);
    std::vector<int> variants;
    for (int v = 0; v < f.variants; ++v) {
      variants.push_back(prototype_for(f.species, derive_key(f.seed, static_cast<std::uint64_t>(v)), 0.0, f.where));
      if (progress) progress->update(++done);
    }
    for (int i = 0; i < f.count; ++i) {
      Rng rng(derive_key(f.seed ^ 0xf0e57u, static_cast<std::uint64_t>(i)));
      Placement pl;
      pl.position = {f.area[0] + (f.area[2] - f.area[0]) * rng.uniform(),
                     f.area[1] + (f.area[3] - f.area[1]) * rng.uniform(), 0.0};
      pl.rotation = 360.0 * rng.uniform();
      pl.scale = rng.vary(1.0, 0.1);
      add_instance(variants[static_cast<size_t>(i % f.variants)], pl, look);
    }
  }
  for (const MeshDesc& m : scene.meshes) add_mesh(m);
  if (scene.ground.enabled) {
    ground_albedo_ = to_vec3(scene.ground.albedo);
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, 4));
    const float s = kGroundHalfSize;
    const float corners[12] = {-s, -s, 0, s, -s, 0, s, s, 0, -s, s, 0};
    std::copy(corners, corners + 12, v);
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, 2));
    const unsigned tris[6] = {0, 1, 2, 0, 2, 3};
    std::copy(tris, tris + 6, idx);
    rtcCommitGeometry(g);
    ground_id_ = rtcAttachGeometry(scene_.get(), g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene_.get());
  device.check("building the scene");
  stats_.prototypes = prototypes_.size();
  stats_.instances = instances_.size();
  stats_.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

World::~World() = default;

bool World::intersect(const Ray& ray, WorldHit& hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = ray.origin.x; rh.ray.org_y = ray.origin.y; rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.direction.x; rh.ray.dir_y = ray.direction.y; rh.ray.dir_z = ray.direction.z;
  rh.ray.tnear = ray.t_min;
  rh.ray.tfar = ray.t_max;
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_.get(), &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit.mesh = nullptr;
  if (rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID && rh.hit.geomID < mesh_of_geometry_.size() &&
      mesh_of_geometry_[rh.hit.geomID] >= 0) {
    const Mesh& mesh = meshes_[static_cast<size_t>(mesh_of_geometry_[rh.hit.geomID])];
    const std::uint32_t* tri = &mesh.indices[3 * static_cast<std::size_t>(rh.hit.primID)];
    const glm::vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
    const glm::vec3 front = glm::normalize(glm::cross(b - a, c - a));
    SurfaceHit& s = hit.surface;
    s.kind = SurfaceKind::None;
    s.t = rh.ray.tfar;
    s.primitive = rh.hit.primID;
    s.position = ray.origin + ray.direction * s.t;
    hit.mesh_front = glm::dot(front, ray.direction) < 0.0f;
    s.geometric_normal = hit.mesh_front ? front : -front;
    s.shading_normal = s.geometric_normal;
    s.tangent = glm::normalize(b - a);
    s.leaf = -1;
    hit.ground = false;
    hit.instance = -1;
    hit.mesh = &mesh.looks[mesh.material[rh.hit.primID]];
    return true;
  }
  if (rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID) {
    // The ground.
    hit.ground = true;
    hit.instance = -1;
    SurfaceHit& s = hit.surface;
    s.kind = SurfaceKind::None;
    s.t = rh.ray.tfar;
    s.position = ray.origin + ray.direction * s.t;
    s.position.z = 0.0f;
    s.geometric_normal = ray.direction.z < 0.0f ? glm::vec3(0, 0, 1) : glm::vec3(0, 0, -1);
    s.shading_normal = s.geometric_normal;
    s.tangent = glm::vec3(1, 0, 0);
    s.leaf = -1;
    return true;
  }
  const int instance = instance_of_geometry_[rh.hit.instID[0]];
  const Instance& inst = instances_[static_cast<size_t>(instance)];
  // The same ray in the prototype's space (t is unchanged by an affine map of the direction).
  Ray local;
  local.origin = glm::vec3(inst.to_object * glm::vec4(ray.origin, 1.0f));
  local.direction = glm::vec3(inst.to_object * glm::vec4(ray.direction, 0.0f));
  const glm::vec3 ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  prototypes_[static_cast<size_t>(inst.prototype)].embree->describe_hit(
      local, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, ng, hit.surface);
  SurfaceHit& s = hit.surface;
  s.position = ray.origin + ray.direction * s.t;
  s.geometric_normal = glm::normalize(inst.normal_to_world * s.geometric_normal);
  s.shading_normal = glm::normalize(inst.normal_to_world * s.shading_normal);
  s.tangent = glm::normalize(glm::mat3(inst.to_world) * s.tangent);
  hit.ground = false;
  hit.instance = instance;
  return true;
}

bool World::occluded(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r{};
  r.org_x = ray.origin.x; r.org_y = ray.origin.y; r.org_z = ray.origin.z;
  r.dir_x = ray.direction.x; r.dir_y = ray.direction.y; r.dir_z = ray.direction.z;
  r.tnear = ray.t_min;
  r.tfar = ray.t_max;
  r.mask = ~0u;
  rtcOccluded1(scene_.get(), &context, &r);
  return r.tfar < 0.0f;
}

}  // namespace arbor::trace
