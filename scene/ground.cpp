#include "scene/ground.h"

namespace arbor::scene {

namespace {
glm::vec3 to_vec3(const Rgb& c) { return glm::vec3(c[0], c[1], c[2]); }
}  // namespace

materials::Material ground_material(const spec::GroundDesc& d, const spec::TerrainDesc& terrain) {
  if (d.patch_cover <= 0.0 && d.detail <= 0.0 && d.stones <= 0.0 && d.litter <= 0.0 &&
      !terrain.enabled)
    return materials::DiffuseMaterial{to_vec3(d.albedo)};
  materials::GroundMaterial g;
  g.albedo = to_vec3(d.albedo);
  g.patch_albedo = to_vec3(d.patch_albedo);
  g.set_cover(static_cast<float>(d.patch_cover));
  g.scale = static_cast<float>(d.patch_scale);
  g.detail = static_cast<float>(d.detail);
  g.stones = static_cast<float>(d.stones);
  g.stone_albedo = to_vec3(d.stone_albedo);
  g.set_litter(static_cast<float>(d.litter));
  g.litter_albedo = to_vec3(d.litter_albedo);
  if (terrain.enabled) {
    g.terrain = true;
    g.soil_albedo = to_vec3(terrain.soil_albedo);
    g.rock_albedo = to_vec3(terrain.rock_albedo);
  }
  return g;
}

}  // namespace arbor::scene
