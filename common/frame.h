// Orthonormal frames and rotations (right-handed, angles in radians unless a name says degrees).
#pragma once

#include <cmath>

#include <glm/vec3.hpp>
#include <glm/geometric.hpp>

namespace arbor {

using Vec3 = glm::dvec3;

constexpr double kPi = 3.14159265358979323846;
constexpr double radians(double degrees) { return degrees * (kPi / 180.0); }
constexpr double degrees(double radians) { return radians * (180.0 / kPi); }

// Rotates v about the unit axis by angle (Rodrigues' formula).
inline Vec3 rotate(const Vec3& v, const Vec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}

// A local coordinate system: z along a stem (or leaf), y and x across it.
struct Frame {
  Vec3 x{1, 0, 0};
  Vec3 y{0, 1, 0};
  Vec3 z{0, 0, 1};

  // Rotation about the frame's own x axis: positive angles turn z toward -y.
  Frame rotated_x(double angle) const { return {x, rotate(y, x, angle), rotate(z, x, angle)}; }
  // Rotation about the frame's own y axis: positive angles turn z toward +x.
  Frame rotated_y(double angle) const { return {rotate(x, y, angle), y, rotate(z, y, angle)}; }
  // Rotation about the frame's own z axis: positive angles turn x toward +y.
  Frame rotated_z(double angle) const { return {rotate(x, z, angle), rotate(y, z, angle), z}; }
  // Rotation of the whole frame about an axis given in the parent coordinates.
  Frame rotated_about(const Vec3& axis, double angle) const {
    return {rotate(x, axis, angle), rotate(y, axis, angle), rotate(z, axis, angle)};
  }
  // Re-orthonormalises after many rotations (Gram-Schmidt from z, then y).
  Frame orthonormalized() const {
    const Vec3 nz = glm::normalize(z);
    const Vec3 nx = glm::normalize(glm::cross(y, nz));
    return {nx, glm::cross(nz, nx), nz};
  }
};

}  // namespace arbor
