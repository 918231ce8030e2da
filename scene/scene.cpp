// Building a scene: species loaded once, trees grown once per (species, seed, time), placements,
// materials from species looks and scene overrides, meshes in world space.
#include "scene/scene.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "common/error.h"
#include "common/math.h"
#include "common/progress.h"
#include "common/rng.h"
#include "common/strings.h"
#include "formats/obj_mesh.h"
#include "formats/species_file.h"
#include "generator/grow.h"
#include "scene/ground.h"
#include "scene/render_budget.h"
#include "scene/tree_parts.h"

namespace arbor::scene {

namespace {

glm::vec3 to_vec3(const Rgb& c) { return glm::vec3(c[0], c[1], c[2]); }

// The materials of one placed tree (species defaults with the scene's overrides).
struct TreeLook {
  materials::Material bark, leaf;
  materials::TreemakerWeights treemaker;
  LodScale lod;  // Weber & Penn §5's s and d for the tree's season
};

class SceneBuilder {
 public:
  SceneBuilder(Scene& scene, std::string ocio_config)
      : s_(scene), ocio_config_(std::move(ocio_config)) {}

  const generator::Species& species(const std::string& path) {
    for (const auto& [p, sp] : species_) {
      if (p == path) return *sp;
    }
    // A species file's errors name the species file, line and column themselves.
    species_.emplace_back(path, std::make_unique<generator::Species>(formats::load_species(path)));
    return *species_.back().second;
  }

  // One tree to grow: its species file, seed and time, and the scene key to blame.
  struct GrowRequest {
    std::string path;
    std::uint64_t seed = 0;
    double time = 0.0;
    SourceLocation where;
    double sink = 0.0;  // GeometryOptions::sink_slope: on a terrain, the trunk continued down
    std::string key() const {
      return path + "#" + std::to_string(seed) + "@" + std::to_string(time);
    }
  };

  // The prototype of each request, growing those not grown yet on up to `threads_` threads at
  // once and adding them in the requests' order: growth is a function of (species, seed, time)
  // alone, so the scene is the one growing them one by one would build, at any thread count.
  // The first failing request in order is the error reported.
  std::vector<int> prototypes_for(const std::vector<GrowRequest>& requests,
                                  Progress* progress = nullptr, std::size_t* done = nullptr) {
    // The requests not grown yet, each key once, their species read here in order.
    std::vector<std::string> keys;
    std::vector<const GrowRequest*> jobs;
    std::vector<std::string> job_keys;
    std::vector<const generator::Species*> job_species;
    std::set<std::string> pending;
    for (const GrowRequest& r : requests) {
      keys.push_back(r.key());
      if (prototype_keys_.count(keys.back()) || !pending.insert(keys.back()).second) continue;
      jobs.push_back(&r);
      job_keys.push_back(keys.back());
      job_species.push_back(&species(r.path));
    }
    std::vector<std::optional<TreePrototypeData>> grown(jobs.size());
    std::vector<std::exception_ptr> errors(jobs.size());
    std::atomic<std::size_t> next{0};
    std::mutex progress_mutex;
    const auto work = [&] {
      for (std::size_t j; (j = next++) < jobs.size();) {
        try {
          grown[j] = grow_prototype(*job_species[j], *jobs[j]);
        } catch (...) {
          errors[j] = std::current_exception();
        }
        if (progress && done) {
          const std::lock_guard<std::mutex> lock(progress_mutex);
          progress->update(++*done);
        }
      }
    };
    std::vector<std::thread> pool;  // this thread works too
    for (std::size_t t = 1; t < std::min<std::size_t>(threads_, jobs.size()); ++t)
      pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      if (errors[j]) std::rethrow_exception(errors[j]);
      add_prototype(job_keys[j], std::move(*grown[j]));
    }
    std::vector<int> indices;
    for (const std::string& key : keys) indices.push_back(prototype_keys_.at(key));
    return indices;
  }

  void set_threads(unsigned threads) {
    threads_ = threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
  }

