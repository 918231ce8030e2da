// The second order of scattering, computed exactly rather than by Hillaire's isotropic table
// (nishita_multiple.cpp), in the manner of Bruneton & Neyret 2008 ("Precomputed atmospheric
// scattering", EGSR, §4: the radiance field of one order is tabulated over altitude, view zenith,
// sun zenith and azimuth, and the next order scatters it with the true phase functions).
//
// 1. The single-scattered radiance field L₁(y, ω'): the light arriving at a point y from
//    direction ω' that has scattered once (the sunlight scattered along the ray from y towards
//    ω', through the true extinction on both legs) or been reflected once by the Lambertian ground
//    where the ray meets it. Tabulated over 16 altitudes (h = 60 km u²) × 64 cos-zenith columns
//    (half above the point's horizon, half below, each dense at the horizon, as Bruneton's) × 5
//    sun zenith angles (the observer's ± 10°, as the ψ_ms table) × 32 azimuths from the sun
//    (φ = π x², dense where the aureole is), per wavelength; 32 steps along each ray.
// 2. The second scattering at y towards the observer (view direction ω, light leaving along −ω):
//      J₂(y, ω) = β_R(y) ∫ p_R(ω·ω') L₁(y, ω') dω' + σ_M(y) ∫ p_M(ω·ω') L₁(y, ω') dω'.
//    Rayleigh's phase is a polynomial of degree 2 in ω·ω', so its integral is exact from L₁'s
//    moments of order 0 and 2 at y, E = ∫ L₁ dω' and M = ∫ L₁ ω'ω'ᵀ dω':
//      ∫ p_R L₁ dω' = 3/(16π) (E + ωᵀ M ω)
//    — tabulated at the field's altitude and sun nodes from its own nodes (trapezoids). The
//    aerosols' phase is peaked (g = 0.76): its integral is a quadrature about ω, in 16 bands of
//    the angle from ω (γ = π x², each weighted by its exact share of the phase) × 16 azimuths,
//    left out where the aerosols scatter less than 10⁻⁴ of what the air does.
// 3. The second order seen by the observer: ∫ T(0, y) J₂(y, ω) dt along the view ray (16 steps,
//    true extinction), tabulated over the view's elevation (24 rows, e = 90° x²) and azimuth from
//    the sun (32 columns, φ = π x²), bilinear.
// The orders from the third on: nishita_multiple.cpp.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include "common/fast_trig.h"
#include "tracer/lights/nishita.h"
#include "tracer/lights/nishita_grid.h"

