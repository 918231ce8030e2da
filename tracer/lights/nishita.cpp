// The single-scattering sky of Nishita et al. 1993: the radiance seen along a view ray is the
// integral over the ray of the sunlight scattered towards the observer at each point — the
// scattering coefficient × phase function × the sun's irradiance attenuated from the top of the
// atmosphere to the point and from the point to the observer — here with ozone absorption added to
// the attenuation (Nishita et al. have molecules and aerosols only) and evaluated at 25
// wavelengths.
#include "tracer/lights/nishita.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "common/math.h"

namespace arbor::tracer {

namespace {

using namespace atmosphere;

// Preetham, Shirley & Smits 1999's extraterrestrial solar spectral radiance, 380 … 750 nm.
constexpr std::array<double, 38> kSolar = {
    165.5, 162.3, 211.2, 258.8, 258.2, 242.3, 267.6, 296.6, 305.4, 300.6, 306.6, 288.3, 287.1,
    278.2, 271.0, 272.3, 263.6, 255.0, 250.6, 253.1, 253.5, 251.3, 246.3, 241.7, 236.8, 232.1,
    228.2, 223.4, 219.7, 215.3, 211.0, 207.3, 202.4, 198.7, 194.3, 190.7, 186.3, 182.6};

// One lobe of Wyman, Sloan & Shirley's fit: a Gaussian with different widths on either side.
double lobe(double x, double mu, double s1, double s2) {
  const double t = (x - mu) / (x < mu ? s1 : s2);
  return std::exp(-0.5 * t * t);
}

}  // namespace

double atmosphere::solar_spectrum(double nm) {
  const double x = (nm - 380.0) / 10.0;
  const int i = std::clamp(static_cast<int>(std::floor(x)), 0, static_cast<int>(kSolar.size()) - 2);
  const double f = x - i;  // beyond 750 nm, > 1: the last segment's slope continued
  return std::max(0.0, (1.0 - f) * kSolar[static_cast<std::size_t>(i)] +
                           f * kSolar[static_cast<std::size_t>(i) + 1]);
}

double atmosphere::mie_forward_fraction() {
  static const double f = [] {
    constexpr int n = 20000;  // midpoints in cos θ; the peak at g = 0.76 is a few hundred wide
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double t = -1.0 + 2.0 * (i + 0.5) / n;
      sum += mie_phase(t) * 0.5 * (3.0 * t * t - 1.0);
    }
    return 2.0 * kPi * sum * 2.0 / n;
  }();
  return f;
}

double atmosphere::dust_for_turbidity(double linke_turbidity) {
  constexpr double m = 2.0, water = 1.5;  // air mass, precipitable water (cm)
  const double clean = -0.101 + 0.235 * std::pow(m, -0.16);
  const double vapour = 0.112 * std::pow(m, -0.55) * std::pow(water, 0.34);
  const double aerosol = linke_turbidity / (9.4 + 0.9 * m) - clean - vapour;
  // The aerosols' optical depth is the column of dust 1 (its scale height) × its extinction.
  return std::max(0.0, aerosol) / (kMieExtinction * kMieHeight);
}

double atmosphere::dust_for_visibility(double km) {
  const double extinction = 3.912 / (km * 1e3) - NishitaSky::rayleigh_scattering(550.0);
  return std::max(0.0, extinction) / kMieExtinction;
}

double NishitaSky::rayleigh_scattering(double nm) {
  // β = 8π³ (n² − 1)² / (3 N λ⁴) × (6 + 3ρ) / (6 − 7ρ) (the King correction for depolarisation
  // ρ = 0.0279), with the refractive index of standard air (15 °C, 101 325 Pa) by Peck & Reeder's
  // dispersion formula (1972, J. Opt. Soc. Am. 62, 958), and N = 2.547e25 m⁻³ molecules of it:
  // 1.16e-5 m⁻¹ at 550 nm, a Rayleigh optical depth of 0.093 for the 8 km scale height.
  const double s2 = 1.0 / (nm * 1e-3 * nm * 1e-3);  // (1/λ in µm)²
  const double n1 = (8060.51 + 2480990.0 / (132.274 - s2) + 17455.7 / (39.32957 - s2)) * 1e-8;
  const double N = 2.547e25, rho = 0.0279, l = nm * 1e-9;
  const double n2 = n1 * (2.0 + n1);  // n² − 1
  return 8.0 * kPi * kPi * kPi * n2 * n2 / (3.0 * N * l * l * l * l) * (6.0 + 3.0 * rho) /
         (6.0 - 7.0 * rho);
}