  const materials::ColorMap* albedo_map(const std::string& path) {
    for (const auto& [p, map] : s_.albedo_maps) {
      if (p == path) return map.get();
    }
    s_.albedo_maps.emplace_back(path, std::make_unique<materials::ColorMap>(path, ocio_config_));
    return s_.albedo_maps.back().second.get();
  }

  const materials::HeightMap* bump_map(const std::string& path) {
    for (const auto& [p, map] : s_.bump_maps) {
      if (p == path) return map.get();
    }
    s_.bump_maps.emplace_back(path, std::make_unique<materials::HeightMap>(path));
    return s_.bump_maps.back().second.get();
  }

  // One coat per (ior, roughness): its albedo table is computed once however many trees share it.
  const materials::CuticleCoat* cuticle(double ior, double roughness) {
    for (const auto& [key, coat] : cuticles_) {
      if (key.first == ior && key.second == roughness) return coat;
    }
    std::unique_ptr<const materials::CuticleCoat> coat =
        materials::CuticleCoat::make(ior, roughness);
    cuticles_.emplace_back(std::make_pair(ior, roughness), coat.get());
    if (coat) s_.coats.push_back(std::move(coat));
    return cuticles_.back().second;
  }
  // A leaf's coat, and its regularised twin when the render regularises (else none).
  void coat(materials::LeafMaterial& l, double ior, double roughness) {
    l.cuticle = cuticle(ior, roughness);
    l.regularized = nullptr;
    if (l.cuticle && regularize_) {
      const double r = materials::CuticleCoat::regularized_roughness(roughness);
      if (r != roughness) l.regularized = cuticle(ior, r);
    }
  }
  void set_regularize(bool on) { regularize_ = on; }
  // [render] lod: each instance's level of detail from its range to `camera`.
  // (`camera` placed on the terrain: placed_camera.)
  void set_lod(const spec::RenderSettings& render, const spec::CameraDesc& camera) {
    lod_ = render.lod;
    lod_quality_ = render.lod_quality;
    camera_ = {camera.position[0], camera.position[1], camera.position[2]};
    height_ = render.height;
    fov_ = camera.fov;
  }

  // The species' bark colour by relief and marks (materials/bark_color.h) over `albedo`.
  static materials::BarkPattern bark_pattern(const generator::BarkLook& own,
                                             const glm::vec3& albedo) {
    materials::BarkPattern p;
    p.furrows = own.furrow_albedo.has_value();
    // Without furrows of its own, the base darkens towards half the bark's albedo.
    p.furrow_albedo = own.furrow_albedo ? to_vec3(*own.furrow_albedo) : 0.5f * albedo;
    p.lenticels = static_cast<float>(own.lenticels);
    p.lenticel_albedo = to_vec3(own.lenticel_albedo);
    p.scars = static_cast<float>(own.scars);
    p.scar_albedo = to_vec3(own.scar_albedo);
    p.base_height = static_cast<float>(own.base_height);
    return p;
  }