namespace arbor::tracer {

using namespace atmosphere;

namespace {

constexpr int kW = NishitaSky::kWavelengths;
constexpr int kFieldRows = 16, kFieldHalf = 32, kFieldMus = 2 * kFieldHalf, kFieldSuns = 5,
              kFieldAzimuths = 32, kFieldSteps = 32;
constexpr int kMieAround = 16, kSecondSteps = 16;
constexpr double kSunSpan = 10.0 * kPi / 180.0;

double row_radius(int i) {
  const double u = double(i) / (kFieldRows - 1);
  return kEarthRadius + kTop * u * u;
}

// A continuous index x (kN − 1) with x = sqrt(value / span), split into cell and fraction.
void warped(double value, double span, int n, int& i, double& f) {
  const double x = std::sqrt(std::clamp(value / span, 0.0, 1.0)) * (n - 1);
  i = std::min(n - 2, static_cast<int>(x));
  f = x - i;
}

// The frame at y: its zenith, and the horizontal direction towards the sun (any if overhead).
struct LocalFrame {
  glm::dvec3 x, y, z;
  LocalFrame(const glm::dvec3& p, const glm::dvec3& sun) : z(glm::normalize(p)) {
    glm::dvec3 h = sun - glm::dot(sun, z) * z;
    if (glm::dot(h, h) < 1e-18)
      h = std::fabs(z.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    h -= glm::dot(h, z) * z;
    x = glm::normalize(h);
    y = glm::cross(z, x);
  }
};

}  // namespace

const std::array<double, kMieBands>& atmosphere::mie_band_weights() {
  static const std::array<double, kMieBands> weights = [] {
    std::array<double, kMieBands> w{};
    constexpr int sub = 256;  // midpoints in γ within each band
    for (int b = 0; b < kMieBands; ++b) {
      for (int n = 0; n < sub; ++n) {
        const double x0 = (b + double(n) / sub) / kMieBands,
                     x1 = (b + double(n + 1) / sub) / kMieBands;
        const double g0 = kPi * x0 * x0, g1 = kPi * x1 * x1;
        w[static_cast<std::size_t>(b)] +=
            2.0 * kPi * mie_phase(std::cos(0.5 * (g0 + g1))) * (std::cos(g0) - std::cos(g1));
      }
    }
    return w;
  }();
  return weights;
}

struct NishitaSky::Field {
  double theta_lo = 0.0, theta_hi = kPi;
  std::vector<float> radiance;  // [row][column][sun][azimuth][wavelength]
  // The Rayleigh moments at each row and sun node: E, Mxx, Myy, Mzz, Mxz in the frame whose x
  // points to the sun's azimuth.
  std::vector<std::array<Spectrum, 5>> moments;  // [row][sun]
  static std::size_t at(int i, int j, int s, int a) {
    return ((((static_cast<std::size_t>(i) * kFieldMus + j) * kFieldSuns + s) * kFieldAzimuths) +
            a) *
           kW;
  }
  double sun_theta(int s) const { return theta_lo + (theta_hi - theta_lo) * s / (kFieldSuns - 1); }
  void sun_of(double mu_s, int& s, double& f) const {
    const double v =
        std::clamp((std::acos(std::clamp(mu_s, -1.0, 1.0)) - theta_lo) / (theta_hi - theta_lo), 0.0,
                   1.0) *
        (kFieldSuns - 1);
    s = std::min(kFieldSuns - 2, static_cast<int>(v));
    f = v - s;
  }
};

namespace {

// The aerosols' bands' and their azimuths' cosines and sines, once.
struct Rings {
  std::array<double, kMieBands> cg, sg;
  std::array<double, kMieAround> cp, sp;
};
const Rings& rings() {
  static const Rings q = [] {
    Rings r;
    for (int n = 0; n < kMieBands; ++n) {
      r.cg[static_cast<std::size_t>(n)] = std::cos(mie_band_angle(n));
      r.sg[static_cast<std::size_t>(n)] = std::sin(mie_band_angle(n));
    }
    for (int n = 0; n < kMieAround; ++n) {
      r.cp[static_cast<std::size_t>(n)] = std::cos(2.0 * kPi * (n + 0.5) / kMieAround);
      r.sp[static_cast<std::size_t>(n)] = std::sin(2.0 * kPi * (n + 0.5) / kMieAround);
    }
    return r;
  }();
  return q;
}

// The moments E, Mxx, Myy, Mzz, Mxz of one (row, sun) node of the field, by trapezoids over its
// columns (each half of the sphere apart: the horizon is an edge) and azimuths (doubled: the field
// is symmetric about the sun's vertical plane).
template <typename Spectrum, typename Field>
std::array<Spectrum, 5> node_moments(const Field& field, int i, int s) {
  const double r = row_radius(i);
  std::array<Spectrum, 5> m{};
  for (int j = 0; j < kFieldMus; ++j) {
    const double wmu = column_weight(r, j, kFieldHalf);
    const double mu = column_mu(r, j, kFieldHalf), sin_mu = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    for (int a = 0; a < kFieldAzimuths; ++a) {
      auto phi_at = [](int n) {
        const double x = double(std::clamp(n, 0, kFieldAzimuths - 1)) / (kFieldAzimuths - 1);
        return kPi * x * x;
      };
      const double phi = phi_at(a), wphi = 0.5 * (phi_at(a + 1) - phi_at(a - 1));
      const double w = 2.0 * wmu * wphi;
      const double ox = sin_mu * std::cos(phi), oy = sin_mu * std::sin(phi);
      const double f[5] = {1.0, ox * ox, oy * oy, mu * mu, ox * mu};
      const float* l = &field.radiance[Field::at(i, j, s, a)];
      for (int q = 0; q < 5; ++q)
        for (int c = 0; c < kW; ++c) m[q][c] += w * f[q] * l[c];
    }
  }
  return m;
}

}  // namespace

void NishitaSky::field_cell(Field& field, int i, int j) const {
  const double albedo = a_.ground_albedo;
  const double r = row_radius(i), mu = column_mu(r, j, kFieldHalf);
  const glm::dvec3 y(0.0, 0.0, r), w(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu);
  const bool ground = hits_earth(r, mu);
  const double length = ray_length(r, mu);
  // The view leg is the same for every sun: each step's position and the Rayleigh and
  // aerosol scattering there times the transmittance back to y and the step's length.
  struct Step {
    glm::dvec3 z;
    double r;
    Spectrum rayleigh, mie;
  };
  std::array<Step, kFieldSteps> steps;
  Depth seen;
  for (int t_i = 0; t_i < kFieldSteps; ++t_i) {
    const double a0 = double(t_i) / kFieldSteps, a1 = double(t_i + 1) / kFieldSteps;
    const double t = length * 0.25 * (a0 + a1) * (a0 + a1), dt = length * (a1 * a1 - a0 * a0);
    Step& st = steps[static_cast<std::size_t>(t_i)];
    st.z = y + w * t;
    st.r = glm::length(st.z);
    const Depth rho = densities(st.r);
    const Spectrum tau = optical_depth(step_depth(seen, rho, dt));
    for (int k = 0; k < kW; ++k) {
      const double tv = std::exp(-tau[k]) * dt;
      st.rayleigh[k] = beta_r_[k] * rho.rayleigh * tv;
      st.mie[k] = kMieScattering * rho.mie * tv;
    }
  }
  Spectrum to_ground{};
  if (ground && albedo > 0.0) {
    const Spectrum tau = optical_depth(seen);
    for (int k = 0; k < kW; ++k) to_ground[k] = std::exp(-tau[k]) * albedo / kPi;
  }
  const glm::dvec3 foot = glm::normalize(y + w * length);
  for (int s = 0; s < kFieldSuns; ++s) {
    const double th = field.sun_theta(s);
    for (int a = 0; a < kFieldAzimuths; ++a) {
      const double x = double(a) / (kFieldAzimuths - 1), phi = kPi * x * x;
      const glm::dvec3 sun(std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi),
                           std::cos(th));
      const double cs = glm::dot(w, sun), pr = rayleigh_phase(cs), pm = mie_phase(cs);
      Spectrum l{}, ts;
      for (const Step& st : steps) {
        if (!sun_transmittance(st.r, glm::dot(st.z, sun) / st.r, ts)) continue;
        for (int k = 0; k < kW; ++k) l[k] += (st.rayleigh[k] * pr + st.mie[k] * pm) * ts[k];
      }
      const double mu_ground = glm::dot(foot, sun);
      if (ground && albedo > 0.0 && sun_transmittance(kEarthRadius, mu_ground, ts)) {
        for (int k = 0; k < kW; ++k) l[k] += to_ground[k] * mu_ground * ts[k];
      }
      float* out = &field.radiance[Field::at(i, j, s, a)];
      for (int k = 0; k < kW; ++k) out[k] = static_cast<float>(l[k]);
    }
  }
}

void NishitaSky::build_second_order() {
  Field field;
  const double theta_sun =
      std::acos(std::clamp(glm::dot(glm::normalize(glm::dvec3(0.0, 0.0, r0_)), sun_), -1.0, 1.0));
  field.theta_lo = std::max(0.0, theta_sun - kSunSpan);
  field.theta_hi = std::min(kPi, theta_sun + kSunSpan);
  field.radiance.assign(Field::at(kFieldRows, 0, 0, 0), 0.0f);
  // 1. The single-scattered field, every (row, column) apart.
  tbb::parallel_for(tbb::blocked_range<int>(0, kFieldRows * kFieldMus),
                    [&](const tbb::blocked_range<int>& cells) {
                      for (int cell = cells.begin(); cell < cells.end(); ++cell)
                        field_cell(field, cell / kFieldMus, cell % kFieldMus);
                    });
  // 2. Its moments for the Rayleigh part.
  field.moments.resize(static_cast<std::size_t>(kFieldRows) * kFieldSuns);
  for (int i = 0; i < kFieldRows; ++i)
    for (int s = 0; s < kFieldSuns; ++s)
      field.moments[static_cast<std::size_t>(i) * kFieldSuns + s] =
          node_moments<Spectrum>(field, i, s);
  // 3. The second order along the observer's view rays.
  second_.assign(static_cast<std::size_t>(kSecondRows) * kSecondCols, glm::dvec3(0.0));
  const double sun_azimuth = std::atan2(sun_.y, sun_.x);
  tbb::parallel_for(
      tbb::blocked_range<int>(0, kSecondRows * kSecondCols),
      [&](const tbb::blocked_range<int>& cells) {
        for (int cell = cells.begin(); cell < cells.end(); ++cell) {
          const int i = cell / kSecondCols, c = cell % kSecondCols;
          const double xe = double(i) / (kSecondRows - 1), e = 0.5 * kPi * xe * xe;
          const double xa = double(c) / (kSecondCols - 1), az = sun_azimuth + kPi * xa * xa;
          const glm::dvec3 d(std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e));
          const double length = to_top(r0_, d.z);
          Spectrum l{};
          Depth seen;
          for (int t_i = 0; t_i < kSecondSteps; ++t_i) {
            const double a0 = double(t_i) / kSecondSteps, a1 = double(t_i + 1) / kSecondSteps;
            const double t = length * 0.25 * (a0 + a1) * (a0 + a1),
                         dt = length * (a1 * a1 - a0 * a0);
            const glm::dvec3 y = glm::dvec3(0.0, 0.0, r0_) + d * t;
            const Depth rho = densities(glm::length(y));
            const Depth to_y = step_depth(seen, rho, dt);
            const Spectrum tau = optical_depth(to_y), j2 = second_source(field, y, d);
            for (int k = 0; k < kW; ++k) l[k] += std::exp(-tau[k]) * j2[k] * dt;
          }
          glm::dvec3 xyz(0.0);
          for (int k = 0; k < kW; ++k) xyz += l[k] * solar_[k] * cmf_[k];
          second_[static_cast<std::size_t>(cell)] = xyz;
        }
      });
}

