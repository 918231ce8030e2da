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
// The integrals over Ω: 16 bands equal in cos θ × 16 azimuths; along each direction 24 steps
// spaced quadratically from x. The table: 32 altitudes (h = 60 km · u²) × 64 values of μ_s,
// bilinear.
#include <cmath>

#include <glm/geometric.hpp>

#include "tracer/lights/nishita.h"

namespace arbor::tracer {

using namespace atmosphere;

NishitaSky::Spectrum NishitaSky::scattering(const Depth& rho) const {
  Spectrum s{};
  for (int k = 0; k < kWavelengths; ++k)
    s[k] = beta_r_[k] * rho.rayleigh + kMieScattering * rho.mie;
  return s;
}

void NishitaSky::build_multiple_scattering() {
  constexpr int kBands = 16, kAzimuths = 16, kSteps = 24;
  constexpr double kIsotropic = 1.0 / (4.0 * kPi);
  const double albedo = a_.ground_albedo;
  ms_table_.assign(static_cast<size_t>(kMsRows) * kMsCols, Spectrum{});
  for (int i = 0; i < kMsRows; ++i) {
    const double u = double(i) / (kMsRows - 1), r = kEarthRadius + kTop * u * u;
    for (int j = 0; j < kMsCols; ++j) {
      const double mu_s = -1.0 + 2.0 * j / (kMsCols - 1);
      const glm::dvec3 x(0.0, 0.0, r), sun(std::sqrt(std::max(0.0, 1.0 - mu_s * mu_s)), 0.0, mu_s);
      Spectrum second{}, transfer{};
      for (int b = 0; b < kBands; ++b) {
        const double mu = -1.0 + 2.0 * (b + 0.5) / kBands, s = std::sqrt(1.0 - mu * mu);
        for (int c = 0; c < kAzimuths; ++c) {
          const double phi = 2.0 * kPi * (c + 0.5) / kAzimuths;
          const glm::dvec3 w(s * std::cos(phi), s * std::sin(phi), mu);
          const bool ground = hits_earth(r, mu);
          const double length =
              ground ? -r * mu - std::sqrt(std::max(
                                     0.0, r * r * (mu * mu - 1.0) + kEarthRadius * kEarthRadius))
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
            const Depth to_y{seen.rayleigh + 0.5 * rho.rayleigh * dt, seen.mie + 0.5 * rho.mie * dt,
                             seen.ozone + 0.5 * rho.ozone * dt};
            seen.rayleigh += rho.rayleigh * dt;
            seen.mie += rho.mie * dt;
            seen.ozone += rho.ozone * dt;
            const Spectrum tx = optical_depth(to_y), ss = scattering(rho);
            const Depth to_sun = depth_to_sun(ry, glm::dot(y, sun) / ry);
            const bool lit = std::isfinite(to_sun.rayleigh);
            const Spectrum ts = lit ? optical_depth(to_sun) : Spectrum{};
            for (int k = 0; k < kWavelengths; ++k) {
              const double view = std::exp(-tx[k]) * dt;
              fp[k] += view * ss[k];
              // The sunlight scattered at y towards x, by the true phase functions.
              if (lit)
                lp[k] += view * (beta_r_[k] * rho.rayleigh * pr + kMieScattering * rho.mie * pm) *
                         std::exp(-ts[k]);
            }
          }
          if (ground && albedo > 0.0) {
            // The ground point: lit by the sun through the atmosphere, reflecting Lambertian.
            const glm::dvec3 p = x + w * length;
            const double mu_ground = glm::dot(glm::normalize(p), sun);
            if (mu_ground > 0.0) {
              const Spectrum tx = optical_depth(seen);
              const Spectrum ts = optical_depth(depth_to_sun(kEarthRadius, mu_ground));
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
  }
}

NishitaSky::Spectrum NishitaSky::multiple_scattering(double r, double mu_sun) const {
  const TableCell cell = table_cell(r, mu_sun, kMsRows, kMsCols);
  const int i = cell.i, j = cell.j;
  const double fu = cell.fu, fv = cell.fv;
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
