// A physical clear sky: single scattering of sunlight by the molecules (Rayleigh) and aerosols
// (Mie) of a spherical atmosphere with exponential density profiles, attenuated on both legs of
// the path by scattering and by ozone absorption — the single-scattering model of Nishita, Sirai,
// Tadamura & Nakamae 1993 ("Display of the Earth taking into account atmospheric scattering"),
// integrated spectrally and returned as CIE XYZ. docs/rendering.md, "Sky", gives every constant.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/vec3.hpp>

#include "common/math.h"

namespace arbor::tracer {

// The atmosphere's definition, shared by the sky models and the Monte Carlo simulation that checks
// them (sky_monte_carlo.h). docs/rendering.md, "Sky", gives the sources.
namespace atmosphere {
constexpr double kEarthRadius = 6360e3;  // m
constexpr double kTop = 60e3;            // m: the atmosphere's thickness
constexpr double kTopRadius = kEarthRadius + kTop;
constexpr double kRayleighHeight = 8000.0;  // m, scale height of the molecules
constexpr double kMieHeight = 1200.0;       // m, scale height of the aerosols
// Aerosols at sea level: scattering 2e-5 m⁻¹ (an aerosol optical depth of 0.024 at any wavelength,
// a very clear day), single-scattering albedo 0.9, asymmetry g = 0.76.
constexpr double kMieScattering = 2.0e-5, kMieExtinction = kMieScattering / 0.9, kMieG = 0.76;
// Ozone: a layer between 10 and 40 km peaking at 25 km (a tent of unit peak), holding 300 Dobson
// units (1 DU = 2.687e20 molecules m⁻²) in all: peak number density 300 × 2.687e20 / 15 km.
constexpr double kOzonePeakDensity = 300.0 * 2.687e20 / 15e3;  // molecules m⁻³
// The extraterrestrial sun's spectral radiance at `nm` nanometres (any scale): the table of
// Preetham, Shirley & Smits 1999 (380–750 nm every 10 nm, from Iqbal 1983), linear between its
// points and continued along its last slope to 780 nm.
double solar_spectrum(double nm);

// The Rayleigh phase function, 3/(16π) (1 + cos² θ).
inline double rayleigh_phase(double c) { return 3.0 / (16.0 * kPi) * (1.0 + c * c); }

// The Cornette–Shanks phase function (the one Nishita et al. use for aerosols), normalised over
// the sphere: 3/(8π) (1 − g²)(1 + cos² θ) / ((2 + g²)(1 + g² − 2g cos θ)^(3/2)).
inline double mie_phase(double c);

// The δ-M forward fraction of the aerosol phase function (Wiscombe 1977): its second Legendre
// moment χ₂ = 2π ∫ p(t) P₂(t) dt, 0.656 for g = 0.76.
double mie_forward_fraction();

inline double mie_phase(double c) {
  const double g = kMieG, g2 = g * g;
  return 3.0 / (8.0 * kPi) * (1.0 - g2) * (1.0 + c * c) /
         ((2.0 + g2) * std::pow(1.0 + g2 - 2.0 * g * c, 1.5));
}
// Distance from radius r along cos zenith μ to the top of the atmosphere (r inside it).
inline double to_top(double r, double mu) {
  const double disc = r * r * (mu * mu - 1.0) + kTopRadius * kTopRadius;
  return std::max(0.0, -r * mu + std::sqrt(std::max(0.0, disc)));
}

// Whether a ray from radius r along cos zenith μ meets the Earth.
inline bool hits_earth(double r, double mu) {
  return mu < 0.0 && r * r * (mu * mu - 1.0) + kEarthRadius * kEarthRadius >= 0.0;
}

// The dust_density of Linke's turbidity TL (at air mass 2, Kasten 1980's pyrheliometric formula
// TL = (9.4 + 0.9 M) δ with δ the broadband optical depth): δ = δ_cda + δ_w + δ_a, the
// clean dry atmosphere's δ_cda = −0.101 + 0.235 M^−0.16 and the water vapour's
// δ_w = 0.112 M^−0.55 w^0.34 fitted by Molineaux, Ineichen & O'Neill 1998 (Appl. Opt. 37), w =
// 1.5 cm, and δ_a the aerosols' optical depth at 700 nm (their equivalence). TL 3 → δ_a 0.071.
double dust_for_turbidity(double linke_turbidity);
// The dust_density of a meteorological visibility in km (Koschmieder: 3.912 / the extinction at
// 550 nm at the ground, the air's included). 50 km → 2.4, 20 km → 6.4.
double dust_for_visibility(double km);

}  // namespace atmosphere

struct Atmosphere {
  double air_density = 1.0;    // × the standard Rayleigh profile
  double dust_density = 1.0;   // × the clear-day aerosol (Mie) profile
  double ozone_density = 1.0;  // × a 300 Dobson-unit ozone layer
  double altitude = 0.0;       // metres above sea level of the observer (the scene's z = 0)
  // Every order of scattering — the second exactly (nishita_second.cpp), the further ones after
  // Hillaire 2020 (nishita_multiple.cpp) — and the light of a Lambertian ground of this albedo;
  // off: Nishita's single scattering.
  bool multiple_scattering = false;
  double ground_albedo = 0.0;
  // With multiple_scattering, for verification (tests and bench/sky_bench): 1 or 2 keeps only the
  // first one or two orders of the sky (radiance_xyz); 0, every order.
  int orders = 0;
  // With multiple_scattering: false when the model serves aerial perspective alone (segments),
  // which needs neither the exact second order nor the anisotropic further orders — a third of
  // the build.
  bool sky = true;
};

class NishitaSky {
 public:
  static constexpr int kWavelengths = 25;  // 380 … 780 nm, 16.67 nm apart
  static constexpr int kViewSteps = 32;    // default quadrature steps along a view ray

