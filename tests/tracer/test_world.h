// A scene description built (scene/) and put into Embree (tracer/) in one step, as `arbor render`
// does, with arbor's own OCIO config.
#pragma once

#include <memory>
#include <string>

#include "imaging/color.h"
#include "scene/scene.h"
#include "tracer/embree/embree_device.h"
#include "tracer/embree/world.h"

namespace arbor::tracer {

inline const std::string kOcioConfig = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";

struct TestWorld {
  TestWorld(const formats::SceneDesc& desc, const EmbreeDevice& device)
      : scene(scene::build_scene(desc, kOcioConfig)), world(*scene, device) {}
  std::unique_ptr<const scene::Scene> scene;
  World world;
};

// The sky's CIE XYZ → scene_linear through arbor's config.
inline imaging::ColorTransform xyz_to_scene_linear() {
  static const imaging::ColorPipeline color(kOcioConfig);
  return color.xyz_to_scene_linear();
}

}  // namespace arbor::tracer
