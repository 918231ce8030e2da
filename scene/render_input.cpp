#include "scene/render_input.h"

#include "scene/terrain.h"

namespace arbor::scene {

namespace {

glm::dvec3 vec(const formats::Vec3d& v) { return {v[0], v[1], v[2]}; }

}  // namespace

CameraSpec camera_spec(const formats::CameraDesc& c) {
  return {vec(c.position),   vec(c.look_at),   vec(c.up),  c.fov,
          c.aperture_radius, c.focus_distance, c.exposure, c.auto_exposure};
}

SunSpec sun_spec(const formats::SunDesc& s) {
  return {s.enabled, s.elevation, s.azimuth, s.irradiance, s.angular_diameter};
}

SkySpec sky_spec(const formats::SkyDesc& s) {
  SkySpec sky;
  sky.model = s.model;
  sky.turbidity = s.turbidity;
  sky.air_density = s.air_density;
  sky.dust_density = s.dust_density;
  sky.ozone_density = s.ozone_density;
  sky.altitude = s.altitude;
  sky.visibility = s.visibility;
  sky.turbidity_given = s.turbidity_given;
  sky.dust_given = s.dust_given;
  // A description made in code has no [ground] read with it: the default ground's.
  sky.ground_albedo = s.ground_albedo >= 0.0 ? s.ground_albedo : formats::mean_albedo({});
  sky.color = {s.color[0], s.color[1], s.color[2]};
  sky.path = s.path;
  sky.rotation = s.rotation;
  sky.scale = s.scale;
  return sky;
}

RenderInput render_input(const formats::SceneDesc& d) {
  RenderInput in;
  in.scene = d.path;
  const formats::RenderSettings& r = d.render;
  in.render = {r.width,
               r.height,
               r.spp,
               r.seed,
               r.integrator,
               r.max_depth,
               r.treemaker_spp,
               r.pass_spp,
               r.independent_passes,
               r.noise_threshold,
               r.min_spp,
               r.threads,
               r.regularize};
  // A camera standing on the terrain needs the terrain (built here once more: the scene's own is
  // built later, by build_scene). The reader checked the camera; one made in code, or placed on
  // the terrain, is checked here.
  const formats::CameraDesc camera =
      d.camera.above_ground ? placed_camera(d.camera, Terrain(d.terrain)) : d.camera;
  formats::check_camera(camera);
  in.camera = camera_spec(camera);
  in.sun = sun_spec(d.sun);
  in.sky = sky_spec(d.sky);
  in.sky.aerial_perspective = r.aerial_perspective;
  in.output = d.output;
  return in;
}

}  // namespace arbor::scene
