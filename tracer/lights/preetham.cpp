// The Preetham, Shirley & Smits 1999 daylight sky (its appendix): Perez distributions of
// luminance and chromaticity, linear in turbidity.
#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "common/math.h"
#include "tracer/lights/sky_model.h"

namespace arbor::tracer {

namespace {

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

SkyMap preetham_sky_map(const SkyContext& c) {
  SkyMap map;
  map.width = c.width;
  map.height = c.width / 2;
  map.texels.resize(static_cast<size_t>(map.width) * map.height);
  const double elevation = c.sun.elevation * kPi / 180.0;
  const double theta_s = kPi / 2.0 - elevation;
  const glm::vec3 sun_direction(c.sun_direction);
  for (int j = 0; j < map.height; ++j) {
    for (int i = 0; i < map.width; ++i) {
      const glm::vec3 d =
          lat_long_direction({(i + 0.5f) / map.width, (j + 0.5f) / map.height}, c.rotation);
      glm::vec3 colour(0.0f);
      if (d.z > 0.0f) {
        const double gamma = std::acos(std::clamp(double(glm::dot(d, sun_direction)), -1.0, 1.0));
        const glm::dvec3 xyz = preetham_xyz(c.sky.turbidity, std::acos(double(d.z)), gamma,
                                            std::min(theta_s, kPi / 2.0 - 1e-3), c.sun.irradiance);
        float rgb[3] = {static_cast<float>(xyz.x), static_cast<float>(xyz.y),
                        static_cast<float>(xyz.z)};
        c.xyz_to_linear(rgb);
        // Out-of-gamut negatives (none for daylight) would be emission of negative light.
        colour = glm::max(glm::vec3(rgb[0], rgb[1], rgb[2]), glm::vec3(0.0f));
      }
      map.texels[static_cast<size_t>(j) * map.width + i] = colour;
    }
  }
  return map;
}

}  // namespace arbor::tracer
