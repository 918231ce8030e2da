#include "scene/frame.h"

#include <cstdint>
#include <string>

#include "common/error.h"
#include "common/rng.h"

namespace arbor::scene {

void apply_frame(spec::SceneDesc& scene, std::optional<int> frame) {
  const bool numbered = scene.output.exr.find('#') != std::string::npos ||
                        scene.output.png.find('#') != std::string::npos;
  if (!frame) {
    if (numbered) {
      throw InputError({},
                       "the output " +
                           (scene.output.exr.find('#') != std::string::npos ? scene.output.exr
                                                                            : scene.output.png) +
                           " names a frame number (#): give --frame N");
    }
    return;
  }
  const spec::AnimationDesc& an = scene.animation;
  if (an.frames == 0) {
    throw InputError({scene.path, 0, 0},
                     "--frame " + std::to_string(*frame) + ": the scene has no [animation] table");
  }
  if (*frame < 0 || *frame >= an.frames) {
    throw InputError(an.where, "--frame " + std::to_string(*frame) +
                                   " is outside the animation's frames 0 to " +
                                   std::to_string(an.frames - 1));
  }
  scene.clock = *frame / an.fps;
  if (!an.pin_seed)
    scene.render.seed = derive_key(scene.render.seed, static_cast<std::uint64_t>(*frame));
  scene.output.exr = spec::frame_path(scene.output.exr, *frame);
  scene.output.png = spec::frame_path(scene.output.png, *frame);
}

}  // namespace arbor::scene
