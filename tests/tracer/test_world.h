// A scene description built (scene/) and put into Embree (tracer/) in one step, as `arbor render`
// does, with arbor's own OCIO config.
#pragma once

#include <memory>
#include <string>

#include <glm/gtc/matrix_inverse.hpp>
#include <gtest/gtest.h>

#include "imaging/color.h"
#include "scene/scene.h"
#include "tracer/embree/embree_device.h"
#include "tracer/embree/world.h"

namespace arbor::tracer {

inline const std::string kOcioConfig = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";

struct TestWorld {
  TestWorld(const spec::SceneDesc& desc, const EmbreeDevice& device)
      : scene(scene::build_scene(desc, kOcioConfig)), world(*scene, device) {}
  std::unique_ptr<const scene::Scene> scene;
  World world;
};

// One tree geometry as a scene of one prototype and one instance at `placement`, in Embree.
class GeometryWorld {
 public:
  GeometryWorld(const generator::TreeGeometry& g, const EmbreeDevice& device,
                const spec::Placement& placement = {})
      : scene_(make_scene(g, placement)), world_(*scene_, device) {}
  // The closest hit in world space; false when the ray escapes.
  bool intersect(const Ray& ray, SurfaceHit& hit) const {
    WorldHit w;
    if (!world_.intersect(ray, w)) return false;
    EXPECT_EQ(w.instance, 0);
    EXPECT_NE(w.material, nullptr);
    hit = w.surface;
    return true;
  }
  const World& world() const { return world_; }

 private:
  static std::unique_ptr<scene::Scene> make_scene(const generator::TreeGeometry& g,
                                                  const spec::Placement& placement) {
    auto scene = std::make_unique<scene::Scene>();
    scene::TreePrototypeData p;
    p.geometry = std::make_unique<generator::TreeGeometry>(g);
    scene->prototypes.push_back(std::move(p));
    scene::TreeInstance inst;
    inst.to_world = scene::placement_matrix(placement);
    inst.to_object = glm::inverse(inst.to_world);
    inst.normal_to_world = glm::inverseTranspose(glm::mat3(inst.to_world));
    scene->instances.push_back(inst);
    return scene;
  }
  std::unique_ptr<scene::Scene> scene_;
  World world_;
};

// The sky's CIE XYZ → scene_linear through arbor's config.
inline imaging::ColorTransform xyz_to_scene_linear() {
  static const imaging::ColorPipeline color(kOcioConfig);
  return color.xyz_to_scene_linear();
}

}  // namespace arbor::tracer