double NishitaSky::ozone_cross_section(double nm) {
  // The Chappuis band: peak 5e-25 m² (5e-21 cm²) near 600 nm, modelled as a Gaussian of standard
  // deviation 50 nm — within about 20 % of measured cross-sections from 500 to 650 nm, where ozone
  // matters for the sky's colour; far smaller elsewhere, as measured.
  const double t = (nm - 600.0) / 50.0;
  return 5.0e-25 * std::exp(-0.5 * t * t);
}

glm::dvec3 NishitaSky::cie_xyz_bar(double nm) {
  // Wyman, Sloan & Shirley 2013, "Simple analytic approximations to the CIE XYZ color matching
  // functions", the multi-lobe fit (their eq. 2 and table 1).
  const double x = 1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) -
                   0.065 * lobe(nm, 501.1, 20.4, 26.2);
  const double y = 0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1);
  const double z = 1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8);
  return {x, y, z};
}

NishitaSky::NishitaSky(const Atmosphere& atmosphere, const glm::dvec3& sun_direction,
                       double sun_irradiance)
    : a_(atmosphere), sun_(glm::normalize(sun_direction)), r0_(kEarthRadius + atmosphere.altitude) {
  const double dl = 400.0 / (kWavelengths - 1);
  double y = 0.0;
  for (int k = 0; k < kWavelengths; ++k) {
    const double nm = wavelength(k);
    beta_r_[k] = rayleigh_scattering(nm);
    sigma_o_[k] = ozone_cross_section(nm) * kOzonePeakDensity;
    cmf_[k] = cie_xyz_bar(nm) * dl;
    solar_[k] = solar_spectrum(nm);
    y += solar_[k] * cmf_[k].y;
  }
  // Scaled so that the sun outside the atmosphere has CIE Y = its irradiance.
  for (double& s : solar_) s *= y > 0.0 ? sun_irradiance / y : 0.0;
  for (int k = 0; k < kWavelengths; ++k) space_xyz_ += solar_[k] * cmf_[k];

  sun_table_.resize(static_cast<size_t>(kRows) * kCols);
  for (int i = 0; i < kRows; ++i) {
    const double u = double(i) / (kRows - 1), r = kEarthRadius + kTop * u * u;
    // Below the horizon a ray meets the Earth; those cells hold the grazing ray's depth so that
    // interpolation next to the horizon stays finite (depth_to_sun tests the Earth itself).
    const double mu_horizon =
        -std::sqrt(std::max(0.0, 1.0 - (kEarthRadius / r) * (kEarthRadius / r)));
    for (int j = 0; j < kCols; ++j) {
      double mu = -1.0 + 2.0 * j / (kCols - 1);
      if (hits_earth(r, mu)) mu = mu_horizon + 1e-6;
      sun_table_[static_cast<size_t>(i) * kCols + j] = integrate_to_space(r, mu, 96);
    }
  }
  if (a_.multiple_scattering) {
    sun_transmittance_.resize(sun_table_.size());
    for (std::size_t c = 0; c < sun_table_.size(); ++c) {
      const Spectrum tau = optical_depth(sun_table_[c]);
      for (int k = 0; k < kWavelengths; ++k) sun_transmittance_[c][k] = std::exp(-tau[k]);
    }
    build_multiple_scattering();
    if (a_.sky) {
      build_transfer();
      build_second_order();
    }
  }
  if (!hits_earth(r0_, sun_.z)) {
    const auto tau = optical_depth(integrate_to_space(r0_, sun_.z, 512));
    for (int k = 0; k < kWavelengths; ++k) sun_xyz_ += solar_[k] * std::exp(-tau[k]) * cmf_[k];
  }
}

NishitaSky::Depth NishitaSky::densities(double r) const {
  const double h = std::max(0.0, r - kEarthRadius);
  Depth d;
  d.rayleigh = a_.air_density * std::exp(-h / kRayleighHeight);
  d.mie = a_.dust_density * std::exp(-h / kMieHeight);
  d.ozone = a_.ozone_density * std::max(0.0, 1.0 - std::fabs(h - 25e3) / 15e3);
  return d;
}

