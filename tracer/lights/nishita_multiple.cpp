// Multiple scattering for the Nishita atmosphere: the table of Hillaire 2020 ("A Scalable and
// Production Ready Sky and Atmosphere Rendering Technique", EGSR, §5.5), per wavelength.
//
// At a point x (radius r) with the sun at cos zenith μ_s, the light that has scattered twice or
// more arrives nearly isotropically. Hillaire's approximation, used here as he states it:
//   L'(x, ω)  = ∫ T(x, y) σ_s(y) p_u S(y) dt + T(x, p) L_ground(p)                 (his eq. 6)
//     (along ω to the top of the atmosphere or the ground point p; S(y) the sunlight reaching y,
//      p_u = 1/4π the isotropic phase function, L_ground = albedo/π × the sun's irradiance at p)
//   L_2nd(x)  = ∫_Ω L'(x, ω) p_u dω                                                (eq. 7)
//   f_ms(x)   = ∫_Ω p_u ∫ T(x, y) σ_s(y) dt dω                                      (eq. 8)
//   ψ_ms(x)   = L_2nd / (1 − f_ms)     (every further order a geometric series)     (eq. 9)
// and a view ray gains σ_s(y) ψ_ms(y) at each of its points (eq. 11) besides single scattering.
//
// The aerosols scatter mostly forward (g = 0.76), and there Hillaire's isotropic second scattering
// is 9 % too bright at the zenith and 14 % too dark on the horizon towards the sun (dust 3, sun
// 40°, against sky_monte_carlo.h). So the orders ≥ 2 are computed in the δ-M scaled atmosphere
// (Wiscombe 1977, "The delta-M method", J. Atmos. Sci. 34): the fraction f = χ₂ = 0.656 of the
// aerosols' scattering that lies in the forward peak is counted as not scattered at all —
// extinction σ_t − f σ_m on every leg of the table's paths and on the view ray's way back to the
// observer, scattering σ_s − f σ_m in eq. 8 and eq. 11 — while each first scattering keeps the true
// phase functions. Single scattering keeps the true extinction towards the sun (the forward-
// scattered sunlight is not a sharper sun) and, like the multiple scattering, the scaled extinction
// from the scattering point to the observer (light scattered forward on the way stays in view).
// Measured against the simulation (bench/sky_bench, 7 directions, dust 3, ground 0.3): within
// 4.5–5.5 % at sun 40° and 60° (was 14 %), and within 16 % at 10°, where the horizon towards the
// sun lies inside its aureole.
// The integrals over Ω: 16 bands equal in cos θ × 16 azimuths; along each direction 24 steps
// spaced quadratically from x. The table: 32 altitudes (h = 60 km · u²) × 11 sun zenith angles,
// bilinear. Hillaire tabulates every μ_s, for any sun; a map has one sun, and a point of a view
// ray sees it at most 8° from where the observer does (a ray leaves the atmosphere within 873 km,
// 7.9° of the Earth's arc), so the columns span the observer's sun zenith angle ± 10°: a sixth of
// the cells. The cells are independent and computed in parallel, each the same on any thread.
#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include "tracer/lights/nishita.h"

