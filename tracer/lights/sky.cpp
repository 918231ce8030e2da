// The sky: a model's radiance map (sky_model.h) importance-sampled, and the sun disk.
#include "tracer/lights/sky.h"

#include "tracer/lights/limb_darkening.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "imaging/color.h"
#include "common/math.h"

namespace arbor::tracer {

namespace {
constexpr float kPif = static_cast<float>(kPi);
constexpr int kLimbSteps = 33;  // the limb darkening's table over the disk's radius

// The limb darkening's table, scaled so that as Sky::limb_at interpolates it its area mean is
// exactly 1 (the irradiance E, not 0.3 % less): ∫ 2s p(s) ds of each linear piece a + b s.
std::vector<glm::vec3> limb_table(const imaging::ColorTransform& xyz_to_linear) {
  std::vector<glm::vec3> limb = solar_limb_profile(xyz_to_linear, kLimbSteps);
  glm::dvec3 mean(0.0);
  for (int i = 0; i + 1 < kLimbSteps; ++i) {
    const double s0 = double(i) / (kLimbSteps - 1), s1 = double(i + 1) / (kLimbSteps - 1);
    const glm::dvec3 p0(limb[static_cast<std::size_t>(i)]),
        p1(limb[static_cast<std::size_t>(i) + 1]);
    const glm::dvec3 b = (p1 - p0) / (s1 - s0), a = p0 - b * s0;
    mean += a * (s1 * s1 - s0 * s0) + b * (2.0 / 3.0) * (s1 * s1 * s1 - s0 * s0 * s0);
  }
  for (glm::vec3& v : limb) v = glm::vec3(glm::dvec3(v) / mean);
  return limb;
}

}  // namespace

Sky::Sky(const spec::SkyDesc& sky, const spec::SunDesc& sun,
         const imaging::ColorTransform& xyz_to_linear, int width, bool aerial_perspective) {
  const double elevation = sun.elevation * kPi / 180.0, azimuth = sun.azimuth * kPi / 180.0;
  sun_direction_d_ = glm::dvec3(std::cos(elevation) * std::cos(azimuth),
                                std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
  sun_direction_ = glm::vec3(sun_direction_d_);
  if (sun.enabled && sun.irradiance > 0.0) {
    // E = ∫ L cos θ dω over the disk = L π sin²(α): uniform radiance L = E / (π sin² α).
    const double alpha = 0.5 * sun.angular_diameter * kPi / 180.0;
    // 1 - cos α in double (2 sin²(α/2), no cancellation): as a float cos α it was 0.18 % off at
    // α = 0.25°, and with it the sun's pdf and the ground it lights.
    sun_one_minus_cos_ = 2.0 * std::sin(0.5 * alpha) * std::sin(0.5 * alpha);
    sun_radiance_ =
        glm::vec3(static_cast<float>(sun.irradiance / (kPi * std::sin(alpha) * std::sin(alpha))));
    sun_irradiance_ = static_cast<float>(sun.irradiance);
    sun_irradiance_color_ = glm::vec3(sun_irradiance_);
    sun_present_ = true;
    limb_ = limb_table(xyz_to_linear);
  }
  if (sky.model == spec::SkyModel::None) return;
  rotation_ = static_cast<float>(sky.rotation * kPi / 180.0);
  SkyMap map = make_sky_map(
      {sky, sun, sun_direction_d_, xyz_to_linear, width, rotation_, aerial_perspective});
  width_ = map.width;
  height_ = map.height;
  map_ = std::move(map.texels);
  aerial_ = std::move(map.aerial);
  if (map.sun_irradiance && sun_present_) {
    // The atmosphere's sun: coloured and dimmed on its way to the ground.
    const glm::vec3 e = *map.sun_irradiance;
    const double alpha = 0.5 * sun.angular_diameter * kPi / 180.0;
    sun_radiance_ = e / static_cast<float>(kPi * std::sin(alpha) * std::sin(alpha));
    sun_irradiance_color_ = e;
    sun_irradiance_ = (e.x + e.y + e.z) / 3.0f;
    sun_present_ = sun_irradiance_ > 0.0f;  // a sun below the horizon lights nothing directly
    if (!sun_present_) sun_radiance_ = sun_irradiance_color_ = glm::vec3(0.0f);
  }
  // Sampling weights: luminance × sin θ (the lat-long map's area element).
  std::vector<float> w(map_.size());
  for (int j = 0; j < height_; ++j) {
    const float sin_theta = std::sin(kPif * (j + 0.5f) / height_);
    for (int i = 0; i < width_; ++i) {
      const glm::vec3 c = map_[static_cast<size_t>(j) * width_ + i];
      w[static_cast<size_t>(j) * width_ + i] = luminance(c.x, c.y, c.z) * sin_theta;
    }
  }
  distribution_ = Distribution2D(w, width_, height_);
  // Each texel covers (2π / width) (π / height) sin θ of solid angle.
  glm::dvec3 e(0.0);
  double e_lum = 0.0, e2_lum = 0.0;  // ∫ Y cos θ dω and ∫ Y² cos θ dω over the upper hemisphere
  const double texel = 2.0 * kPi * kPi / (static_cast<double>(width_) * height_);
  for (int j = 0; j < height_; ++j) {
    const double theta = kPi * (j + 0.5) / height_;
    const double cos_theta = std::cos(theta);
    if (cos_theta <= 0.0) continue;
    glm::dvec3 row(0.0);
    double row_y = 0.0, row_y2 = 0.0;
    for (int i = 0; i < width_; ++i) {
      const glm::vec3 c = map_[static_cast<size_t>(j) * width_ + i];
      row += glm::dvec3(c);
      const double y = luminance(c.x, c.y, c.z);
      row_y += y;
      row_y2 += y * y;
    }
    const double dw = cos_theta * std::sin(theta) * texel;
    e += row * dw;
    e_lum += row_y * dw;
    e2_lum += row_y2 * dw;
  }
  // Cosine sampling (pdf cos θ / π) estimates E = ∫ Y cos θ dω by π Y(ω): its relative variance
  // is π ∫ Y² cos θ dω / E² − 1, 0 for a constant sky.
  cosine_variance_up_ =
      e_lum > 0.0 ? static_cast<float>(kPi * e2_lum / (e_lum * e_lum) - 1.0) : 0.0f;
  irradiance_up_ = glm::vec3(e);
  present_ = !distribution_.empty();
}

glm::vec2 Sky::to_map(const glm::vec3& d) const {
  float phi = std::atan2(d.y, d.x) - rotation_;
  phi -= 2.0f * kPif * std::floor(phi / (2.0f * kPif));
  const float theta = std::acos(std::clamp(d.z, -1.0f, 1.0f));
  return {phi / (2.0f * kPif), theta / kPif};
}

glm::vec3 Sky::from_map(glm::vec2 p) const { return lat_long_direction(p, rotation_); }

glm::vec3 Sky::map_at(glm::vec2 p) const {
  const int i = std::clamp(static_cast<int>(p.x * width_), 0, width_ - 1);
  const int j = std::clamp(static_cast<int>(p.y * height_), 0, height_ - 1);
  return map_[static_cast<size_t>(j) * width_ + i];
}

glm::vec3 Sky::radiance(const glm::vec3& d) const {
  return present_ ? map_at(to_map(d)) : glm::vec3(0.0f);
}

LightSample Sky::lookup(const glm::vec3& d) const {
  LightSample s;
  s.direction = d;
  if (!present_) return s;
  const glm::vec2 p = to_map(d);
  s.radiance = map_at(p);
  const float sin_theta = std::sin(p.y * kPif);
  s.pdf = sin_theta > 0.0f ? distribution_.pdf(p) / (2.0f * kPif * kPif * sin_theta) : 0.0f;
  return s;
}

LightSample Sky::sample(glm::vec2 u) const {
  LightSample s;
  if (!present_) return s;
  float pdf_map = 0.0f;
  const glm::vec2 p = distribution_.sample(u, pdf_map);
  s.direction = from_map(p);
  if (pdf_map <= 0.0f) return s;
  // The density of the direction actually returned: a point on a cell edge can round into the
  // neighbouring cell, and MIS needs sample() and pdf() to agree exactly.
  const LightSample at = lookup(s.direction);
  s.pdf = at.pdf;
  s.radiance = at.radiance;
  return s;
}

float Sky::pdf(const glm::vec3& d) const { return lookup(d).pdf; }

bool Sky::in_sun(const glm::vec3& d) const {
  if (!sun_present_) return false;
  // 1 - cos θ from the chord, |d̂ - w|² / 2, in double: a float dot product near 1 has an error
  // of about 1 % of the cone.
  const glm::dvec3 dd = glm::normalize(glm::dvec3(d)), w(sun_direction_d_);
  const glm::dvec3 chord = dd - w;
  return 0.5 * glm::dot(chord, chord) <= sun_one_minus_cos_;
}

glm::vec3 Sky::limb_at(double one_minus_cos) const {
  // s = θ / α from the cones' 1 − cos (θ² / 2 to within θ⁴ / 24), linear between table points.
  const double s = std::sqrt(std::clamp(one_minus_cos / sun_one_minus_cos_, 0.0, 1.0));
  const double x = s * (kLimbSteps - 1);
  const int i = std::min(kLimbSteps - 2, static_cast<int>(x));
  const float f = static_cast<float>(x - i);
  return (1.0f - f) * limb_[static_cast<std::size_t>(i)] +
         f * limb_[static_cast<std::size_t>(i) + 1];
}

glm::vec3 Sky::sun_radiance(const glm::vec3& direction) const {
  if (!sun_present_) return glm::vec3(0.0f);
  const glm::dvec3 chord = glm::normalize(glm::dvec3(direction)) - sun_direction_d_;
  return sun_radiance_ * limb_at(0.5 * glm::dot(chord, chord));
}

float Sky::sun_pdf() const { return static_cast<float>(1.0 / (2.0 * kPi * sun_one_minus_cos_)); }

LightSample Sky::sample_sun(glm::vec2 u) const {
  LightSample s;
  if (!sun_present_) return s;
  // Uniform direction in the cone around the sun: 1 - cos θ = u (1 - cos α), uniform, and
  // sin θ = sqrt(h (2 - h)) from it, in double (near 1, a float cos θ has 160 levels in the cone).
  const double h = static_cast<double>(u.x) * sun_one_minus_cos_;
  const double cos_t = 1.0 - h, sin_t = std::sqrt(h * (2.0 - h));
  const double phi = 2.0 * kPi * static_cast<double>(u.y);
  const glm::dvec3 w(sun_direction_d_);
  const glm::dvec3 a = std::fabs(w.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  const glm::dvec3 x = glm::normalize(glm::cross(a, w)), y = glm::cross(w, x);
  s.direction = glm::vec3(
      glm::normalize(x * (sin_t * std::cos(phi)) + y * (sin_t * std::sin(phi)) + w * cos_t));
  s.radiance = sun_radiance_;  // the light it casts: the uniform disk's (sky.h)
  s.pdf = sun_pdf();
  return s;
}

}  // namespace arbor::tracer