  TreeLook look_for(const generator::Species& sp, const spec::BarkOverride& bark,
                    const spec::LeafOverride& leaf, const spec::TreemakerOverride& tm,
                    const SourceLocation& where) {
    TreeLook look;
    // The species' own weights (a template's light {}), else arbor's defaults
    // (treemaker-format.md), then the scene's [tree.treemaker] / [forest.treemaker].
    const generator::TmLight& own = sp.treemaker_light;
    materials::TreemakerWeights& w = look.treemaker;
    w.ambient = tm.ambient.value_or(own.ambient.value_or(w.ambient));
    w.lambert = tm.lambert.value_or(own.lambert.value_or(w.lambert));
    w.height = tm.height.value_or(own.height.value_or(w.height));
    w.radius = tm.radius.value_or(own.radius.value_or(w.radius));
    w.angle = tm.angle.value_or(own.angle.value_or(w.angle));
    materials::BarkMaterial b;
    b.albedo = to_vec3(bark.albedo.value_or(sp.bark.albedo));
    b.bump_height = static_cast<float>(bark.bump_height.value_or(sp.bark.bump_height));
    b.roughness = static_cast<float>(bark.roughness.value_or(sp.bark.roughness) * kPi / 180.0);
    b.bump_tile = static_cast<float>(bark.bump_tile);
    if (!bark.albedo_map.empty()) b.albedo_map = albedo_map(bark.albedo_map);
    if (!bark.bump_map.empty()) b.bump_map = bump_map(bark.bump_map);
    // A scene that sets the bark's albedo or an image replaces the species' bark look, its
    // pattern included (docs/species-format.md).
    if (!bark.albedo && bark.albedo_map.empty() && bark.bump_map.empty())
      b.pattern = bark_pattern(sp.bark, b.albedo);
    look.bark = b;
    materials::LeafMaterial l;
    if (!leaf.albedo_map.empty()) l.albedo_map = albedo_map(leaf.albedo_map);
    const Rgb front = leaf.reflectance.value_or(sp.leaf.reflectance);
    const Rgb back = leaf.back_reflectance.value_or(sp.leaf.back_reflectance);
    const Rgb transmittance = leaf.transmittance.value_or(sp.leaf.transmittance);
    if (!generator::leaf_conserves_energy(front, back, transmittance)) {
      throw InputError(where, std::string(generator::kLeafEnergyRule) +
                                  " (the species' values with this tree's overrides)");
    }
    l.front = to_vec3(front);
    l.back = to_vec3(back);
    l.transmittance = to_vec3(transmittance);
    coat(l, leaf.cuticle_ior.value_or(sp.leaf.cuticle_ior),
         leaf.cuticle_roughness.value_or(sp.leaf.cuticle_roughness));
    l.variation = {static_cast<float>(leaf.variation.value_or(sp.leaf.variation)),
                   static_cast<float>(leaf.hue_variation.value_or(sp.leaf.hue_variation)),
                   static_cast<float>(leaf.crown_gradient.value_or(sp.leaf.crown_gradient))};
    l.texture = {static_cast<float>(leaf.veins.value_or(sp.leaf.veins)), sp.leaf.vein_pairs};
    const generator::Season season = leaf.season.value_or(sp.leaf.season);
    l.season = leaf_season(season, sp.leaf.autumn, front);
    look.leaf = l;
    look.lod = lod_scale(lod_quality_, season, !sp.leaf.autumn.has_value());
    return look;
  }

  // A new object "<prefix>.<n>", n counting the objects of that prefix; its id.
  std::uint32_t new_object(const std::string& prefix) {
    const int n = object_count_[prefix]++;
    s_.object_names.push_back(prefix + "." + std::to_string(n));
    return static_cast<std::uint32_t>(s_.object_names.size());
  }
  // The id of the material of this name (one name, one id).
  std::uint32_t material_named(const std::string& name) {
    const auto found = material_ids_.find(name);
    if (found != material_ids_.end()) return found->second;
    s_.material_names.push_back(name);
    return material_ids_[name] = static_cast<std::uint32_t>(s_.material_names.size());
  }

  void add_instance(int prototype, const spec::Placement& pl, const TreeLook& look,
                    const std::string& species) {
    TreeInstance inst;
    const std::string name = file_stem(species);
    inst.object_id = new_object(name);
    inst.bark_id = material_named(name + "/bark");
    inst.leaf_front_id = material_named(name + "/leaf front");
    inst.leaf_back_id = material_named(name + "/leaf back");
    inst.prototype = prototype;
    const glm::mat4 m = placement_matrix(pl);
    inst.to_world = m;
    inst.to_object = glm::inverse(m);
    inst.normal_to_world = glm::inverseTranspose(glm::mat3(m));
    inst.bark = look.bark;
    inst.leaf = look.leaf;
    inst.treemaker = look.treemaker;
    // Rotation about z and uniform scale: heights and horizontal distances scale by `scale`.
    const TreeExtent& pe = s_.prototypes[static_cast<size_t>(prototype)].extent;
    inst.extent.base = glm::vec3(m * glm::vec4(pe.base, 1.0f));
    inst.extent.height = pe.height * static_cast<float>(pl.scale);
    inst.extent.radius = pe.radius * static_cast<float>(pl.scale);
    if (lod_) {
      // Range to the middle of the tree's bounds.
      const generator::TreeGeometry& g = *s_.prototypes[static_cast<size_t>(prototype)].geometry;
      const glm::vec3 middle(m * glm::vec4(0.5f * (g.bounds_min + g.bounds_max), 1.0f));
      const double range = glm::length(glm::dvec3(middle) - camera_);
      inst.lod = instance_lod(calibrated_range(range, height_, fov_), look.lod, g.lod_items);
    }
    s_.instances.push_back(inst);
  }

