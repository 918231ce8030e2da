// Backward Monte Carlo path tracing through the layered spherical atmosphere (see the header).
// Per path: a wavelength drawn in proportion to its weight in X + Y + Z; free flights by delta
// tracking (tentative collisions at the majorant extinction, real ones with probability
// σ_t(x)/σ̄); at a real collision the throughput keeps the single-scattering albedo σ_s/σ_t and
// the sun is sampled (next-event estimation: phase × transmittance to the sun); the next
// direction is drawn from a one-sample mixture of a uniform sphere (for Rayleigh) and
// Henyey–Greenstein with the aerosols' g (for Cornette–Shanks), weighted by phase / mixture pdf.
// The ground reflects Lambertian: the sun sampled there too, then a cosine-distributed bounce.
// Russian roulette after the fourth event keeps it unbiased.
#include "tracer/lights/sky_monte_carlo.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/math.h"
#include "common/rng.h"

namespace arbor::tracer {

namespace {

using namespace atmosphere;

struct Medium {
  const Atmosphere& a;
  double beta_r,
      sigma_o;  // at the path's wavelength: Rayleigh scattering, ozone cross-section × peak
  double majorant;

  double height(const glm::dvec3& p) const { return glm::length(p) - kEarthRadius; }
  double rayleigh(double h) const {
    return beta_r * a.air_density * std::exp(-h / kRayleighHeight);
  }
  double mie_density(double h) const { return a.dust_density * std::exp(-h / kMieHeight); }
  double ozone(double h) const {
    return sigma_o * a.ozone_density * std::max(0.0, 1.0 - std::fabs(h - 25e3) / 15e3);
  }
  double extinction(double h) const {
    return rayleigh(h) + kMieExtinction * mie_density(h) + ozone(h);
  }
};

// Distance along the ray (p + t d) to the sphere of radius R from inside it, or to its near side
// from outside; -1 when the ray misses it. `inside`: p is inside (take the far root).
double to_sphere(const glm::dvec3& p, const glm::dvec3& d, double R, bool inside) {
  const double b = glm::dot(p, d), c = glm::dot(p, p) - R * R;
  const double disc = b * b - c;
  if (disc < 0.0) return -1.0;
  const double s = std::sqrt(disc);
  if (inside) return -b + s;
  const double t = -b - s;
  return t > 0.0 ? t : -1.0;
}

// Transmittance from p towards the sun: 0 when the Earth is in the way, else exp(−∫σ_t) by
// 256 midpoint steps spaced quadratically from p (the density falls fastest near the ground).
double sun_transmittance(const Medium& m, const glm::dvec3& p, const glm::dvec3& sun) {
  if (to_sphere(p, sun, kEarthRadius, false) > 0.0) return 0.0;
  const double length = std::max(0.0, to_sphere(p, sun, kTopRadius, true));
  constexpr int kSteps = 256;
  double tau = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double a = double(i) / kSteps, b = double(i + 1) / kSteps;
    const double t = length * 0.25 * (a + b) * (a + b), dt = length * (b * b - a * a);
    tau += m.extinction(std::max(0.0, m.height(p + sun * t))) * dt;
  }
  return std::exp(-tau);
}

// An orthonormal frame's two tangents about unit n.
void tangents(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
  t = glm::normalize(std::fabs(n.z) < 0.9 ? glm::cross(n, glm::dvec3(0, 0, 1))
                                          : glm::cross(n, glm::dvec3(1, 0, 0)));
  b = glm::cross(n, t);
}

glm::dvec3 around(const glm::dvec3& n, double cos_theta, double phi) {
  glm::dvec3 t, b;
  tangents(n, t, b);
  const double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  return glm::normalize(n * cos_theta + (t * std::cos(phi) + b * std::sin(phi)) * s);
}

double hg_pdf(double c, double g) {
  const double g2 = g * g;
  return (1.0 - g2) / (4.0 * kPi * std::pow(1.0 + g2 - 2.0 * g * c, 1.5));
}

double hg_sample_cos(double u, double g) {
  const double g2 = g * g, s = (1.0 - g2) / (1.0 - g + 2.0 * g * u);
  return (1.0 + g2 - s * s) / (2.0 * g);
}

// One path's contribution (radiance relative to the extraterrestrial spectral irradiance) and
// its number of scattering events.
double trace(const Medium& m, glm::dvec3 p, glm::dvec3 d, const glm::dvec3& sun,
             const SkyMonteCarloOptions& o, Rng& rng, int& events) {
  double throughput = 1.0, radiance = 0.0;
  events = 0;
  for (;;) {
    // The free flight: to a real collision, the ground, or out of the atmosphere.
    const double ground = to_sphere(p, d, kEarthRadius, false);
    const double top = to_sphere(p, d, kTopRadius, true);
    const double limit = ground > 0.0 ? ground : top;
    double t = 0.0;
    bool collided = false;
    for (;;) {
      t -= std::log(1.0 - rng.uniform()) / m.majorant;
      if (t >= limit) break;
      const double h = std::max(0.0, m.height(p + d * t));
      if (rng.uniform() * m.majorant < m.extinction(h)) {
        collided = true;
        break;
      }
    }
    if (!collided && ground <= 0.0) return radiance;  // out to space: the sun is sampled, not hit
    ++events;
    if (!collided) {
      // The ground: Lambertian, the sun sampled, then a cosine-distributed bounce.
      if (o.single_scattering || o.ground_albedo <= 0.0) return radiance;
      p = p + d * ground;
      const glm::dvec3 n = glm::normalize(p);
      p = n * (kEarthRadius + 1e-3);
      const double cos_sun = glm::dot(n, sun);
      if (cos_sun > 0.0)
        radiance += throughput * o.ground_albedo / kPi * cos_sun * sun_transmittance(m, p, sun);
      if (events == o.max_orders) return radiance;
      throughput *= o.ground_albedo;
      d = around(n, std::sqrt(rng.uniform()), 2.0 * kPi * rng.uniform());
    } else {
      p = p + d * t;
      const double h = std::max(0.0, m.height(p));
      const double sr = m.rayleigh(h), sm = kMieScattering * m.mie_density(h);
      const double ss = sr + sm;
      throughput *= ss / m.extinction(h);
      // Light from the sun (travelling −sun) scattered back along −d: cos θ = sun · d.
      const double cs = glm::dot(sun, d);
      const double phase = (sr * rayleigh_phase(cs) + sm * mie_phase(cs)) / ss;
      radiance += throughput * phase * sun_transmittance(m, p, sun);
      if (o.single_scattering || events == o.max_orders) return radiance;
      // The next direction d' (light arriving along −d' leaves along −d: cos θ = d · d').
      const double pick_r = sr / ss;
      glm::dvec3 next;
      if (rng.uniform() < pick_r) {
        next = around(d, 2.0 * rng.uniform() - 1.0, 2.0 * kPi * rng.uniform());
      } else {
        next = around(d, hg_sample_cos(rng.uniform(), kMieG), 2.0 * kPi * rng.uniform());
      }
      const double c = glm::dot(d, next);
      const double value = (sr * rayleigh_phase(c) + sm * mie_phase(c)) / ss;
      const double pdf = pick_r / (4.0 * kPi) + (1.0 - pick_r) * hg_pdf(c, kMieG);
      throughput *= value / pdf;
      d = next;
    }
    if (events >= 4) {
      const double q = std::min(1.0, throughput);
      if (rng.uniform() >= q) return radiance;
      throughput /= q;
    }
  }
}

}  // namespace

