// Camera ray generation.
#include "tracer/camera.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "common/math.h"

namespace arbor::tracer {

Camera::Camera(const spec::CameraDesc& d, int width, int height) : width_(width), height_(height) {
  origin_ = glm::vec3(d.position[0], d.position[1], d.position[2]);
  const glm::vec3 target(d.look_at[0], d.look_at[1], d.look_at[2]);
  const glm::vec3 up(d.up[0], d.up[1], d.up[2]);
  forward_ = glm::normalize(target - origin_);
  right_ = glm::normalize(glm::cross(forward_, up));
  up_ = glm::cross(right_, forward_);
  tan_half_ = static_cast<float>(std::tan(0.5 * d.fov * kPi / 180.0));
  aspect_ = static_cast<float>(width) / static_cast<float>(height);
  aperture_ = static_cast<float>(d.aperture_radius);
  focus_ = static_cast<float>(d.focus_distance);
}

Ray Camera::generate(glm::vec2 film, glm::vec2 lens) const {
  const float sx = (2.0f * film.x / width_ - 1.0f) * tan_half_ * aspect_;
  const float sy = (1.0f - 2.0f * film.y / height_) * tan_half_;
  glm::vec3 dir = glm::normalize(forward_ + right_ * sx + up_ * sy);
  Ray ray;
  ray.origin = origin_;
  if (aperture_ > 0.0f) {
    // Points at the focus distance (along the view axis) stay sharp.
    const glm::vec3 focal = origin_ + dir * (focus_ / glm::dot(dir, forward_));
    const glm::vec2 d = concentric_disk(lens.x, lens.y) * aperture_;
    ray.origin = origin_ + right_ * d.x + up_ * d.y;
    dir = glm::normalize(focal - ray.origin);
  }
  ray.direction = dir;
  return ray;
}

}  // namespace arbor::tracer
