// A scene description built (scene/) and put into Embree (tracer/) in one step, as `arbor render`
// does, with arbor's own OCIO config.
#pragma once

#include <memory>
#include <string>

#include "imaging/color.h"
#include "scene/scene.h"
#include "tracer/embree/embree_device.h"
#include "tracer/embree/world.h"

namespace arbor::trace {

inline const std::string kOcioConfig = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";

struct TestWorld {
  TestWorld(const SceneDesc& desc, const EmbreeDevice& device)
      : scene(build_scene(desc, kOcioConfig)), world(*scene, device) {}
  std::unique_ptr<const Scene> scene;
  World world;
};

// The sky's CIE XYZ → scene_linear through arbor's config.
inline ColorTransform xyz_to_scene_linear() {
  static const ColorPipeline color(kOcioConfig);
  return color.xyz_to_scene_linear();
}

}  // namespace arbor::trace