  void add_mesh(const spec::MeshDesc& d);

 private:
  static TreePrototypeData grow_prototype(const generator::Species& sp, const GrowRequest& r) {
    generator::GrowOptions options;
    options.seed = r.seed;
    options.time = r.time;
    generator::Skeleton skeleton;
    try {
      skeleton = generator::grow_tree(sp, options);
    } catch (const RuntimeFailure& e) {
      throw InputError(r.where, std::string(e.what()));
    }
    generator::GeometryOptions geometry = generator::geometry_options_for(sp);
    geometry.sink_slope = r.sink;
    TreePrototypeData p;
    p.geometry = std::make_unique<generator::TreeGeometry>(
        generator::build_tree_geometry(skeleton, geometry));
    p.extent = tree_extent(skeleton, *p.geometry);
    return p;
  }

  void add_prototype(const std::string& key, TreePrototypeData p) {
    s_.stats.curve_segments += p.geometry->stats.curve_segments;
    s_.stats.triangles += p.geometry->stats.leaf_triangles + p.geometry->stats.grid_triangles;
    s_.stats.geometry_bytes += p.geometry->stats.bytes;
    s_.prototypes.push_back(std::move(p));
    prototype_keys_.emplace(key, static_cast<int>(s_.prototypes.size()) - 1);
  }

