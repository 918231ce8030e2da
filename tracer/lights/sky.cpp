// Sky radiance maps, their importance sampling, the Preetham model and the sun disk.
#include "tracer/lights/sky.h"

#include <algorithm>
#include <cmath>

#include <OpenImageIO/imagebuf.h>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/error.h"
#include "common/input_file.h"
#include "imaging/color.h"
#include "common/math.h"
#include "tracer/lights/nishita.h"


namespace arbor::trace {

namespace {
constexpr float kPif = static_cast<float>(kPi);

double perez(double theta, double gamma, const double c[5]) {
  // Perez et al. luminance distribution: (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ).
  const double cos_theta = std::max(std::cos(theta), 1e-3);
  return (1.0 + c[0] * std::exp(c[1] / cos_theta)) *
         (1.0 + c[2] * std::exp(c[3] * gamma) + c[4] * std::cos(gamma) * std::cos(gamma));
}
}  // namespace

glm::dvec3 preetham_xyz(double T, double theta, double gamma, double theta_s, double sun_e) {
  // Preetham, Shirley & Smits 1999, appendix: Perez coefficients linear in turbidity T.
  const double cY[5] = {0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251,
                        0.1206 * T - 2.5771, -0.0670 * T + 0.3703};
  const double cx[5] = {-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125,
                        -0.0641 * T - 0.8989, -0.0033 * T + 0.0452};
  const double cy[5] = {-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102,
                        -0.0441 * T - 1.6537, -0.0109 * T + 0.0529};
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2.0 * theta_s);
  const double Yz = (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;  // kcd/m²
  const double t2 = theta_s * theta_s, t3 = t2 * theta_s;
  const double xz = T * T * (0.00166 * t3 - 0.00375 * t2 + 0.00209 * theta_s) +
                    T * (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * theta_s + 0.00394) +
                    (0.11693 * t3 - 0.21196 * t2 + 0.06052 * theta_s + 0.25886);
  const double yz = T * T * (0.00275 * t3 - 0.00610 * t2 + 0.00317 * theta_s) +
                    T * (-0.04214 * t3 + 0.08970 * t2 - 0.04153 * theta_s + 0.00516) +
                    (0.15346 * t3 - 0.26756 * t2 + 0.06670 * theta_s + 0.26688);
  const double Y = Yz * perez(theta, gamma, cY) / perez(0.0, theta_s, cY);
  const double x = xz * perez(theta, gamma, cx) / perez(0.0, theta_s, cx);
  const double y = yz * perez(theta, gamma, cy) / perez(0.0, theta_s, cy);
  // xyY → XYZ. A sun of irradiance E stands for 100 klux: the sky keeps the model's ratio to it.
  const double X = x / y * Y, Z = (1.0 - x - y) / y * Y;
  const double scale = std::max(0.0, sun_e) * 1000.0 / 100000.0;
  return glm::dvec3(X, Y, Z) * scale;
}

Sky::Sky(const SkySpec& sky, const SunSpec& sun, const ColorTransform& xyz_to_linear, int width) {
  const double elevation = sun.elevation * kPi / 180.0, azimuth = sun.azimuth * kPi / 180.0;
  sun_direction_d_ = glm::dvec3(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                std::sin(elevation));
  sun_direction_ = glm::vec3(sun_direction_d_);
  if (sun.enabled && sun.irradiance > 0.0) {
    // E = ∫ L cos θ dω over the disk = L π sin²(α): uniform radiance L = E / (π sin² α).
    const double alpha = 0.5 * sun.angular_diameter * kPi / 180.0;
    // 1 - cos α in double (2 sin²(α/2), no cancellation): as a float cos α it was 0.18 % off at
    // α = 0.25°, and with it the sun's pdf and the ground it lights.
    sun_one_minus_cos_ = 2.0 * std::sin(0.5 * alpha) * std::sin(0.5 * alpha);
    sun_radiance_ = glm::vec3(static_cast<float>(sun.irradiance / (kPi * std::sin(alpha) * std::sin(alpha))));
    sun_irradiance_ = static_cast<float>(sun.irradiance);
    sun_irradiance_color_ = glm::vec3(sun_irradiance_);
    sun_present_ = true;
  }
  if (sky.model == SkyModel::None) return;
  rotation_ = static_cast<float>(sky.rotation * kPi / 180.0);
  if (sky.model == SkyModel::Envmap) {
    check_input_file(sky.path, "environment map");
    OIIO::ImageBuf image(sky.path);
    if (!image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
      throw InputError({sky.path, 0, 0}, "cannot read the environment map: " + image.geterror());
    }
    const OIIO::ImageSpec& spec = image.spec();
    width_ = spec.width;
    height_ = spec.height;
    map_.resize(static_cast<size_t>(width_) * height_);
    std::vector<float> pixel(static_cast<size_t>(std::max(3, spec.nchannels)));
    for (int j = 0; j < height_; ++j) {
      for (int i = 0; i < width_; ++i) {
        image.getpixel(i, j, pixel.data(), static_cast<int>(pixel.size()));
        const glm::vec3 c = spec.nchannels >= 3 ? glm::vec3(pixel[0], pixel[1], pixel[2])
                                                : glm::vec3(pixel[0]);
        if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) {
          throw InputError({sky.path, 0, 0}, "the environment map has a pixel that is not finite");
        }
        map_[static_cast<size_t>(j) * width_ + i] = glm::max(c, glm::vec3(0.0f)) * static_cast<float>(sky.scale);
      }
    }
  } else if (sky.model == SkyModel::Nishita) {
    nishita(sky, sun, xyz_to_linear, width);
  } else {
    width_ = width;
    height_ = width / 2;
    map_.resize(static_cast<size_t>(width_) * height_);
    const double theta_s = kPi / 2.0 - elevation;
    for (int j = 0; j < height_; ++j) {
      for (int i = 0; i < width_; ++i) {
        const glm::vec3 d = from_map({(i + 0.5f) / width_, (j + 0.5f) / height_});
        glm::vec3 c(0.0f);
        if (sky.model == SkyModel::Constant) {
          c = glm::vec3(sky.color[0], sky.color[1], sky.color[2]);
        } else if (d.z > 0.0f) {
          const double gamma = std::acos(std::clamp(double(glm::dot(d, sun_direction_)), -1.0, 1.0));
          const glm::dvec3 xyz = preetham_xyz(sky.turbidity, std::acos(double(d.z)), gamma,
                                              std::min(theta_s, kPi / 2.0 - 1e-3), sun.irradiance);
          float rgb[3] = {static_cast<float>(xyz.x), static_cast<float>(xyz.y), static_cast<float>(xyz.z)};
          xyz_to_linear(rgb);
          // Out-of-gamut negatives (none for daylight) would be emission of negative light.
          c = glm::max(glm::vec3(rgb[0], rgb[1], rgb[2]), glm::vec3(0.0f));
        }
        map_[static_cast<size_t>(j) * width_ + i] = c;
      }
    }
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
  const double texel = 2.0 * kPi * kPi / (static_cast<double>(width_) * height_);
  for (int j = 0; j < height_; ++j) {
    const double theta = kPi * (j + 0.5) / height_;
    const double cos_theta = std::cos(theta);
    if (cos_theta <= 0.0) continue;
    glm::dvec3 row(0.0);
    for (int i = 0; i < width_; ++i) row += glm::dvec3(map_[static_cast<size_t>(j) * width_ + i]);
    e += row * (cos_theta * std::sin(theta) * texel);
  }
  irradiance_up_ = glm::vec3(e);
  present_ = !distribution_.empty();
}

void Sky::nishita(const SkySpec& sky, const SunSpec& sun, const ColorTransform& xyz_to_linear, int width) {
  width_ = width;
  height_ = width / 2;
  map_.assign(static_cast<size_t>(width_) * height_, glm::vec3(0.0f));
  Atmosphere atmosphere;
  atmosphere.air_density = sky.air_density;
  atmosphere.dust_density = sky.dust_density;
  atmosphere.ozone_density = sky.ozone_density;
  atmosphere.altitude = sky.altitude;
  // [sun] irradiance is the sun's outside the atmosphere (as CIE Y); what reaches the ground is
  // what the atmosphere lets through, coloured by it. As with Preetham's sky, the sky is lit by
  // that sun even when [sun] enabled = false (which removes only its disk).
  const NishitaSky model(atmosphere, sun_direction_d_, sun.irradiance);
  auto convert = [&](const glm::dvec3& xyz) {
    float rgb[3] = {static_cast<float>(xyz.x), static_cast<float>(xyz.y), static_cast<float>(xyz.z)};
    xyz_to_linear(rgb);
    return glm::dvec3(rgb[0], rgb[1], rgb[2]);
  };
  // White balance: the sun outside the atmosphere is white in the rendering space (as the other
  // models' sun is), so the colours are the atmosphere's alone — a channel scale in that space.
  const glm::dvec3 space = convert(model.extraterrestrial_xyz());
  const double space_y = model.extraterrestrial_xyz().y;
  const glm::dvec3 balance = glm::all(glm::greaterThan(space, glm::dvec3(0.0))) ? space_y / space : glm::dvec3(1.0);
  auto to_linear = [&](const glm::dvec3& xyz) {
    return glm::max(glm::vec3(convert(xyz) * balance), glm::vec3(0.0f));
  };
  // Rows are independent: in parallel, each texel the same whatever the thread.
  tbb::parallel_for(tbb::blocked_range<int>(0, height_ / 2 + 1), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j < rows.end(); ++j) {
      for (int i = 0; i < width_; ++i) {
        const glm::vec3 d = from_map({(i + 0.5f) / width_, (j + 0.5f) / height_});
        if (d.z <= 0.0f) continue;
        map_[static_cast<size_t>(j) * width_ + i] = to_linear(model.radiance_xyz(glm::dvec3(d)));
      }
    }
  });
  if (sun_present_) {
    const glm::vec3 e = to_linear(model.sun_irradiance_xyz());
    const double alpha = 0.5 * sun.angular_diameter * kPi / 180.0;
    sun_radiance_ = e / static_cast<float>(kPi * std::sin(alpha) * std::sin(alpha));
    sun_irradiance_color_ = e;
    sun_irradiance_ = (e.x + e.y + e.z) / 3.0f;
    sun_present_ = sun_irradiance_ > 0.0f;  // a sun below the horizon lights nothing directly
    if (!sun_present_) sun_radiance_ = sun_irradiance_color_ = glm::vec3(0.0f);
  }
}

