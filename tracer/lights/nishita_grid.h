// Grids shared by the atmosphere's tables (nishita_multiple.cpp, nishita_second.cpp): cos-zenith
// columns that follow a point's horizon, and the aerosols' phase function split into bands about
// a direction.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "tracer/lights/nishita.h"

namespace arbor::tracer::atmosphere {

// The cos zenith of the horizon seen from radius r (0 at the ground, negative above it).
inline double horizon_mu(double r) {
  const double q = kEarthRadius / r;
  return -std::sqrt(std::max(0.0, 1.0 - q * q));
}

// Columns over cos zenith μ at radius r, `half` above the horizon and `half` below, each dense at
// the horizon (as Bruneton & Neyret 2008's parameterisation): column j < half is
// μ_h + (1 − μ_h) x², column half + j is μ_h − (1 + μ_h) x², x = j / (half − 1), each just off
// the horizon so that the first column above sees the sky and the first below the ground.
inline double column_mu(double r, int j, int half) {
  const double h = horizon_mu(r);
  const double x = double(j % half) / (half - 1);
  if (j < half) return std::min(1.0, h + 1e-6 + (1.0 - h) * x * x);
  return std::max(-1.0, h - 1e-6 - (1.0 + h) * x * x);
}

// The column holding μ at radius r (the first of two to blend, within μ's half) and the weight of
// the second.
inline void column_of(double r, double mu, int half, int& j, double& f) {
  const double h = horizon_mu(r);
  const bool above = mu >= h;
  const double x =
      std::sqrt(std::clamp(above ? (mu - h) / (1.0 - h) : (h - mu) / (1.0 + h), 0.0, 1.0)) *
      (half - 1);
  const int i = std::min(half - 2, static_cast<int>(x));
  j = i + (above ? 0 : half);
  f = x - i;
}

// The trapezoid weight (in μ) of column j among its half's columns at radius r.
inline double column_weight(double r, int j, int half) {
  const int first = j < half ? 0 : half, k = j - first;
  return 0.5 * std::fabs(column_mu(r, first + std::min(half - 1, k + 1), half) -
                         column_mu(r, first + std::max(0, k - 1), half));
}

// The aerosols' phase function over 16 bands of the angle γ from a direction, γ = π x² with x
// uniform (band b holds x in [b, b + 1) / 16 and is represented by its midpoint): each band's
// exact share of the phase function.
constexpr int kMieBands = 16;
inline double mie_band_angle(int b) {
  const double x = (b + 0.5) / kMieBands;
  return kPi * x * x;
}
const std::array<double, kMieBands>& mie_band_weights();

}  // namespace arbor::tracer::atmosphere
