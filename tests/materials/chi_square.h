// A chi-square test of a BSDF's sampling against its own pdf, over both hemispheres: directions
// are binned in (cos θ, φ) cells; each cell's expected count is the pdf integrated over the cell
// numerically (so the test checks sample() against pdf(), whatever the BSDF).
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "common/rng.h"
#include "materials/bsdf.h"
#include "common/math.h"

namespace arbor::materials::testing {

struct ChiSquareResult {
  double chi2 = 0.0;
  int degrees_of_freedom = 0;
};

inline ChiSquareResult chi_square(const std::function<BsdfSample(Rng&)>& sample,
                                  const std::function<double(const Dir&)>& pdf, int samples,
                                  std::uint64_t seed, int n_cos = 20, int n_phi = 16, int sub = 8) {
  // n_cos cells over cos θ in [-1, 1], n_phi over φ; a peaked lobe wants more cells and a finer
  // sub-grid for the cells' integrals.
  std::vector<double> observed(n_cos * n_phi, 0.0), expected(n_cos * n_phi, 0.0);
  Rng rng(seed);
  for (int i = 0; i < samples; ++i) {
    const BsdfSample s = sample(rng);
    if (s.pdf <= 0.0) continue;
    const int c = std::min(n_cos - 1, static_cast<int>((s.wi.z + 1.0) * 0.5 * n_cos));
    double phi = std::atan2(s.wi.y, s.wi.x);
    if (phi < 0.0) phi += 2.0 * kPi;
    const int p = std::min(n_phi - 1, static_cast<int>(phi / (2.0 * kPi) * n_phi));
    observed[c * n_phi + p] += 1.0;
  }
  // ∫ pdf dω over a cell = ∫∫ pdf d(cos θ) dφ: midpoint rule on a sub × sub grid.
  for (int c = 0; c < n_cos; ++c) {
    for (int p = 0; p < n_phi; ++p) {
      double integral = 0.0;
      for (int a = 0; a < sub; ++a) {
        for (int b = 0; b < sub; ++b) {
          const double z = -1.0 + 2.0 * (c + (a + 0.5) / sub) / n_cos;
          const double phi = 2.0 * kPi * (p + (b + 0.5) / sub) / n_phi;
          const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
          integral += pdf(Dir(r * std::cos(phi), r * std::sin(phi), z));
        }
      }
      expected[c * n_phi + p] =
          integral / double(sub * sub) * (2.0 / n_cos) * (2.0 * kPi / n_phi) * samples;
    }
  }
  ChiSquareResult result;
  for (std::size_t k = 0; k < observed.size(); ++k) {
    if (expected[k] < 5.0) continue;  // pooled out: too few expected for the χ² approximation
    const double d = observed[k] - expected[k];
    result.chi2 += d * d / expected[k];
    ++result.degrees_of_freedom;
  }
  --result.degrees_of_freedom;
  return result;
}

// ∫ f dω over the upper hemisphere (z > 0) by the midpoint rule on an n × 4n grid in (cos θ, φ),
// independent of any BSDF's sampling.
inline double hemisphere_integral(const std::function<double(const Dir&)>& f, int n = 400) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double z = (i + 0.5) / n, r = std::sqrt(std::max(0.0, 1.0 - z * z));
    for (int j = 0; j < 4 * n; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / (4 * n);
      sum += f(Dir(r * std::cos(phi), r * std::sin(phi), z));
    }
  }
  return sum * (1.0 / n) * (2.0 * kPi / (4 * n));
}

// The 99.9th percentile of χ² with k degrees of freedom (Wilson–Hilferty).
inline double chi_square_critical(int k) {
  const double z = 3.0902;  // standard normal 99.9 %
  const double h = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - h + z * std::sqrt(h), 3.0);
}

}  // namespace arbor::materials::testing
