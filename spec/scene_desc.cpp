// What the scene description's plain data can tell of itself: the camera's consistency, the
// names of its choices, its frame paths and the files it reads.
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "common/error.h"
#include "spec/scene_desc.h"

namespace arbor::spec {

void check_camera(const CameraDesc& d) {
  const glm::vec3 origin(d.position[0], d.position[1], d.position[2]);
  const glm::vec3 target(d.look_at[0], d.look_at[1], d.look_at[2]);
  const glm::vec3 up(d.up[0], d.up[1], d.up[2]);
  if (glm::length(target - origin) < 1e-9f) {
    throw InputError(d.look_at_where, "camera.look_at must differ from camera.position");
  }
  if (glm::length(glm::cross(glm::normalize(target - origin), up)) < 1e-6f) {
    throw InputError(d.up_where,
                     "camera.up must not be parallel to the viewing direction (nor zero)");
  }
}

const char* name_of(Integrator integrator) {
  return kIntegratorNames[static_cast<std::size_t>(integrator)];
}
const char* name_of(SkyModel model) { return kSkyModelNames[static_cast<std::size_t>(model)]; }

std::optional<Integrator> integrator_named(std::string_view name) {
  for (std::size_t i = 0; i < kIntegratorNames.size(); ++i) {
    if (name == kIntegratorNames[i]) return static_cast<Integrator>(i);
  }
  return std::nullopt;
}

std::string frame_path(const std::string& path, int frame) {
  const std::size_t first = path.find('#');
  if (first == std::string::npos) return path;
  std::size_t last = first;
  while (last < path.size() && path[last] == '#') ++last;
  std::string number = std::to_string(frame);
  if (number.size() < last - first) number.insert(0, last - first - number.size(), '0');
  return path.substr(0, first) + number + path.substr(last);
}

std::vector<std::string> scene_inputs(const SceneDesc& s) {
  std::vector<std::string> in{s.path};
  auto add = [&](const std::string& p) {
    if (!p.empty()) in.push_back(p);
  };
  auto looks = [&](const BarkOverride& b, const LeafOverride& l) {
    add(b.bump_map);
    add(b.albedo_map);
    add(l.albedo_map);
  };
  for (const TreeDesc& t : s.trees) {
    add(t.species);
    looks(t.bark, t.leaf);
  }
  for (const ForestDesc& f : s.forests) {
    add(f.species);
    looks(f.bark, f.leaf);
  }
  for (const MeshDesc& m : s.meshes) add(m.path);
  if (s.sky.model == SkyModel::Envmap) add(s.sky.path);
  if (s.terrain.enabled && s.terrain.kind == TerrainKind::Image) add(s.terrain.path);
  return in;
}

}  // namespace arbor::spec