  // sun_direction: unit, z up; sun_irradiance: the sun's irradiance outside the atmosphere, on a
  // plane facing it, as CIE Y (the luminance of a scene-linear colour).
  NishitaSky(const Atmosphere& atmosphere, const glm::dvec3& sun_direction, double sun_irradiance);

  // Radiance of the sky (without the sun's disk) seen in direction `view` (unit), CIE XYZ;
  // `steps` quadrature steps along the view ray. Black below the horizon.
  glm::dvec3 radiance_xyz(const glm::dvec3& view, int steps = kViewSteps) const;
  // The sun's irradiance at the observer on a plane facing it, after its path through the
  // atmosphere, CIE XYZ (0 when the sun is below the horizon).
  glm::dvec3 sun_irradiance_xyz() const { return sun_xyz_; }
  // The sun's irradiance outside the atmosphere, CIE XYZ (Y is the irradiance given).
  glm::dvec3 extraterrestrial_xyz() const { return space_xyz_; }
  // Along `view` (unit) from the observer, at each of the ascending distances `at` (metres): the
  // light the air before it scatters towards the observer (CIE XYZ, in radiance_xyz's units; with
  // multiple scattering, single scattering and σ_s ψ, nishita_multiple.cpp) and the
  // extraterrestrial sun's XYZ after the path's transmittance — aerial perspective's inputs
  // (aerial.h). With multiple scattering the transmittance is δ-M scaled (Wiscombe 1977): the
  // fraction f = χ₂ of the aerosols' scattering in their forward peak counts as not scattered,
  // because a surface's light scattered a few degrees stays about its pixel, where the air's own
  // light does not include it. `steps` midpoint steps between consecutive distances.
  struct Segment {
    glm::dvec3 inscattered{0.0}, transmitted{0.0};
  };
  std::vector<Segment> segments(const glm::dvec3& view, const std::vector<double>& at,
                                int steps) const;
  // Transmittance of the atmosphere from the observer towards `direction`, at wavelength index k.
  double transmittance(const glm::dvec3& direction, int k) const;
  // What wavelength k adds to XYZ per unit of radiance relative to the extraterrestrial sun
  // (its spectral irradiance × the colour matching functions × the band's width).
  glm::dvec3 spectral_weight(int k) const {
    return solar_[static_cast<std::size_t>(k)] * cmf_[static_cast<std::size_t>(k)];
  }

  static double wavelength(int k) { return 380.0 + 400.0 * k / (kWavelengths - 1); }  // nm
  // Rayleigh scattering coefficient of sea-level air (m⁻¹) at `nm` nanometres.
  static double rayleigh_scattering(double nm);
  // Ozone absorption cross-section (m²) at `nm` nanometres: the Chappuis band as a Gaussian.
  static double ozone_cross_section(double nm);
  // CIE 1931 2° colour matching functions, the multi-lobe fit of Wyman, Sloan & Shirley 2013.
  static glm::dvec3 cie_xyz_bar(double nm);

