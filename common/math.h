// Constants and small functions every layer shares: π, degrees, luminance, RGB triples as read
// from files, the concentric disk map.
#pragma once

#include <array>
#include <cmath>

#include <glm/vec2.hpp>

namespace arbor {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 6.283185307179586;
constexpr double radians(double degrees) { return degrees * (kPi / 180.0); }
constexpr double degrees(double radians) { return radians * (180.0 / kPi); }

// Rec. 709 luminance of linear RGB, in the precision of the arguments.
template <class T>
constexpr T luminance(T r, T g, T b) {
  return T(0.2126) * r + T(0.7152) * g + T(0.0722) * b;
}

// A colour as a file states it (scene-linear RGB, double precision).
using Rgb = std::array<double, 3>;

// Uniform point on the unit disk from [0,1)² (Shirley & Chiu 1997, the concentric map), in the
// precision of the arguments (the camera's lens in float, BSDF sampling in double).
template <class T>
glm::vec<2, T, glm::defaultp> concentric_disk(T ux, T uy) {
  const T a = T(2) * ux - T(1), b = T(2) * uy - T(1);
  if (a == T(0) && b == T(0)) return {T(0), T(0)};
  const T quarter_pi = T(kPi / 4.0);
  T r, phi;
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    phi = quarter_pi * (b / a);
  } else {
    r = b;
    phi = T(2) * quarter_pi - quarter_pi * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

}  // namespace arbor
