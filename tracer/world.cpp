// Building the world: species loaded once, trees grown once per (species, seed, time), Embree
// instances for placements, a ground quad; world-space hits from instanced hits.
#include "tracer/world.h"

#include <chrono>
#include <cmath>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "common/error.h"
#include "common/progress.h"
#include "common/rng.h"
#include "generator/weber_penn.h"

namespace arbor::trace {

namespace {
constexpr float kGroundHalfSize = 1.0e4f;  // metres: the ground quad reaches past any horizon
glm::vec3 to_vec3(const Rgb& c) { return glm::vec3(c[0], c[1], c[2]); }
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
    skeleton = gen::grow_weber_penn(sp.weber_penn, options);
  } catch (const RuntimeFailure& e) {
    throw InputError(where, std::string(e.what()));
  }
  Prototype p;
  p.geometry = std::make_unique<gen::TreeGeometry>(
      gen::build_tree_geometry(skeleton, gen::geometry_options_for(sp.leaf)));
  p.embree = std::make_unique<TreePrototype>(device_, *p.geometry);
  stats_.curve_segments += p.geometry->stats.curve_segments;
  stats_.triangles += p.geometry->stats.leaf_triangles + p.geometry->stats.grid_triangles;
  stats_.geometry_bytes += p.geometry->stats.bytes;
  prototypes_.push_back(std::move(p));
  const int index = static_cast<int>(prototypes_.size()) - 1;
  prototype_keys_.emplace_back(key, index);
  return index;
}

TreeLook World::look_for(const gen::Species& sp, const BarkOverride& bark,
                         const LeafOverride& leaf, const SourceLocation& where) const {
  TreeLook look;
  look.bark_albedo = to_vec3(bark.albedo.value_or(sp.bark.albedo));
  look.bump_height = static_cast<float>(bark.bump_height.value_or(sp.bark.bump_height));
  if (!bark.bump_map.empty()) {
    throw InputError(where, "bark.bump_map images are not supported by this build yet; remove "
                            "bump_map to use the procedural bark");
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
  RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(g, prototypes_[static_cast<size_t>(prototype)].embree->scene());
  rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &m[0][0]);
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene_, g);
  rtcReleaseGeometry(g);
  if (instance_of_geometry_.size() <= id) instance_of_geometry_.resize(id + 1, -1);
  instance_of_geometry_[id] = static_cast<int>(instances_.size());
  instances_.push_back(inst);
}

World::World(const SceneDesc& scene, const EmbreeDevice& device, Progress* progress)
    : device_(device) {
  const auto start = std::chrono::steady_clock::now();
  scene_ = rtcNewScene(device.get());
  std::size_t total = scene.trees.size(), done = 0;
  for (const ForestDesc& f : scene.forests) total += static_cast<std::size_t>(f.variants);
  if (progress) progress->set_total(total);
  for (const TreeDesc& t : scene.trees) {
    const int p = prototype_for(t.species, t.seed, t.time, t.where);
    add_instance(p, t.placement, look_for(species(t.species, t.where), t.bark, t.leaf, t.where));
    if (progress) progress->update(++done);
  }
  for (const ForestDesc& f : scene.forests) {
    const TreeLook look = look_for(species(f.species, f.where), f.bark, f.leaf, f.where);
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
    ground_id_ = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene_);
  device.check("building the scene");
  stats_.prototypes = prototypes_.size();
  stats_.instances = instances_.size();
  stats_.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

World::~World() {
  if (scene_) rtcReleaseScene(scene_);
}

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
  rtcIntersect1(scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
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
  rtcOccluded1(scene_, &context, &r);
  return r.tfar < 0.0f;
}

}  // namespace arbor::trace