NishitaSky::Depth NishitaSky::integrate_to_space(double r, double mu, int steps) const {
  // Midpoints of steps growing quadratically from the start, where the air is densest.
  const double length = to_top(r, mu), s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
  Depth sum;
  for (int i = 0; i < steps; ++i) {
    const double a = double(i) / steps, b = double(i + 1) / steps;
    const double t = length * 0.25 * (a + b) * (a + b), dt = length * (b * b - a * a);
    const double x = t * s, z = r + t * mu;
    const Depth d = densities(std::sqrt(x * x + z * z));
    sum.rayleigh += d.rayleigh * dt;
    sum.mie += d.mie * dt;
    sum.ozone += d.ozone * dt;
  }
  return sum;
}

NishitaSky::Depth NishitaSky::depth_to_space(double r, double mu) const {
  if (hits_earth(r, mu)) {
    const double inf = std::numeric_limits<double>::infinity();
    return {inf, inf, inf};
  }
  return integrate_to_space(r, mu, 512);
}

NishitaSky::TableCell NishitaSky::table_cell(double r, double mu, int rows, int cols) {
  const double u = std::sqrt(std::clamp((r - kEarthRadius) / kTop, 0.0, 1.0)) * (rows - 1);
  const double v = (std::clamp(mu, -1.0, 1.0) + 1.0) * 0.5 * (cols - 1);
  const int i = std::min(rows - 2, static_cast<int>(u)),
            j = std::min(cols - 2, static_cast<int>(v));
  return {i, j, u - i, v - j};
}

NishitaSky::Depth NishitaSky::depth_to_sun(double r, double mu) const {
  if (hits_earth(r, mu)) {
    const double inf = std::numeric_limits<double>::infinity();
    return {inf, inf, inf};
  }
  const TableCell cell = table_cell(r, mu, kRows, kCols);
  const int i = cell.i, j = cell.j;
  const double fu = cell.fu, fv = cell.fv;
  const Depth& d00 = sun_table_[static_cast<size_t>(i) * kCols + j];
  const Depth& d01 = sun_table_[static_cast<size_t>(i) * kCols + j + 1];
  const Depth& d10 = sun_table_[static_cast<size_t>(i + 1) * kCols + j];
  const Depth& d11 = sun_table_[static_cast<size_t>(i + 1) * kCols + j + 1];
  auto mix = [&](double Depth::*f) {
    return (1.0 - fu) * ((1.0 - fv) * d00.*f + fv * d01.*f) +
           fu * ((1.0 - fv) * d10.*f + fv * d11.*f);
  };
  return {mix(&Depth::rayleigh), mix(&Depth::mie), mix(&Depth::ozone)};
}

bool NishitaSky::sun_transmittance(double r, double mu, Spectrum& out) const {
  if (hits_earth(r, mu)) return false;
  const TableCell cell = table_cell(r, mu, kRows, kCols);
  const std::size_t at = static_cast<std::size_t>(cell.i) * kCols + cell.j;
  const Spectrum &t00 = sun_transmittance_[at], &t01 = sun_transmittance_[at + 1],
                 &t10 = sun_transmittance_[at + kCols], &t11 = sun_transmittance_[at + kCols + 1];
  const double w00 = (1.0 - cell.fu) * (1.0 - cell.fv), w01 = (1.0 - cell.fu) * cell.fv,
               w10 = cell.fu * (1.0 - cell.fv), w11 = cell.fu * cell.fv;
  for (int k = 0; k < kWavelengths; ++k)
    out[k] = w00 * t00[k] + w01 * t01[k] + w10 * t10[k] + w11 * t11[k];
  return true;
}

std::array<double, NishitaSky::kWavelengths> NishitaSky::optical_depth(const Depth& d) const {
  std::array<double, kWavelengths> tau{};
  for (int k = 0; k < kWavelengths; ++k) {
    tau[k] = beta_r_[k] * d.rayleigh + kMieExtinction * d.mie + sigma_o_[k] * d.ozone;
  }
  return tau;
}

double NishitaSky::transmittance(const glm::dvec3& direction, int k) const {
  return std::exp(
      -optical_depth(depth_to_space(r0_, glm::normalize(direction).z))[static_cast<size_t>(k)]);
}