  Scene& s_;
  std::string ocio_config_;
  unsigned threads_ = 1;
  std::vector<std::pair<std::string, std::unique_ptr<generator::Species>>> species_;
  std::map<std::string, int> prototype_keys_;  // (species, seed, time) → prototype
  std::vector<std::pair<std::pair<double, double>, const materials::CuticleCoat*>> cuticles_;
  bool regularize_ = false;  // [render] regularize
  bool lod_ = false;         // [render] lod, lod_quality, and what the range is calibrated by
  double lod_quality_ = 1.0;
  glm::dvec3 camera_{0.0};
  int height_ = 1;
  double fov_ = 45.0;
  std::map<std::string, int> object_count_;
  std::map<std::string, std::uint32_t> material_ids_;
};

void SceneBuilder::add_mesh(const spec::MeshDesc& d) {
  const formats::ObjMesh obj = formats::load_obj(d.path);
  MeshObject mesh;
  mesh.object_id = new_object(file_stem(d.path));
  // Placement: the file's up axis to z, then scale, rotation about z, position.
  glm::mat4 m = placement_matrix(d.placement);
  if (d.up == "y") m = glm::rotate(m, 1.5707963f, glm::vec3(1, 0, 0));  // y up → z up
  mesh.positions.reserve(obj.positions.size());
  for (const glm::vec3& p : obj.positions) mesh.positions.emplace_back(m * glm::vec4(p, 1.0f));
  std::map<std::string, std::uint16_t> material_index;
  auto material_of = [&](const std::string& name) -> std::uint16_t {
    const auto found = material_index.find(name);
    if (found != material_index.end()) return found->second;
    if (mesh.materials.size() >= 65535) {
      throw InputError(d.where, "mesh " + d.path + ": more than 65535 materials");
    }
    materials::Material material;
    const auto it = d.materials.find(name);
    if (it != d.materials.end()) {
      const spec::MeshMaterialDesc& md = it->second;
      // A mesh's bark is its albedo, unmapped and unbumped; its leaves are untinted.
      if (md.kind == "leaf") {
        materials::LeafMaterial leaf;
        leaf.tinted = false;
        leaf.front = to_vec3(md.reflectance);
        leaf.back = to_vec3(md.back_reflectance);
        leaf.transmittance = to_vec3(md.transmittance);
        coat(leaf, md.cuticle_ior, md.cuticle_roughness);
        material = leaf;
      } else {
        material = materials::DiffuseMaterial{to_vec3(md.albedo)};
      }
    }
    mesh.materials.push_back(material);
    mesh.material_ids.push_back(
        material_named(file_stem(d.path) + "/" + (name.empty() ? "default" : name)));
    return material_index[name] = static_cast<std::uint16_t>(mesh.materials.size() - 1);
  };
  // [mesh.material.NAME] by the faces' material name, else by their group; with no table at all
  // every face is diffuse grey.
  std::vector<std::uint16_t> material_of_part(obj.parts.size());
  for (std::size_t i = 0; i < obj.parts.size(); ++i) {
    const formats::ObjMesh::Part& part = obj.parts[i];
    std::string key;
    if (!d.materials.empty()) {
      if (!part.material.empty() && d.materials.count(part.material))
        key = part.material;
      else if (d.materials.count(part.group))
        key = part.group;
      else {
        throw InputError(d.where,
                         "mesh " + d.path + ": faces of group '" + part.group + "' (material '" +
                             part.material + "', from line " + std::to_string(obj.part_line[i]) +
                             ") have no [mesh.material.*] entry; name the group or the material");
      }
    }
    material_of_part[i] = material_of(key);
  }
  mesh.indices = obj.indices;
  // Normals go through the inverse transpose of the placement (scale is uniform, but stay exact).
  const glm::mat3 to_world_normal = glm::transpose(glm::inverse(glm::mat3(m)));
  mesh.normals.reserve(obj.normals.size());
  for (const glm::vec3& n : obj.normals)
    mesh.normals.push_back(glm::normalize(to_world_normal * n));
  static_assert(MeshObject::kNoNormal == formats::ObjMesh::kNoNormal,
                "a mesh keeps the OBJ reader's \"no normal\"");
  mesh.normal_indices = obj.normal_indices;
  mesh.material.reserve(obj.part.size());
  for (const std::uint32_t p : obj.part) mesh.material.push_back(material_of_part[p]);
  if (mesh.indices.empty()) throw InputError({d.path, 0, 0}, "the OBJ mesh has no faces");
  s_.stats.triangles += mesh.indices.size() / 3;
  s_.stats.geometry_bytes +=
      sizeof(glm::vec3) * (mesh.positions.size() + mesh.normals.size()) +
      sizeof(std::uint32_t) * (mesh.indices.size() + mesh.normal_indices.size()) +
      sizeof(std::uint16_t) * mesh.material.size();
  s_.meshes.push_back(std::move(mesh));
}

// The community's plants (scene/community.h): `variants` trees of each species grown (in
// parallel), every plant one of them chosen by its number, turned at random and scaled so that
// its crown's radius is its circle of influence.
template <class Animated, class OnGround>
void add_community(const spec::CommunityDesc& d, Scene& s, SceneBuilder& b, double sink,
                   Progress* progress, std::size_t* done, Animated animated, OnGround on_ground) {
  const auto start = std::chrono::steady_clock::now();
  const Community c = simulate_community(d, s.terrain);
  s.stats.simulation_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<SceneBuilder::GrowRequest> requests;
  for (std::size_t k = 0; k < d.species.size(); ++k) {
    const spec::CommunitySpecies& sp = d.species[k];
    for (int v = 0; v < sp.variants; ++v) {
      requests.push_back({sp.species,
                          derive_key(derive_key(d.seed, k), static_cast<std::uint64_t>(v)),
                          animated(sp.species, 0.0), sp.where, sink});
    }
  }
  const std::vector<int> prototypes = b.prototypes_for(requests, progress, done);
  std::vector<std::size_t> first(d.species.size(), 0);
  std::vector<TreeLook> looks;
  for (std::size_t k = 0; k < d.species.size(); ++k) {
    const spec::CommunitySpecies& sp = d.species[k];
    if (k > 0) first[k] = first[k - 1] + static_cast<std::size_t>(d.species[k - 1].variants);
    looks.push_back(b.look_for(b.species(sp.species), sp.bark, sp.leaf, sp.treemaker, sp.where));
  }
  for (const Plant& p : c.plants) {
    const spec::CommunitySpecies& sp = d.species[static_cast<std::size_t>(p.species)];
    Rng rng(derive_key(d.seed ^ 0x91a47u, p.id));
    const auto variant = static_cast<int>(rng.uniform() * sp.variants);
    const int prototype =
        prototypes[first[static_cast<std::size_t>(p.species)] + static_cast<std::size_t>(variant)];
    const float crown = s.prototypes[static_cast<std::size_t>(prototype)].extent.radius;
    spec::Placement pl;
    pl.position = {p.position.x, p.position.y, 0.0};
    pl.rotation = 360.0 * rng.uniform();
    pl.scale = p.radius / std::max(0.1, static_cast<double>(crown));
    s.community.push_back({s.instances.size(), p.species, variant, p.age, p.radius});
    b.add_instance(prototype, on_ground(pl), looks[static_cast<std::size_t>(p.species)],
                   sp.species);
  }
}

// The ground plane, the terrain's object and the material they share, the meadow and the rocks.
void add_ground_and_meadow(const spec::SceneDesc& desc, Scene& s, SceneBuilder& b) {
  if (desc.ground.enabled || desc.terrain.enabled) {
    s.has_ground = desc.ground.enabled;
    if (desc.ground.enabled) {
      s.object_names.emplace_back("ground");
      s.ground_object_id = static_cast<std::uint32_t>(s.object_names.size());
    }
    if (desc.terrain.enabled) {
      s.object_names.emplace_back("terrain");
      s.terrain_object_id = static_cast<std::uint32_t>(s.object_names.size());
      s.stats.geometry_bytes += s.terrain.bytes();
    }
    s.ground_material_id = b.material_named("ground");
    s.ground = ground_material(desc.ground, desc.terrain);
  }
  if (desc.meadow.density > 0.0) {
    s.meadow = grow_meadow(desc.meadow, desc.clock, s.terrain);
    s.object_names.emplace_back("meadow");
    s.meadow.object_id = static_cast<std::uint32_t>(s.object_names.size());
    s.meadow.front_id = b.material_named("meadow/blade front");
    s.meadow.back_id = b.material_named("meadow/blade back");
    s.stats.geometry_bytes += s.meadow.bytes();
  }
  if (desc.rocks.enabled) {
    s.rocks = place_rocks(desc.rocks, s.terrain);
    s.object_names.emplace_back("rocks");
    s.rocks.object_id = static_cast<std::uint32_t>(s.object_names.size());
    s.rocks.material_id = b.material_named("rocks");
    s.stats.geometry_bytes += s.rocks.bytes();
  }
}

}  // namespace