 private:
  struct Depth {
    double rayleigh = 0.0, mie = 0.0, ozone = 0.0;  // column densities (density × metres)
  };
  Depth densities(double r) const;  // at radius r: the three profiles' densities
  // A midpoint step of dt through densities rho: returns the depth to the step's middle (`seen`
  // and half the step) and adds the whole step to `seen`.
  static Depth step_depth(Depth& seen, const Depth& rho, double dt) {
    const Depth middle{seen.rayleigh + 0.5 * rho.rayleigh * dt, seen.mie + 0.5 * rho.mie * dt,
                       seen.ozone + 0.5 * rho.ozone * dt};
    seen.rayleigh += rho.rayleigh * dt;
    seen.mie += rho.mie * dt;
    seen.ozone += rho.ozone * dt;
    return middle;
  }
  Depth depth_to_space(double r, double mu) const;  // along a ray from radius r at cos zenith μ
  Depth depth_to_sun(double r, double mu) const;    // tabulated depth_to_space towards the sun
  // A table over altitude rows (h = H u²) and cos-zenith columns over [-1, 1]: the cell holding
  // (r, μ) and the bilinear weights within it.
  struct TableCell {
    int i, j;
    double fu, fv;
  };
  static TableCell table_cell(double r, double mu, int rows, int cols);
  Depth integrate_to_space(double r, double mu, int steps) const;
  using Spectrum = std::array<double, kWavelengths>;
  // One quadrature step of a view ray, of length dt at the point p (from the Earth's centre): adds
  // the light it scatters towards the observer (per wavelength, relative to the extraterrestrial
  // sun) to l and its column densities to `seen`; pr and pm, the phase functions at the angle
  // between the ray and the sun.
  // `second_exact`: the second order is added apart (second_order), so single scattering keeps
  // the true extinction on both legs and the table adds the orders from the third on.
  void scatter_step(const glm::dvec3& p, const glm::dvec3& view, double dt, double pr, double pm,
                    Depth& seen, Spectrum& l, bool second_exact) const;
  std::array<double, kWavelengths> optical_depth(const Depth& d) const;
  // The orders beyond the second (nishita_multiple.cpp): the table ψ of every order from the
  // second over altitude and the sun's cos zenith (bilinear at radius r); the skylight on the
  // ground D₁ by the sun's cos zenith there; and the orders from the third on scattered towards a
  // view of cos zenith μ_view (there) by the true phase functions.
  void build_multiple_scattering();
  Spectrum multiple_scattering(double r, double mu_sun) const;
  Spectrum ground_sky(double mu_sun) const;
  double ms_column(double mu_sun) const;  // the sun's continuous column in those tables
  void build_transfer();
  Spectrum third_scattering(double r, double mu_view, double mu_sun, const Depth& rho) const;
  // Along the ray from x (from the Earth's centre) in direction w (unit) to the top or the ground:
  // adds ∫ T σ_s dt to `transfer` and, given the sun, the sunlight scattered once towards x to
  // `single`; returns the ray's column densities. 24 steps spaced quadratically from x.
  Depth march(const glm::dvec3& x, const glm::dvec3& w, const glm::dvec3* sun, Spectrum* single,
              Spectrum& transfer) const;
  static double ray_length(double r, double mu);  // to the top or the ground
  // The transmittance towards the sun from radius r at the sun's cos zenith μ, per wavelength:
  // depth_to_sun's table exponentiated once (bilinear in transmittance); false in the Earth's
  // shadow. For the orders beyond the first, where it saves an exponential per wavelength.
  bool sun_transmittance(double r, double mu, Spectrum& out) const;
  Spectrum scattering(const Depth& rho) const;  // σ_s at densities rho, per wavelength
  // The second order exactly (nishita_second.cpp): the single-scattered radiance field, its
  // moments and the second scattering of it along the observer's view rays, tabulated over the
  // view's elevation and azimuth from the sun.
  struct Field;
  void build_second_order();
  void field_cell(Field& field, int i, int j) const;  // one altitude row and cos-zenith column
  Spectrum second_source(const Field& field, const glm::dvec3& y, const glm::dvec3& view) const;
  glm::dvec3 second_order(const glm::dvec3& view) const;

  Atmosphere a_;
  glm::dvec3 sun_{0.0, 0.0, 1.0};
  double r0_ = 0.0;                           // the observer's radius
  std::array<double, kWavelengths> solar_{};  // extraterrestrial spectral irradiance, scaled
  std::array<double, kWavelengths> beta_r_{}, sigma_o_{};
  std::array<glm::dvec3, kWavelengths> cmf_{};
  // depth_to_sun's table: altitude rows (h = H u²) × μ columns over [-1, 1].
  static constexpr int kRows = 64, kCols = 256;
  std::vector<Depth> sun_table_;
  std::vector<Spectrum> sun_transmittance_;  // exp(−optical_depth) of each sun_table_ cell
  static constexpr int kMsRows = 32, kMsCols = 11;
  static constexpr double kMsSpan = 10.0 * kPi / 180.0;  // radians either side of the sun's
  // ψ: altitude rows (h = H u²) × columns of the sun's zenith angle over [lo, hi]
  std::vector<Spectrum> ms_table_;
  double ms_theta_lo_ = 0.0, ms_theta_hi_ = kPi;
  std::vector<Spectrum> ground_sky_;  // D₁ per sun column
  Spectrum ground_transfer_{};        // G
  // F_R, F_M in the air and from the ground: altitude rows × view cos-zenith columns.
  static constexpr int kTransferHalf = 32;
  std::vector<Spectrum> transfer_r_, transfer_m_, ground_r_, ground_m_;
  // The second order's radiance (XYZ) over view elevation rows × azimuth columns.
  static constexpr int kSecondRows = 24, kSecondCols = 32;
  std::vector<glm::dvec3> second_;
  glm::dvec3 sun_xyz_{0.0}, space_xyz_{0.0};
};

}  // namespace arbor::tracer