glm::dvec3 NishitaSky::radiance_xyz(const glm::dvec3& view, int steps) const {
  if (view.z < 0.0) return glm::dvec3(0.0);
  const glm::dvec3 d = glm::normalize(view);
  const double cos_scatter = glm::dot(d, sun_);
  const double pr = rayleigh_phase(cos_scatter), pm = mie_phase(cos_scatter);
  const double length = to_top(r0_, d.z);
  std::array<double, kWavelengths> l{};
  Depth seen;  // from the observer to the current point
  for (int i = 0; i < steps; ++i) {
    const double a = double(i) / steps, b = double(i + 1) / steps;
    const double t = length * 0.25 * (a + b) * (a + b), dt = length * (b * b - a * a);
    const glm::dvec3 p = glm::dvec3(0.0, 0.0, r0_) + d * t;
    scatter_step(p, d, dt, pr, pm, seen, l, a_.multiple_scattering);
  }
  glm::dvec3 xyz = a_.multiple_scattering && a_.orders != 1 ? second_order(d) : glm::dvec3(0.0);
  for (int k = 0; k < kWavelengths; ++k) xyz += l[k] * solar_[k] * cmf_[k];
  return xyz;
}

void NishitaSky::scatter_step(const glm::dvec3& p, const glm::dvec3& view, double dt, double pr,
                              double pm, Depth& seen, Spectrum& l, bool second_exact) const {
  const double r = glm::length(p);
  const Depth rho = densities(r);
  // The depth to the midpoint: everything before it and half of this step.
  const Depth to_point = step_depth(seen, rho, dt);
  const double mu_sun = glm::dot(p, sun_) / r;
  if (a_.multiple_scattering && !(second_exact && a_.orders > 0)) {
    // Every order from the second, isotropically (σ_s ψ, Hillaire 2020's eq. 11); or, beside the
    // exact second order, the orders from the third on towards the view.
    Spectrum source =
        second_exact ? third_scattering(r, glm::dot(p, view) / r, mu_sun, rho) : scattering(rho);
    if (!second_exact) {
      const Spectrum psi = multiple_scattering(r, mu_sun);
      for (int k = 0; k < kWavelengths; ++k) source[k] *= psi[k];
    }
    const Spectrum tau = optical_depth(to_point);
    for (int k = 0; k < kWavelengths; ++k) l[k] += source[k] * dt * std::exp(-tau[k]);
  }
  const Depth sun = depth_to_sun(r, mu_sun);
  if (!std::isfinite(sun.rayleigh)) return;  // the point is in the Earth's shadow
  const double mie = kMieScattering * rho.mie * pm * dt;
  const double mie_depth = kMieExtinction * (to_point.mie + sun.mie);
  for (int k = 0; k < kWavelengths; ++k) {
    const double tau = beta_r_[k] * (to_point.rayleigh + sun.rayleigh) + mie_depth +
                       sigma_o_[k] * (to_point.ozone + sun.ozone);
    l[k] += (beta_r_[k] * rho.rayleigh * pr * dt + mie) * std::exp(-tau);
  }
}

std::vector<NishitaSky::Segment> NishitaSky::segments(const glm::dvec3& view,
                                                      const std::vector<double>& at,
                                                      int steps) const {
  const glm::dvec3 d = glm::normalize(view), origin(0.0, 0.0, r0_);
  const double cos_scatter = glm::dot(d, sun_);
  const double pr = rayleigh_phase(cos_scatter), pm = mie_phase(cos_scatter);
  std::vector<Segment> out(at.size());
  Spectrum l{};
  Depth seen;
  double start = 0.0;
  for (std::size_t n = 0; n < at.size(); ++n) {
    const double dt = (at[n] - start) / steps;
    for (int i = 0; i < steps; ++i)
      scatter_step(origin + d * (start + (i + 0.5) * dt), d, dt, pr, pm, seen, l, false);
    start = at[n];
    Spectrum tau = optical_depth(seen);
    if (a_.multiple_scattering) {
      const double forward = mie_forward_fraction() * kMieScattering * seen.mie;
      for (int k = 0; k < kWavelengths; ++k) tau[k] -= forward;
    }
    for (int k = 0; k < kWavelengths; ++k) {
      out[n].inscattered += l[k] * solar_[k] * cmf_[k];
      out[n].transmitted += std::exp(-tau[k]) * solar_[k] * cmf_[k];
    }
  }
  return out;
}

}  // namespace arbor::tracer
