// Orthonormal frames: the stems' and leaves' Frame with its rotations (right-handed, angles in
// radians unless a name says degrees), and the shading frame around a surface normal.
#pragma once

#include <cmath>

#include <glm/vec3.hpp>
#include <glm/geometric.hpp>

#include "common/math.h"

namespace arbor {

using Vec3 = glm::dvec3;

// Rotates v about the unit axis by the angle whose cosine and sine are c and s (Rodrigues'
// formula).
inline Vec3 rotate(const Vec3& v, const Vec3& axis, double c, double s) {
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}
inline glm::vec3 rotate(const glm::vec3& v, const glm::vec3& axis, float c, float s) {
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0f - c);
}
// Rotates v about the unit axis by angle.
inline Vec3 rotate(const Vec3& v, const Vec3& axis, double angle) {
  return rotate(v, axis, std::cos(angle), std::sin(angle));
}

// A local coordinate system: z along a stem (or leaf), y and x across it.
struct Frame {
  Vec3 x{1, 0, 0};
  Vec3 y{0, 1, 0};
  Vec3 z{0, 0, 1};

  // Rotation about the frame's own x axis: positive angles turn z toward -y.
  Frame rotated_x(double angle) const {
    const double c = std::cos(angle), s = std::sin(angle);  // once for both axes
    return {x, rotate(y, x, c, s), rotate(z, x, c, s)};
  }
  // Rotation about the frame's own y axis: positive angles turn z toward +x.
  Frame rotated_y(double angle) const {
    const double c = std::cos(angle), s = std::sin(angle);
    return {rotate(x, y, c, s), y, rotate(z, y, c, s)};
  }
  // Rotation about the frame's own z axis: positive angles turn x toward +y.
  Frame rotated_z(double angle) const {
    const double c = std::cos(angle), s = std::sin(angle);
    return {rotate(x, z, c, s), rotate(y, z, c, s), z};
  }
  // Rotation of the whole frame about an axis given in the parent coordinates.
  Frame rotated_about(const Vec3& axis, double angle) const {
    const double c = std::cos(angle), s = std::sin(angle);
    return {rotate(x, axis, c, s), rotate(y, axis, c, s), rotate(z, axis, c, s)};
  }
  // Re-orthonormalises after many rotations (Gram-Schmidt from z, then y).
  Frame orthonormalized() const {
    const Vec3 nz = glm::normalize(z);
    const Vec3 nx = glm::normalize(glm::cross(y, nz));
    return {nx, glm::cross(nz, nx), nz};
  }
};

// An orthonormal shading frame around a unit normal n (its z), for converting directions to and
// from a BSDF's local coordinates (Duff et al. 2017, "Building an orthonormal basis, revisited").
struct ShadingFrame {
  glm::vec3 x, y, z;
  explicit ShadingFrame(const glm::vec3& n) : z(n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
    x = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    y = glm::vec3(b, sign + n.y * n.y * a, -n.y);
  }
  // World → local (double, as the BSDFs take it) and back.
  glm::dvec3 local(const glm::vec3& v) const {
    return {glm::dot(v, x), glm::dot(v, y), glm::dot(v, z)};
  }
  glm::vec3 world(const glm::dvec3& v) const {
    return x * static_cast<float>(v.x) + y * static_cast<float>(v.y) + z * static_cast<float>(v.z);
  }
};

}  // namespace arbor
