#include "scene/render_input.h"

#include <stdexcept>

namespace arbor::trace {

namespace {

// The enum value named `name` in `names`; the reader has checked it, so another is a bug.
template <typename Enum, std::size_t N>
Enum named(const std::string& name, const std::array<const char*, N>& names, const char* what) {
  for (std::size_t i = 0; i < N; ++i) {
    if (name == names[i]) return static_cast<Enum>(i);
  }
  throw std::logic_error(std::string("render_input: unknown ") + what + " \"" + name + "\"");
}

glm::dvec3 vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }

}  // namespace

const char* name_of(Integrator integrator) { return kIntegratorNames[static_cast<std::size_t>(integrator)]; }
std::optional<Integrator> integrator_named(std::string_view name) {
  for (std::size_t i = 0; i < kIntegratorNames.size(); ++i) {
    if (name == kIntegratorNames[i]) return static_cast<Integrator>(i);
  }
  return std::nullopt;
}

const char* name_of(SkyModel model) { return kSkyModelNames[static_cast<std::size_t>(model)]; }

CameraSpec camera_spec(const CameraDesc& c) {
  return {vec(c.position), vec(c.look_at), vec(c.up), c.fov, c.aperture_radius, c.focus_distance, c.exposure};
}

SunSpec sun_spec(const SunDesc& s) { return {s.enabled, s.elevation, s.azimuth, s.irradiance, s.angular_diameter}; }

SkySpec sky_spec(const SkyDesc& s) {
  SkySpec sky;
  sky.model = named<SkyModel>(s.model, kSkyModelNames, "sky model");
  sky.turbidity = s.turbidity;
  sky.air_density = s.air_density;
  sky.dust_density = s.dust_density;
  sky.ozone_density = s.ozone_density;
  sky.altitude = s.altitude;
  sky.color = {s.color[0], s.color[1], s.color[2]};
  sky.path = s.path;
  sky.rotation = s.rotation;
  sky.scale = s.scale;
  return sky;
}

RenderInput render_input(const SceneDesc& d) {
  RenderInput in;
  in.scene = d.path;
  const RenderSettings& r = d.render;
  in.render = {r.width,
               r.height,
               r.spp,
               r.seed,
               named<Integrator>(r.integrator, kIntegratorNames, "integrator"),
               r.max_depth,
               r.treemaker_spp,
               r.pass_spp,
               r.independent_passes,
               r.noise_threshold,
               r.min_spp,
               r.threads};
  check_camera(d.camera);  // the reader checked it; a description made in code is checked here
  in.camera = camera_spec(d.camera);
  in.sun = sun_spec(d.sun);
  in.sky = sky_spec(d.sky);
  in.output = d.output;
  return in;
}

}  // namespace arbor::trace
