// Everything the tracer needs besides the built geometry: the render settings, the camera, the
// sun and the sky, and the output specification, as the scene description states them
// (spec/scene_desc.h, whose choices are already enums, Integrator and SkyModel), the camera
// placed. The tracer never reads a file, compares a string, or meets an unknown choice.
#pragma once

#include <string>

#include "spec/scene_desc.h"
#include "imaging/output_spec.h"

namespace arbor::scene {

struct RenderInput {
  std::string scene;  // the scene file, for messages and metadata
  spec::RenderSettings render;
  spec::CameraDesc camera;  // placed on the terrain when it asks to be, and checked
  spec::SunDesc sun;
  spec::SkyDesc sky;
  imaging::OutputSpec output;
};

// The typed input of the scene description `desc` (its choices already checked by the reader);
// InputError when its camera cannot form an image.
RenderInput render_input(const spec::SceneDesc& desc);

}  // namespace arbor::scene