glm::mat4 placement_matrix(const spec::Placement& pl) {
  glm::mat4 m(1.0f);
  m = glm::translate(m, glm::vec3(pl.position[0], pl.position[1], pl.position[2]));
  m = glm::rotate(m, static_cast<float>(pl.rotation * kPi / 180.0), glm::vec3(0, 0, 1));
  m = glm::scale(m, glm::vec3(static_cast<float>(pl.scale)));
  return m;
}

// How a forest's trees are grown: the wind's time, the trunks' sink below their base, the budget
// of geometry its first variant is checked against.
struct ForestGrowth {
  double time = 0.0, sink = 0.0;
  std::uint64_t budget = 0;
};

// A forest: its variants grown (the first alone, so its size checks the budget), then its trees
// scattered over its area.
template <class OnGround>
void add_forest(const spec::ForestDesc& f, Scene& s, SceneBuilder& b, const ForestGrowth& grow,
                Progress* progress, std::size_t* done, OnGround on_ground) {
  const TreeLook look = b.look_for(b.species(f.species), f.bark, f.leaf, f.treemaker, f.where);
  // The first variant alone (its size checks the budget), then the others in parallel.
  std::vector<SceneBuilder::GrowRequest> requests;
  for (int v = 0; v < f.variants; ++v) {
    requests.push_back({f.species, derive_key(f.seed, static_cast<std::uint64_t>(v)), grow.time,
                        f.where, grow.sink});
  }
  std::vector<int> variants;
  {
    const std::size_t before = s.stats.geometry_bytes;
    variants.push_back(b.prototypes_for({requests.front()}, progress, done).front());
    check_forest_budget(f, before, s.stats.geometry_bytes, grow.budget);
  }
  requests.erase(requests.begin());
  const std::vector<int> rest = b.prototypes_for(requests, progress, done);
  variants.insert(variants.end(), rest.begin(), rest.end());
  for (int i = 0; i < f.count; ++i) {
    Rng rng(derive_key(f.seed ^ 0xf0e57u, static_cast<std::uint64_t>(i)));
    spec::Placement pl;
    pl.position = {f.area[0] + (f.area[2] - f.area[0]) * rng.uniform(),
                   f.area[1] + (f.area[3] - f.area[1]) * rng.uniform(), 0.0};
    pl.rotation = 360.0 * rng.uniform();
    pl.scale = rng.vary(1.0, 0.1);
    b.add_instance(variants[static_cast<size_t>(i % f.variants)], on_ground(pl), look, f.species);
  }
}

