// Nishita's single-scattering sky (nishita.h), or the atmosphere's every order, as a map,
// white-balanced to the sun outside the atmosphere, and the sun's irradiance at the ground through
// the same atmosphere; and, when asked for, the same atmosphere's aerial perspective (aerial.h).
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include "tracer/lights/aerial.h"
#include "tracer/lights/nishita.h"
#include "tracer/lights/sky_model.h"

namespace arbor::tracer {

namespace {

Atmosphere atmosphere_of(const SkyContext& c) {
  Atmosphere atmosphere;
  atmosphere.air_density = c.sky.air_density;
  atmosphere.dust_density = c.sky.dust_density;
  atmosphere.ozone_density = c.sky.ozone_density;
  atmosphere.altitude = c.sky.altitude;
  if (c.sky.model == spec::SkyModel::Atmosphere) {
    // Every order of scattering over a ground of the albedo given; the aerosols by the key given.
    atmosphere.multiple_scattering = true;
    atmosphere.ground_albedo = spec::ground_albedo_under(c.sky);
    if (!c.sky.dust_given) {
      atmosphere.dust_density = c.sky.visibility > 0.0
                                    ? atmosphere::dust_for_visibility(c.sky.visibility)
                                    : atmosphere::dust_for_turbidity(c.sky.turbidity);
    }
  }
  return atmosphere;
}

// [sun] irradiance is the sun's outside the atmosphere (as CIE Y); what reaches the ground is
// what the atmosphere lets through, coloured by it. As with Preetham's sky, the sky is lit by
// that sun even when [sun] enabled = false (which removes only its disk).
NishitaSky model_of(const SkyContext& c) {
  return NishitaSky(atmosphere_of(c), c.sun_direction, c.sun.irradiance);
}

// CIE XYZ to the rendering space, white-balanced: the sun outside the atmosphere is white in the
// rendering space (as the other models' sun is), so the colours are the atmosphere's alone — a
// channel scale in that space.
struct ToLinear {
  ToLinear(const SkyContext& c, const NishitaSky& model) : c_(c) {
    const glm::dvec3 space = convert(model.extraterrestrial_xyz());
    const double space_y = model.extraterrestrial_xyz().y;
    balance_ =
        glm::all(glm::greaterThan(space, glm::dvec3(0.0))) ? space_y / space : glm::dvec3(1.0);
  }
  glm::vec3 operator()(const glm::dvec3& xyz) const {
    return glm::max(glm::vec3(convert(xyz) * balance_), glm::vec3(0.0f));
  }

 private:
  glm::dvec3 convert(const glm::dvec3& xyz) const {
    float rgb[3] = {static_cast<float>(xyz.x), static_cast<float>(xyz.y),
                    static_cast<float>(xyz.z)};
    c_.xyz_to_linear(rgb);
    return glm::dvec3(rgb[0], rgb[1], rgb[2]);
  }
  const SkyContext& c_;
  glm::dvec3 balance_{1.0};
};

std::shared_ptr<const AerialPerspective> aerial_of(const NishitaSky& model, const ToLinear& to) {
  return std::make_shared<const AerialPerspective>(model, to, model.extraterrestrial_xyz().y);
}

}  // namespace

SkyMap nishita_sky_map(const SkyContext& c) {
  SkyMap map;
  map.width = c.width;
  map.height = c.width / 2;
  map.texels.assign(static_cast<size_t>(map.width) * map.height, glm::vec3(0.0f));
  const NishitaSky model = model_of(c);
  const ToLinear to_linear(c, model);
  // Rows are independent: in parallel, each texel the same whatever the thread.
  tbb::parallel_for(
      tbb::blocked_range<int>(0, map.height / 2 + 1), [&](const tbb::blocked_range<int>& rows) {
        for (int j = rows.begin(); j < rows.end(); ++j) {
          for (int i = 0; i < map.width; ++i) {
            const glm::vec3 d =
                lat_long_direction({(i + 0.5f) / map.width, (j + 0.5f) / map.height}, c.rotation);
            if (d.z <= 0.0f) continue;
            map.texels[static_cast<size_t>(j) * map.width + i] =
                to_linear(model.radiance_xyz(glm::dvec3(d)));
          }
        }
      });
  map.sun_irradiance = to_linear(model.sun_irradiance_xyz());
  if (c.aerial_perspective) map.aerial = aerial_of(model, to_linear);
  return map;
}

std::shared_ptr<const AerialPerspective> nishita_aerial(const SkyContext& c) {
  // The map came from the disk cache: the model only for its path integrals.
  Atmosphere atmosphere = atmosphere_of(c);
  atmosphere.sky = false;
  const NishitaSky model(atmosphere, c.sun_direction, c.sun.irradiance);
  return aerial_of(model, ToLinear(c, model));
}

}  // namespace arbor::tracer