NishitaSky::Spectrum NishitaSky::second_source(const Field& field, const glm::dvec3& y,
                                               const glm::dvec3& view) const {
  const std::array<double, kMieBands>& band_weight = mie_band_weights();
  const double r = glm::length(y);
  const LocalFrame frame(y, sun_);
  const double mu_s = glm::dot(frame.z, sun_);
  const double u = std::sqrt(std::clamp((r - kEarthRadius) / kTop, 0.0, 1.0)) * (kFieldRows - 1);
  const int i = std::min(kFieldRows - 2, static_cast<int>(u));
  const double fu = u - i;
  int s;
  double fs;
  field.sun_of(mu_s, s, fs);
  const Depth rho = densities(r);
  Spectrum out{};
  // Rayleigh, from the moments.
  {
    const double ox = glm::dot(view, frame.x), oy = glm::dot(view, frame.y),
                 oz = glm::dot(view, frame.z);
    const double f[5] = {1.0, ox * ox, oy * oy, oz * oz, 2.0 * ox * oz};
    const double wn[4] = {(1 - fu) * (1 - fs), (1 - fu) * fs, fu * (1 - fs), fu * fs};
    const std::size_t nodes[4] = {static_cast<std::size_t>(i) * kFieldSuns + s,
                                  static_cast<std::size_t>(i) * kFieldSuns + s + 1,
                                  static_cast<std::size_t>(i + 1) * kFieldSuns + s,
                                  static_cast<std::size_t>(i + 1) * kFieldSuns + s + 1};
    for (int n = 0; n < 4; ++n)
      for (int q = 0; q < 5; ++q)
        for (int k = 0; k < kW; ++k)
          out[k] += wn[n] * f[q] * field.moments[nodes[n]][q][k] * 3.0 / (16.0 * kPi) * beta_r_[k] *
                    rho.rayleigh;
  }
  // The aerosols, by bands about the view — where they are not negligible: above about 15 km
  // (dust 3) they scatter less than 10⁻⁴ of what the air does, and are left out.
  if (kMieScattering * rho.mie < 1e-4 * beta_r_[kW - 1] * rho.rayleigh) return out;
  glm::dvec3 t = std::fabs(view.z) < 0.9 ? glm::cross(view, glm::dvec3(0, 0, 1))
                                         : glm::cross(view, glm::dvec3(1, 0, 0));
  t = glm::normalize(t);
  const glm::dvec3 b = glm::cross(view, t);
  const Rings& ring_of = rings();
  std::array<float, kW> sum{};
  for (int band = 0; band < kMieBands; ++band) {
    const double cg = ring_of.cg[static_cast<std::size_t>(band)],
                 sg = ring_of.sg[static_cast<std::size_t>(band)];
    std::array<float, kW> ring{};
    for (int n = 0; n < kMieAround; ++n) {
      const glm::dvec3 w = cg * view + sg * (ring_of.cp[static_cast<std::size_t>(n)] * t +
                                             ring_of.sp[static_cast<std::size_t>(n)] * b);
      const double mu = glm::dot(w, frame.z);
      // The azimuth from the sun only picks a table cell: the float arc tangent (3e-7 rad) does.
      const double phi = fast_atan2(static_cast<float>(std::fabs(glm::dot(w, frame.y))),
                                    static_cast<float>(glm::dot(w, frame.x)));
      int j, a;
      double fj, fa;
      column_of(r, mu, kFieldHalf, j, fj);
      warped(phi, kPi, kFieldAzimuths, a, fa);
      for (int di = 0; di < 2; ++di)
        for (int dj = 0; dj < 2; ++dj)
          for (int ds = 0; ds < 2; ++ds)
            for (int da = 0; da < 2; ++da) {
              const float weight = static_cast<float>((di ? fu : 1 - fu) * (dj ? fj : 1 - fj) *
                                                      (ds ? fs : 1 - fs) * (da ? fa : 1 - fa));
              const float* l = &field.radiance[Field::at(i + di, j + dj, s + ds, a + da)];
              for (int k = 0; k < kW; ++k) ring[k] += weight * l[k];
            }
    }
    const float share =
        static_cast<float>(band_weight[static_cast<std::size_t>(band)] / kMieAround);
    for (int k = 0; k < kW; ++k) sum[k] += share * ring[k];
  }
  for (int k = 0; k < kW; ++k) out[k] += kMieScattering * rho.mie * sum[k];
  return out;
}

glm::dvec3 NishitaSky::second_order(const glm::dvec3& view) const {
  const double e = std::asin(std::clamp(view.z, 0.0, 1.0));
  const double rel =
      std::fabs(std::remainder(std::atan2(view.y, view.x) - std::atan2(sun_.y, sun_.x), 2.0 * kPi));
  int i, c;
  double fi, fc;
  warped(e, 0.5 * kPi, kSecondRows, i, fi);
  warped(rel, kPi, kSecondCols, c, fc);
  auto at = [&](int row, int col) {
    return second_[static_cast<std::size_t>(row) * kSecondCols + col];
  };
  return (1 - fi) * ((1 - fc) * at(i, c) + fc * at(i, c + 1)) +
         fi * ((1 - fc) * at(i + 1, c) + fc * at(i + 1, c + 1));
}

}  // namespace arbor::tracer
