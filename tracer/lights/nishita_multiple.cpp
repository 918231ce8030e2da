// The orders of scattering beyond the second for the Nishita atmosphere (the second is exact:
// nishita_second.cpp), after Hillaire 2020 ("A Scalable and Production Ready Sky and Atmosphere
// Rendering Technique", EGSR, §5.5), with the ground's reflections of scattered light added to his
// series and the last scattering towards the view made anisotropic. Per wavelength.
//
// Notation: at a point x (radius r, the sun at cos zenith μ_s), A_n(x) is the mean radiance of
// order n − 1 there, so that σ_s A_n is the (isotropic part of the) source of order n;
// F(x, ω) = ∫ T σ_s dt along ω to the top or the ground (what a unit isotropic source all along
// the ray sends back to x); D₁ the irradiance the once-scattered skylight gives the ground; G the
// irradiance at the ground per unit of isotropic source everywhere above it (= ∫ μ F dω over the
// sky there); a the ground's albedo.
//   A_2 = (1/4π) ∫ L₁ dω        (Hillaire's L_2nd, eq. 7: L₁ the sunlight scattered once by the
//                                 true phase functions, or reflected once by the ground)
//   A_3 = A_2 f_air + g_D       f_air = (1/4π) ∫ F dω (his eq. 8), g_D = (1/4π) ∫ T a/π D₁ dω
//                                 over the directions that meet the ground: the ground's
//                                 reflection of the once-scattered skylight, which Hillaire omits
//   A_{n+1} = A_n (f_air + g_G) for n ≥ 3, g_G = (1/4π) ∫ T a/π G dω over the same directions
//   ψ = A_2 + A_3 / (1 − f_air − g_G)         (every order from the second, eq. 9 extended)
// Aerial perspective scatters ψ isotropically (σ_s ψ, eq. 11). The sky (third_scattering) takes
// the orders from the third on towards the view ω through the true phase functions: the radiance
// of orders ≥ 2 arriving at x from ω' is ψ F(x, ω') in the air and T a/π (D₁ + ψ G) from the
// ground, so the source is Σ_i σ_i [ψ F_i(x, ω) + (D₁ + ψ G) F_gnd,i(x, ω)] with F_i = ∫ p_i F dω'
// — a function of altitude and the view's zenith alone (the sun enters only through ψ and D₁).
// Measured against the simulation (bench/sky_bench accuracy; docs/rendering.md has the table).
//
// The integrals over Ω: 16 bands equal in cos θ × 16 azimuths; along each direction 24 steps
// spaced quadratically from x. The ψ table: 32 altitudes (h = 60 km · u²) × 11 sun zenith angles,
// bilinear. A map has one sun, and a point of a view ray sees it at most 8° from where the
// observer does (a ray leaves the atmosphere within 873 km, 7.9° of the Earth's arc), so the
// columns span the observer's sun zenith angle ± 10°. The F tables: the same altitudes × 64 view
// cos-zenith columns that follow the horizon (nishita_grid.h). Cells are independent and computed
// in parallel, each the same on any thread.
#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include "tracer/lights/nishita.h"
#include "tracer/lights/nishita_grid.h"

