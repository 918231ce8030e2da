#include "generator/models/weber_penn/weber_penn_leaves.h"

#include <cmath>

#include "common/fast_trig.h"
#include "common/frame.h"

namespace arbor::generator::wp {

void orient_toward_light(float bend, float at_x, float at_y, glm::vec3& axis, glm::vec3& normal) {
  if (bend == 0.0f) return;
  if (at_x != 0.0f || at_y != 0.0f) {
    const float nx = normal.x, ny = normal.y;
    const float theta_bend = nx == 0.0f && ny == 0.0f
                                 ? fast_atan2(at_y, at_x)
                                 : fast_atan2(nx * at_y - ny * at_x, nx * at_x + ny * at_y);
    float c = 1.0f, s = 0.0f;
    fast_sincos(bend * theta_bend, s, c);
    // About the vertical: x toward y, z unchanged.
    axis = glm::vec3(c * axis.x - s * axis.y, s * axis.x + c * axis.y, axis.z);
    normal = glm::vec3(c * normal.x - s * normal.y, s * normal.x + c * normal.y, normal.z);
  }
  const float horizontal = std::sqrt(normal.x * normal.x + normal.y * normal.y);
  if (horizontal < 1e-12f) return;
  const float phi_bend = fast_atan2(horizontal, normal.z);
  const glm::vec3 across = glm::vec3(normal.y, -normal.x, 0.0f) / horizontal;  // normal × up
  float c = 1.0f, s = 0.0f;
  fast_sincos(bend * phi_bend, s, c);
  axis = rotate(axis, across, c, s);
  normal = rotate(normal, across, c, s);
}

void orient_leaves(const std::vector<PendingLeaf>& pending, float bend, std::vector<Leaf>& leaves) {
  for (std::size_t i = 0; i < pending.size(); ++i) {
    const PendingLeaf& pl = pending[i];
    float ct = 1.0f, st = 0.0f, cd = 1.0f, sd = 0.0f;
    fast_sincos(pl.turn, st, ct);
    fast_sincos(pl.down, sd, cd);
    // Frame::rotated_z then rotated_x, written out for the two axes a leaf keeps.
    const glm::vec3 turned_y = ct * pl.y - st * pl.x;
    Leaf& leaf = leaves[i];
    leaf.axis = cd * pl.z - sd * turned_y;
    leaf.normal = cd * turned_y + sd * pl.z;
    orient_toward_light(bend, leaf.position.x, leaf.position.y, leaf.axis, leaf.normal);
  }
}

}  // namespace arbor::generator::wp
