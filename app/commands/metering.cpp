// Auto exposure metered once per scene: on the render's world, or on frame 0 of an animation.
#include "app/commands/metering.h"

#include <cstdio>
#include <memory>

#include "scene/scene.h"
#include "tracer/exposure.h"

namespace arbor::app {

bool meters_frame_zero(const spec::SceneDesc& scene, const scene::RenderInput& input) {
  return input.camera.auto_exposure && scene.clock != 0.0;
}

double frame_zero_exposure(const spec::SceneDesc& scene, const scene::RenderInput& input,
                           const tracer::Sky& sky, const MeterBuild& how) {
  spec::SceneDesc still = scene;
  still.clock = 0.0;
  const std::unique_ptr<const scene::Scene> built =
      scene::build_scene(still, how.ocio_config, nullptr, how.geometry_budget, how.threads);
  const tracer::World world(*built, *how.device);
  return tracer::metered_exposure(input, world, sky);
}

scene::RenderInput with_scene_exposure(const spec::SceneDesc& scene,
                                       const scene::RenderInput& input, const tracer::World& world,
                                       const tracer::Sky& sky, double frame_zero) {
  if (!input.camera.auto_exposure) return input;
  scene::RenderInput metered = input;
  const bool zero = meters_frame_zero(scene, input);
  metered.camera.exposure = zero ? frame_zero : tracer::metered_exposure(input, world, sky);
  std::fprintf(stderr, "arbor: metered exposure %+.2f stops%s\n", metered.camera.exposure,
               zero ? " (on the animation's frame 0, as every frame)" : "");
  return metered;
}

}  // namespace arbor::app
