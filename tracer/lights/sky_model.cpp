// The factory of sky maps, keyed by the model.
#include "tracer/lights/sky_model.h"

#include <cmath>
#include <stdexcept>

#include "common/math.h"
#include "tracer/lights/sky_cache.h"

namespace arbor::tracer {

// One per model, each in its own file.
SkyMap preetham_sky_map(const SkyContext& context);
SkyMap constant_sky_map(const SkyContext& context);
SkyMap envmap_sky_map(const SkyContext& context);
SkyMap nishita_sky_map(const SkyContext& context);
std::shared_ptr<const AerialPerspective> nishita_aerial(const SkyContext& context);

namespace {

// The Nishita or atmosphere map from the cache, with its aerial perspective when asked for (a
// map read back has none: it is made from the model again).
SkyMap atmosphere_map(const SkyContext& context, const char* model) {
  SkyMap map = cached_sky_map(context, model, nishita_sky_map);
  if (context.aerial_perspective && !map.aerial) map.aerial = nishita_aerial(context);
  return map;
}

}  // namespace

SkyMap make_sky_map(const SkyContext& context) {
  switch (context.sky.model) {
    case spec::SkyModel::Preetham: return preetham_sky_map(context);
    case spec::SkyModel::Constant: return constant_sky_map(context);
    case spec::SkyModel::Envmap: return envmap_sky_map(context);
    case spec::SkyModel::Nishita: return atmosphere_map(context, "nishita");
    case spec::SkyModel::Atmosphere: return atmosphere_map(context, "atmosphere");
    case spec::SkyModel::None: break;
  }
  throw std::logic_error("make_sky_map: no map for this sky model");
}

glm::vec3 lat_long_direction(glm::vec2 p, float rotation) {
  constexpr float kPif = static_cast<float>(kPi);
  const float phi = p.x * 2.0f * kPif + rotation, theta = p.y * kPif;
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

}  // namespace arbor::tracer
