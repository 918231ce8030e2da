// A physical clear sky: single scattering of sunlight by the molecules (Rayleigh) and aerosols
// (Mie) of a spherical atmosphere with exponential density profiles, attenuated on both legs of
// the path by scattering and by ozone absorption — the single-scattering model of Nishita, Sirai,
// Tadamura & Nakamae 1993 ("Display of the Earth taking into account atmospheric scattering"),
// integrated spectrally and returned as CIE XYZ. docs/rendering.md, "Sky", gives every constant.
#pragma once

#include <array>
#include <vector>

#include <glm/vec3.hpp>

namespace arbor::tracer {

struct Atmosphere {
  double air_density = 1.0;    // × the standard Rayleigh profile
  double dust_density = 1.0;   // × the clear-day aerosol (Mie) profile
  double ozone_density = 1.0;  // × a 300 Dobson-unit ozone layer
  double altitude = 0.0;       // metres above sea level of the observer (the scene's z = 0)
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
  // Transmittance of the atmosphere from the observer towards `direction`, at wavelength index k.
  double transmittance(const glm::dvec3& direction, int k) const;

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
  Depth densities(double r) const;                  // at radius r: the three profiles' densities
  Depth depth_to_space(double r, double mu) const;  // along a ray from radius r at cos zenith μ
  Depth depth_to_sun(double r, double mu) const;    // tabulated depth_to_space towards the sun
  Depth integrate_to_space(double r, double mu, int steps) const;
  std::array<double, kWavelengths> optical_depth(const Depth& d) const;

  Atmosphere a_;
  glm::dvec3 sun_{0.0, 0.0, 1.0};
  double r0_ = 0.0;                           // the observer's radius
  std::array<double, kWavelengths> solar_{};  // extraterrestrial spectral irradiance, scaled
  std::array<double, kWavelengths> beta_r_{}, sigma_o_{};
  std::array<glm::dvec3, kWavelengths> cmf_{};
  // depth_to_sun's table: altitude rows (h = H u²) × μ columns over [-1, 1].
  static constexpr int kRows = 64, kCols = 256;
  std::vector<Depth> sun_table_;
  glm::dvec3 sun_xyz_{0.0}, space_xyz_{0.0};
};

}  // namespace arbor::tracer