std::unique_ptr<const Scene> build_scene(const spec::SceneDesc& desc,
                                         const std::string& ocio_config, Progress* progress,
                                         std::uint64_t geometry_budget, unsigned threads) {
  const auto start = std::chrono::steady_clock::now();
  auto scene = std::make_unique<Scene>();
  SceneBuilder b(*scene, ocio_config);
  b.set_threads(threads);
  b.set_regularize(desc.render.regularize);
  // The terrain first: everything stands on it (a tree's or a mesh's z is its height above it).
  if (desc.terrain.enabled) scene->terrain = Terrain(desc.terrain);
  b.set_lod(desc.render, placed_camera(desc.camera, scene->terrain));
  std::size_t total = desc.trees.size(), done = 0;
  for (const spec::ForestDesc& f : desc.forests) total += static_cast<std::size_t>(f.variants);
  for (const spec::CommunitySpecies& c : desc.community.species)
    total += static_cast<std::size_t>(c.variants);
  if (progress) progress->set_total(total);
  // The animation's clock: seconds of wind for models that sway, years of growth for the fractal
  // model (spec/scene_desc.h, AnimationDesc).
  const auto animated = [&](const std::string& species, double time) {
    if (desc.clock == 0.0) return time;
    return b.species(species).model() == generator::Model::Fractal
               ? time + desc.clock * desc.animation.years_per_second
               : time + desc.clock;
  };
  const auto on_ground = [&](spec::Placement pl) {
    pl.position[2] += scene->terrain.height(pl.position[0], pl.position[1]);
    return pl;
  };
  // On a terrain every trunk goes on below its base, far enough for a 60° slope (a tree's base
  // is on the surface under its axis; docs/landscape.md).
  const double sink = desc.terrain.enabled ? 60.0 : 0.0;
  // The trees' prototypes first, grown in parallel; then their instances in scene order.
  std::vector<SceneBuilder::GrowRequest> trees;
  for (const spec::TreeDesc& t : desc.trees)
    trees.push_back({t.species, t.seed, animated(t.species, t.time), t.where, sink});
  const std::vector<int> tree_prototypes = b.prototypes_for(trees, progress, &done);
  for (std::size_t i = 0; i < desc.trees.size(); ++i) {
    const spec::TreeDesc& t = desc.trees[i];
    b.add_instance(tree_prototypes[i], on_ground(t.placement),
                   b.look_for(b.species(t.species), t.bark, t.leaf, t.treemaker, t.where),
                   t.species);
  }
  done = desc.trees.size();
  for (const spec::ForestDesc& f : desc.forests) {
    add_forest(f, *scene, b, {animated(f.species, 0.0), sink, geometry_budget}, progress, &done,
               on_ground);
  }
  if (desc.community.enabled)
    add_community(desc.community, *scene, b, sink, progress, &done, animated, on_ground);
  for (const spec::MeshDesc& m : desc.meshes) {
    spec::MeshDesc placed = m;
    placed.placement = on_ground(m.placement);
    b.add_mesh(placed);
  }
  add_ground_and_meadow(desc, *scene, b);
  scene->stats.prototypes = scene->prototypes.size();
  scene->stats.instances = scene->instances.size();
  scene->stats.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return scene;
}

}  // namespace arbor::scene
