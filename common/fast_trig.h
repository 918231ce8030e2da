// Single-precision sine, cosine and arc tangent from fitted polynomials, for geometry that is
// stored in float (a leaf's axis and normal). glibc's sincosf and atan2f took 27 % of growing the
// weeping willow (issue 31, perf); these take a few nanoseconds, use no library call, and give the
// same bits wherever float arithmetic is IEEE (the build does not contract to FMA on x86-64).
//
// The coefficients were fitted here (minimax by iteratively reweighted least squares on Chebyshev
// nodes, numpy): atan(t) = t P(t²) on [0, 1], sin and cos on [−π/4, π/4]. Largest errors against
// double precision, measured by tests/common/fast_trig_test.cpp: 3.3e-7 rad for the arc tangent,
// 1.9e-7 for sine and cosine of angles up to 1000 rad in magnitude.
#pragma once

#include <algorithm>
#include <cmath>

namespace arbor {

// atan2(y, x) in (−π, π]; 0 for (0, 0).
inline float fast_atan2(float y, float x) {
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float hi = std::max(ax, ay), lo = std::min(ax, ay);
  // No branch (a loop of these vectorises): (0, 0) gives t = 0 and so ±0.
  const float t = lo / (hi > 0.0f ? hi : 1.0f), u = t * t, u2 = u * u, u4 = u2 * u2;
  // P(u) of degree 7 by Estrin's scheme: four short chains instead of one of eight steps.
  const float p01 = 0.99999934f - 0.33329859f * u, p23 = 0.19946566f - 0.13908629f * u;
  const float p45 = 0.096421972f - 0.055912327f * u, p67 = 0.021862958f - 0.0040545668f * u;
  const float p = (p01 + p23 * u2) + (p45 + p67 * u2) * u4;
  // The octant and half-plane by arithmetic rather than branches: their signs are random for
  // leaves, and a mispredicted branch costs more than the polynomial.
  const float swap = ay > ax ? 1.0f : 0.0f, back = x < 0.0f ? 1.0f : 0.0f;
  float r = p * t;
  r += swap * (1.57079633f - 2.0f * r);
  r += back * (3.14159265f - 2.0f * r);
  return std::copysign(r, y);
}

// sin(a) and cos(a) for |a| up to about 1e4 (reduced by quarter turns, π/2 split in two parts so
// that the reduction is exact to float precision).
inline void fast_sincos(float a, float& s, float& c) {
  // The nearest quarter turn, rounded by conversion to int (std::floor is a library call on x86-64
  // without SSE4.1).
  const float q = static_cast<float>(static_cast<int>(a * 0.636619772f + std::copysign(0.5f, a)));
  const float r = (a - q * 1.5703125f) - q * 4.83826794e-4f;
  const float r2 = r * r;
  float sr = -0.00019462117f;
  sr = sr * r2 + 0.0083315847f;
  sr = sr * r2 - 0.16666637f;
  sr = (sr * r2 + 1.0f) * r;
  float cr = -0.0013585921f;
  cr = cr * r2 + 0.041655026f;
  cr = cr * r2 - 0.49999857f;
  cr = cr * r2 + 1.0f;
  // Quadrant 0: (sr, cr); 1: (cr, −sr); 2: (−sr, −cr); 3: (−cr, sr), selected without branches.
  const int quadrant = static_cast<int>(q);
  const float odd = static_cast<float>(quadrant & 1);
  const float sin_sign = 1.0f - static_cast<float>(quadrant & 2);
  const float cos_sign = 1.0f - static_cast<float>((quadrant + 1) & 2);
  s = sin_sign * (sr + odd * (cr - sr));
  c = cos_sign * (cr + odd * (sr - cr));
}

}  // namespace arbor