glm::vec2 Sky::to_map(const glm::vec3& d) const {
  float phi = std::atan2(d.y, d.x) - rotation_;
  phi -= 2.0f * kPif * std::floor(phi / (2.0f * kPif));
  const float theta = std::acos(std::clamp(d.z, -1.0f, 1.0f));
  return {phi / (2.0f * kPif), theta / kPif};
}

glm::vec3 Sky::from_map(glm::vec2 p) const {
  const float phi = p.x * 2.0f * kPif + rotation_, theta = p.y * kPif;
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

glm::vec3 Sky::map_at(glm::vec2 p) const {
  const int i = std::clamp(static_cast<int>(p.x * width_), 0, width_ - 1);
  const int j = std::clamp(static_cast<int>(p.y * height_), 0, height_ - 1);
  return map_[static_cast<size_t>(j) * width_ + i];
}

glm::vec3 Sky::radiance(const glm::vec3& d) const { return present_ ? map_at(to_map(d)) : glm::vec3(0.0f); }

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
  s.direction = glm::vec3(glm::normalize(x * (sin_t * std::cos(phi)) + y * (sin_t * std::sin(phi)) + w * cos_t));
  s.radiance = sun_radiance_;
  s.pdf = sun_pdf();
  return s;
}

}  // namespace arbor::trace