namespace arbor::tracer {

using namespace atmosphere;

NishitaSky::Spectrum NishitaSky::scattering(const Depth& rho) const {
  Spectrum s{};
  for (int k = 0; k < kWavelengths; ++k)
    s[k] = beta_r_[k] * rho.rayleigh + (1.0 - forward_) * kMieScattering * rho.mie;
  return s;
}

NishitaSky::Spectrum NishitaSky::scaled_depth(const Depth& d) const {
  Spectrum tau{};
  for (int k = 0; k < kWavelengths; ++k)
    tau[k] = beta_r_[k] * d.rayleigh + mie_extinction_ * d.mie + sigma_o_[k] * d.ozone;
  return tau;
}

void NishitaSky::build_multiple_scattering() {
  constexpr int kBands = 16, kAzimuths = 16, kSteps = 24;
  constexpr double kIsotropic = 1.0 / (4.0 * kPi);
  const double albedo = a_.ground_albedo;
  const double theta_sun =
      std::acos(std::clamp(glm::dot(glm::normalize(glm::dvec3(0.0, 0.0, r0_)), sun_), -1.0, 1.0));
  ms_theta_lo_ = std::max(0.0, theta_sun - kMsSpan);
  ms_theta_hi_ = std::min(kPi, theta_sun + kMsSpan);
  ms_table_.assign(static_cast<size_t>(kMsRows) * kMsCols, Spectrum{});
  tbb::parallel_for(
      tbb::blocked_range<int>(0, kMsRows * kMsCols), [&](const tbb::blocked_range<int>& cells) {
        for (int cell = cells.begin(); cell < cells.end(); ++cell) {
          const int i = cell / kMsCols, j = cell % kMsCols;
          const double u = double(i) / (kMsRows - 1), r = kEarthRadius + kTop * u * u;
          const double mu_s =
              std::cos(ms_theta_lo_ + (ms_theta_hi_ - ms_theta_lo_) * j / (kMsCols - 1));
          const glm::dvec3 x(0.0, 0.0, r),
              sun(std::sqrt(std::max(0.0, 1.0 - mu_s * mu_s)), 0.0, mu_s);
          Spectrum second{}, transfer{};
          for (int b = 0; b < kBands; ++b) {
            const double mu = -1.0 + 2.0 * (b + 0.5) / kBands, s = std::sqrt(1.0 - mu * mu);
            for (int c = 0; c < kAzimuths; ++c) {
              const double phi = 2.0 * kPi * (c + 0.5) / kAzimuths;
              const glm::dvec3 w(s * std::cos(phi), s * std::sin(phi), mu);
              const bool ground = hits_earth(r, mu);
              const double length =
                  ground ? -r * mu - std::sqrt(std::max(0.0, r * r * (mu * mu - 1.0) +
                                                                 kEarthRadius * kEarthRadius))
                         : to_top(r, mu);
              // Light travelling from y to x (along −ω) left the sun's beam at cos θ = ω · sun.
              const double cs = glm::dot(w, sun), pr = rayleigh_phase(cs), pm = mie_phase(cs);
              Depth seen;
              Spectrum lp{}, fp{};
              for (int t_i = 0; t_i < kSteps; ++t_i) {
                const double a = double(t_i) / kSteps, e = double(t_i + 1) / kSteps;
                const double t = length * 0.25 * (a + e) * (a + e), dt = length * (e * e - a * a);
                const glm::dvec3 y = x + w * t;
                const double ry = glm::length(y);
                const Depth rho = densities(ry);
                const Depth to_y{seen.rayleigh + 0.5 * rho.rayleigh * dt,
                                 seen.mie + 0.5 * rho.mie * dt, seen.ozone + 0.5 * rho.ozone * dt};
                seen.rayleigh += rho.rayleigh * dt;
                seen.mie += rho.mie * dt;
                seen.ozone += rho.ozone * dt;
                const Spectrum tx = scaled_depth(to_y), ss = scattering(rho);
                const Depth to_sun = depth_to_sun(ry, glm::dot(y, sun) / ry);
                const bool lit = std::isfinite(to_sun.rayleigh);
                const Spectrum ts = lit ? scaled_depth(to_sun) : Spectrum{};
                for (int k = 0; k < kWavelengths; ++k) {
                  const double view = std::exp(-tx[k]) * dt;
                  fp[k] += view * ss[k];
                  // The sunlight scattered at y towards x, by the true phase functions.
                  if (lit)
                    lp[k] += view *
                             (beta_r_[k] * rho.rayleigh * pr + kMieScattering * rho.mie * pm) *
                             std::exp(-ts[k]);
                }
              }
              if (ground && albedo > 0.0) {
                // The ground point: lit by the sun through the atmosphere, reflecting Lambertian.
                const glm::dvec3 p = x + w * length;
                const double mu_ground = glm::dot(glm::normalize(p), sun);
                if (mu_ground > 0.0) {
                  const Spectrum tx = scaled_depth(seen);
                  const Spectrum ts = scaled_depth(depth_to_sun(kEarthRadius, mu_ground));
                  for (int k = 0; k < kWavelengths; ++k)
                    lp[k] += std::exp(-tx[k]) * albedo / kPi * mu_ground * std::exp(-ts[k]);
                }
              }
              for (int k = 0; k < kWavelengths; ++k) {
                second[k] += lp[k] * kIsotropic;
                transfer[k] += fp[k] * kIsotropic;
              }
            }
          }
          const double d_omega = 4.0 * kPi / (kBands * kAzimuths);
          Spectrum& psi = ms_table_[static_cast<size_t>(i) * kMsCols + j];
          for (int k = 0; k < kWavelengths; ++k)
            psi[k] = second[k] * d_omega / (1.0 - transfer[k] * d_omega);
        }
      });
}

NishitaSky::Spectrum NishitaSky::multiple_scattering(double r, double mu_sun) const {
  const double u = std::sqrt(std::clamp((r - kEarthRadius) / kTop, 0.0, 1.0)) * (kMsRows - 1);
  const double v = std::clamp((std::acos(std::clamp(mu_sun, -1.0, 1.0)) - ms_theta_lo_) /
                                  (ms_theta_hi_ - ms_theta_lo_),
                              0.0, 1.0) *
                   (kMsCols - 1);
  const int i = std::min(kMsRows - 2, static_cast<int>(u)),
            j = std::min(kMsCols - 2, static_cast<int>(v));
  const double fu = u - i, fv = v - j;
  const Spectrum& a = ms_table_[static_cast<size_t>(i) * kMsCols + j];
  const Spectrum& b = ms_table_[static_cast<size_t>(i) * kMsCols + j + 1];
  const Spectrum& c = ms_table_[static_cast<size_t>(i + 1) * kMsCols + j];
  const Spectrum& d = ms_table_[static_cast<size_t>(i + 1) * kMsCols + j + 1];
  Spectrum out{};
  for (int k = 0; k < kWavelengths; ++k)
    out[k] = (1.0 - fu) * ((1.0 - fv) * a[k] + fv * b[k]) + fu * ((1.0 - fv) * c[k] + fv * d[k]);
  return out;
}

}  // namespace arbor::tracer