SkyMonteCarloResult simulate_sky_radiance(const NishitaSky& units, const Atmosphere& atmosphere,
                                          const glm::dvec3& sun_direction, const glm::dvec3& view,
                                          const SkyMonteCarloOptions& o) {
  const glm::dvec3 sun = glm::normalize(sun_direction), d = glm::normalize(view);
  constexpr int kW = NishitaSky::kWavelengths;
  std::array<glm::dvec3, kW> weight{};
  std::array<double, kW> cdf{}, beta_r{}, sigma_o{};
  double total = 0.0;
  for (int k = 0; k < kW; ++k) {
    weight[k] = units.spectral_weight(k);
    total += weight[k].x + weight[k].y + weight[k].z;
    cdf[k] = total;
    const double nm = NishitaSky::wavelength(k);
    beta_r[k] = NishitaSky::rayleigh_scattering(nm);
    sigma_o[k] = NishitaSky::ozone_cross_section(nm) * kOzonePeakDensity;
  }
  Rng rng(derive_key(o.seed, 0x736b794d43ull));
  const glm::dvec3 observer(0.0, 0.0, kEarthRadius + atmosphere.altitude);
  glm::dvec3 sum(0.0), sum2(0.0);
  double events = 0.0;
  for (int i = 0; i < o.paths; ++i) {
    const double u = rng.uniform() * total;
    const int k = static_cast<int>(std::lower_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
    const int kk = std::min(k, kW - 1);
    const Medium m{atmosphere, beta_r[kk], sigma_o[kk],
                   beta_r[kk] * atmosphere.air_density + kMieExtinction * atmosphere.dust_density +
                       sigma_o[kk] * atmosphere.ozone_density};
    int n = 0;
    const double l = trace(m, observer, d, sun, o, rng, n);
    const glm::dvec3 w = weight[kk];
    const glm::dvec3 x = l * w * (total / (w.x + w.y + w.z));
    sum += x;
    sum2 += x * x;
    events += n;
  }
  SkyMonteCarloResult r;
  const double n = o.paths;
  r.xyz = sum / n;
  r.standard_error = glm::sqrt(glm::max(glm::dvec3(0.0), sum2 / n - r.xyz * r.xyz) / (n - 1.0));
  r.mean_orders = events / n;
  return r;
}

}  // namespace arbor::tracer
