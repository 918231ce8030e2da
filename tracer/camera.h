// Pinhole and thin-lens camera (vertical field of view, focus distance, aperture radius).
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/render_input.h"
#include "tracer/ray.h"

namespace arbor::tracer {

class Camera {
 public:
  Camera(const spec::CameraDesc& camera, int width, int height);
  // A ray through film position (x, y) in pixels (0,0 top-left corner), `lens` in [0,1)².
  Ray generate(glm::vec2 film, glm::vec2 lens) const;
  const glm::vec3& forward() const { return forward_; }

 private:
  glm::vec3 origin_, forward_, right_, up_;
  float tan_half_ = 0.0f, aspect_ = 1.0f, aperture_ = 0.0f, focus_ = 1.0f;
  int width_ = 1, height_ = 1;
};

}  // namespace arbor::tracer
