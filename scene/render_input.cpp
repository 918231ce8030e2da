#include "scene/render_input.h"

#include "scene/terrain.h"

namespace arbor::scene {

RenderInput render_input(const spec::SceneDesc& d) {
  // A camera standing on the terrain needs the terrain (built here once more: the scene's own is
  // built later, by build_scene). The reader checked the camera; one made in code, or placed on
  // the terrain, is checked here.
  spec::CameraDesc camera =
      d.camera.above_ground ? placed_camera(d.camera, Terrain(d.terrain)) : d.camera;
  spec::check_camera(camera);
  return {d.path, d.render, camera, d.sun, d.sky, d.output};
}

}  // namespace arbor::scene