namespace arbor::tracer {

using namespace atmosphere;

namespace {

constexpr int kSteps = 24, kBands = 16, kAzimuths = 16, kAround = 16;
constexpr double kIsotropic = 1.0 / (4.0 * kPi);

double ms_radius(int i, int rows) {
  const double u = double(i) / (rows - 1);
  return kEarthRadius + kTop * u * u;
}

}  // namespace

NishitaSky::Spectrum NishitaSky::scattering(const Depth& rho) const {
  Spectrum s{};
  for (int k = 0; k < kWavelengths; ++k)
    s[k] = beta_r_[k] * rho.rayleigh + kMieScattering * rho.mie;
  return s;
}

double NishitaSky::ray_length(double r, double mu) {
  if (!hits_earth(r, mu)) return to_top(r, mu);
  return std::max(0.0, -r * mu - std::sqrt(std::max(
                                     0.0, r * r * (mu * mu - 1.0) + kEarthRadius * kEarthRadius)));
}

NishitaSky::Depth NishitaSky::march(const glm::dvec3& x, const glm::dvec3& w, const glm::dvec3* sun,
                                    Spectrum* single, Spectrum& transfer) const {
  const double r = glm::length(x), mu = glm::dot(x, w) / r, length = ray_length(r, mu);
  // Light travelling from y to x (along −ω) left the sun's beam at cos θ = ω · sun.
  const double cs = sun ? glm::dot(w, *sun) : 0.0, pr = rayleigh_phase(cs), pm = mie_phase(cs);
  Depth seen;
  for (int t_i = 0; t_i < kSteps; ++t_i) {
    const double a = double(t_i) / kSteps, e = double(t_i + 1) / kSteps;
    const double t = length * 0.25 * (a + e) * (a + e), dt = length * (e * e - a * a);
    const glm::dvec3 y = x + w * t;
    const double ry = glm::length(y);
    const Depth rho = densities(ry);
    const Depth to_y = step_depth(seen, rho, dt);
    const Spectrum tx = optical_depth(to_y), ss = scattering(rho);
    Spectrum tv;
    for (int k = 0; k < kWavelengths; ++k) {
      tv[k] = std::exp(-tx[k]) * dt;
      transfer[k] += tv[k] * ss[k];
    }
    Spectrum ts;
    if (!single || !sun_transmittance(ry, glm::dot(y, *sun) / ry, ts)) continue;
    for (int k = 0; k < kWavelengths; ++k)
      (*single)[k] +=
          tv[k] * ts[k] * (beta_r_[k] * rho.rayleigh * pr + kMieScattering * rho.mie * pm);
  }
  return seen;
}

void NishitaSky::build_multiple_scattering() {
  const double albedo = a_.ground_albedo;
  const double theta_sun =
      std::acos(std::clamp(glm::dot(glm::normalize(glm::dvec3(0.0, 0.0, r0_)), sun_), -1.0, 1.0));
  ms_theta_lo_ = std::max(0.0, theta_sun - kMsSpan);
  ms_theta_hi_ = std::min(kPi, theta_sun + kMsSpan);
  auto sun_of_column = [&](int j) {
    const double mu_s = std::cos(ms_theta_lo_ + (ms_theta_hi_ - ms_theta_lo_) * j / (kMsCols - 1));
    return glm::dvec3(std::sqrt(std::max(0.0, 1.0 - mu_s * mu_s)), 0.0, mu_s);
  };
  // G and D₁ at the ground: ∫ μ F dω and ∫ μ L₁ dω over the sky (L₁ for each sun column).
  ground_transfer_ = Spectrum{};
  ground_sky_.assign(kMsCols, Spectrum{});
  const glm::dvec3 foot(0.0, 0.0, kEarthRadius);
  for (int b = 0; b < kBands; ++b) {
    const double mu = (b + 0.5) / kBands, s = std::sqrt(1.0 - mu * mu);
    for (int c = 0; c < kAzimuths; ++c) {
      const double phi = kPi * (c + 0.5) / kAzimuths;  // a half: both are symmetric
      const glm::dvec3 w(s * std::cos(phi), s * std::sin(phi), mu);
      const double weight = mu * 2.0 * kPi / (kBands * kAzimuths);
      Spectrum transfer{};
      march(foot, w, nullptr, nullptr, transfer);
      for (int k = 0; k < kWavelengths; ++k) ground_transfer_[k] += weight * transfer[k];
      for (int j = 0; j < kMsCols; ++j) {
        const glm::dvec3 sun = sun_of_column(j);
        Spectrum single{}, unused{};
        march(foot, w, &sun, &single, unused);
        for (int k = 0; k < kWavelengths; ++k) ground_sky_[j][k] += weight * single[k];
      }
    }
  }
  if (albedo <= 0.0) {
    ground_transfer_ = Spectrum{};
    ground_sky_.assign(kMsCols, Spectrum{});
  }
  ms_table_.assign(static_cast<size_t>(kMsRows) * kMsCols, Spectrum{});
  tbb::parallel_for(
      tbb::blocked_range<int>(0, kMsRows * kMsCols), [&](const tbb::blocked_range<int>& cells) {
        for (int cell = cells.begin(); cell < cells.end(); ++cell) {
          const int i = cell / kMsCols, j = cell % kMsCols;
          const glm::dvec3 x(0.0, 0.0, ms_radius(i, kMsRows)), sun = sun_of_column(j);
          Spectrum second{}, f_air{}, g_sky{}, g_ground{};
          for (int b = 0; b < kBands; ++b) {
            const double mu = -1.0 + 2.0 * (b + 0.5) / kBands, s = std::sqrt(1.0 - mu * mu);
            for (int c = 0; c < kAzimuths; ++c) {
              const double phi = 2.0 * kPi * (c + 0.5) / kAzimuths;
              const glm::dvec3 w(s * std::cos(phi), s * std::sin(phi), mu);
              Spectrum lp{}, fp{};
              const Depth seen = march(x, w, &sun, &lp, fp);
              for (int k = 0; k < kWavelengths; ++k) {
                second[k] += lp[k] * kIsotropic;
                f_air[k] += fp[k] * kIsotropic;
              }
              if (!hits_earth(x.z, mu) || albedo <= 0.0) continue;
              // The ground point: it reflects (Lambertian) the sun, the once-scattered skylight
              // D₁ and the skylight of the further orders ψ G.
              const glm::dvec3 p = x + w * ray_length(x.z, mu);
              const double mu_ground = glm::dot(glm::normalize(p), sun);
              const Spectrum tx = optical_depth(seen), d1 = ground_sky(mu_ground);
              Spectrum ts{};
              const bool lit = sun_transmittance(kEarthRadius, mu_ground, ts);
              for (int k = 0; k < kWavelengths; ++k) {
                const double reflect = std::exp(-tx[k]) * albedo / kPi * kIsotropic;
                if (lit) second[k] += reflect * mu_ground * ts[k];
                g_sky[k] += reflect * d1[k];
                g_ground[k] += reflect * ground_transfer_[k];
              }
            }
          }
          const double d_omega = 4.0 * kPi / (kBands * kAzimuths);
          Spectrum& psi = ms_table_[static_cast<size_t>(i) * kMsCols + j];
          for (int k = 0; k < kWavelengths; ++k) {
            const double a2 = second[k] * d_omega;
            const double a3 = a2 * f_air[k] * d_omega + g_sky[k] * d_omega;
            psi[k] = a2 + a3 / (1.0 - (f_air[k] + g_ground[k]) * d_omega);
          }
        }
      });
}

double NishitaSky::ms_column(double mu_sun) const {
  return std::clamp((std::acos(std::clamp(mu_sun, -1.0, 1.0)) - ms_theta_lo_) /
                        (ms_theta_hi_ - ms_theta_lo_),
                    0.0, 1.0) *
         (kMsCols - 1);
}

NishitaSky::Spectrum NishitaSky::ground_sky(double mu_sun) const {
  const double v = ms_column(mu_sun);
  const int j = std::min(kMsCols - 2, static_cast<int>(v));
  const double f = v - j;
  Spectrum out{};
  for (int k = 0; k < kWavelengths; ++k)
    out[k] = (1.0 - f) * ground_sky_[static_cast<size_t>(j)][k] +
             f * ground_sky_[static_cast<size_t>(j) + 1][k];
  return out;
}

NishitaSky::Spectrum NishitaSky::multiple_scattering(double r, double mu_sun) const {
  const double u = std::sqrt(std::clamp((r - kEarthRadius) / kTop, 0.0, 1.0)) * (kMsRows - 1);
  const double v = ms_column(mu_sun);
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

void NishitaSky::build_transfer() {
  constexpr int cols = 2 * kTransferHalf;
  const double albedo = a_.ground_albedo;
  // F along each (altitude, cos zenith) of the grid, in the air and from the ground.
  std::vector<Spectrum> air(static_cast<size_t>(kMsRows) * cols), ground(air.size());
  tbb::parallel_for(
      tbb::blocked_range<int>(0, kMsRows * cols), [&](const tbb::blocked_range<int>& cells) {
        for (int cell = cells.begin(); cell < cells.end(); ++cell) {
          const int i = cell / cols, j = cell % cols;
          const double r = ms_radius(i, kMsRows), mu = column_mu(r, j, kTransferHalf);
          const glm::dvec3 w(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu);
          const Depth seen =
              march(glm::dvec3(0.0, 0.0, r), w, nullptr, nullptr, air[static_cast<size_t>(cell)]);
          if (!hits_earth(r, mu) || albedo <= 0.0) continue;
          const Spectrum tp = optical_depth(seen);
          for (int k = 0; k < kWavelengths; ++k)
            ground[static_cast<size_t>(cell)][k] = std::exp(-tp[k]) * albedo / kPi;
        }
      });
  // F_i = ∫ p_i(ω·ω') F(ω') dω' for every view column.
  for (auto* table : {&transfer_r_, &transfer_m_, &ground_r_, &ground_m_})
    table->assign(air.size(), Spectrum{});
  const auto& weights = mie_band_weights();
  tbb::parallel_for(
      tbb::blocked_range<int>(0, kMsRows * cols), [&](const tbb::blocked_range<int>& cells) {
        for (int cell = cells.begin(); cell < cells.end(); ++cell) {
          const int i = cell / cols, j = cell % cols;
          const double r = ms_radius(i, kMsRows), mu = column_mu(r, j, kTransferHalf);
          const size_t row = static_cast<size_t>(i) * cols;
          // Rayleigh, from F's moments (F depends on μ' alone): ∫ (1 + (ω·ω')²) F dω' =
          // E + μ² M_zz + (1 − μ²) M_xx, E = 2π∫F dμ', M_zz = 2π∫F μ'² dμ', M_xx = π∫F (1 − μ'²)
          // dμ'.
          for (int c = 0; c < cols; ++c) {
            const double m = column_mu(r, c, kTransferHalf), w = column_weight(r, c, kTransferHalf);
            const double q = 3.0 / (16.0 * kPi) * 2.0 * kPi * w *
                             (1.0 + mu * mu * m * m + 0.5 * (1.0 - mu * mu) * (1.0 - m * m));
            for (int k = 0; k < kWavelengths; ++k) {
              transfer_r_[cell][k] += q * air[row + c][k];
              ground_r_[cell][k] += q * ground[row + c][k];
            }
          }
          // The aerosols: bands about the view ω = (sv, 0, μ), tangents (μ, 0, −sv) and (0, 1, 0).
          const double sv = std::sqrt(std::max(0.0, 1.0 - mu * mu));
          for (int b = 0; b < kMieBands; ++b) {
            const double g = mie_band_angle(b), share = weights[static_cast<size_t>(b)] / kAround;
            for (int n = 0; n < kAround; ++n) {
              const double psi = 2.0 * kPi * (n + 0.5) / kAround;
              const double mu2 =
                  std::clamp(std::cos(g) * mu - std::sin(g) * std::cos(psi) * sv, -1.0, 1.0);
              int c;
              double fc;
              column_of(r, mu2, kTransferHalf, c, fc);
              for (int k = 0; k < kWavelengths; ++k) {
                transfer_m_[cell][k] +=
                    share * ((1.0 - fc) * air[row + c][k] + fc * air[row + c + 1][k]);
                ground_m_[cell][k] +=
                    share * ((1.0 - fc) * ground[row + c][k] + fc * ground[row + c + 1][k]);
              }
            }
          }
        }
      });
}

NishitaSky::Spectrum NishitaSky::third_scattering(double r, double mu_view, double mu_sun,
                                                  const Depth& rho) const {
  constexpr int cols = 2 * kTransferHalf;
  const double u = std::sqrt(std::clamp((r - kEarthRadius) / kTop, 0.0, 1.0)) * (kMsRows - 1);
  const int i = std::min(kMsRows - 2, static_cast<int>(u));
  const double fu = u - i;
  int c;
  double fc;
  column_of(r, mu_view, kTransferHalf, c, fc);
  auto at = [&](const std::vector<Spectrum>& t, int k) {
    const Spectrum* a = &t[static_cast<size_t>(i) * cols + c];
    const Spectrum* b = &t[static_cast<size_t>(i + 1) * cols + c];
    return (1.0 - fu) * ((1.0 - fc) * a[0][k] + fc * a[1][k]) +
           fu * ((1.0 - fc) * b[0][k] + fc * b[1][k]);
  };
  const Spectrum psi = multiple_scattering(r, mu_sun),
                 psi_ground = multiple_scattering(kEarthRadius, mu_sun), d1 = ground_sky(mu_sun);
  Spectrum out{};
  for (int k = 0; k < kWavelengths; ++k) {
    const double sr = beta_r_[k] * rho.rayleigh, sm = kMieScattering * rho.mie;
    const double ground = d1[k] + psi_ground[k] * ground_transfer_[k];
    out[k] = psi[k] * (sr * at(transfer_r_, k) + sm * at(transfer_m_, k)) +
             ground * (sr * at(ground_r_, k) + sm * at(ground_m_, k));
  }
  return out;
}

}  // namespace arbor::tracer
