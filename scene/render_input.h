// Everything the tracer needs besides the built geometry, as typed values: the render settings,
// the camera, the sun and the sky, and the output specification. scene/ builds it from the scene
// description (formats/scene_desc.h, whose choices are already enums, Integrator and SkyModel),
// so the tracer never reads the description, compares a string, or meets an unknown choice.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "formats/scene_desc.h"
#include "imaging/output_spec.h"

namespace arbor::scene {

struct RenderSpec {
  int width = 0, height = 0;
  int spp = 0;  // of the path integrator
  std::uint64_t seed = 0;
  formats::Integrator integrator = formats::Integrator::Path;
  int max_depth = 0;
  int treemaker_spp = 0;  // of the treemaker integrator (anti-aliasing)
  int pass_spp = 0;
  bool independent_passes = false;
  double noise_threshold = 0.0;  // adaptive sampling; 0: off
  int min_spp = 0;
  int threads = 0;          // 0: all cores
  bool regularize = false;  // glossy lobes roughened after a non-specular bounce
  // The sample count of the integrator in use.
  int samples() const { return integrator == formats::Integrator::Treemaker ? treemaker_spp : spp; }
};

struct CameraSpec {
  glm::dvec3 position{0.0}, look_at{0.0}, up{0.0, 0.0, 1.0};
  double fov = 45.0;             // vertical, degrees
  double aperture_radius = 0.0;  // metres
  double focus_distance = 0.0;   // metres; 0: distance to look_at
  double exposure = 0.0;         // stops
  bool auto_exposure = false;    // metered before rendering (tracer/exposure.h)
};

struct SunSpec {
  bool enabled = true;
  double elevation = 0.0, azimuth = 0.0;  // degrees; azimuth counter-clockwise from +x
  double irradiance = 0.0;                // scene-linear, on a plane facing the sun
  double angular_diameter = 0.0;          // degrees
};

struct SkySpec {
  formats::SkyModel model = formats::SkyModel::None;
  double turbidity = 0.0;                                                             // preetham
  double air_density = 1.0, dust_density = 1.0, ozone_density = 1.0, altitude = 0.0;  // nishita
  // atmosphere (formats::SkyDesc): the aerosols by the key given, the ground's albedo
  double visibility = 0.0;
  bool turbidity_given = false, dust_given = false;
  double ground_albedo = 0.0;
  bool aerial_perspective = false;  // [render]'s: the Sky builds the table (tracer/lights/aerial.h)
  glm::dvec3 color{1.0};            // constant
  std::string path;                 // envmap
  double rotation = 0.0, scale = 1.0;  // envmap
};

struct RenderInput {
  std::string scene;  // the scene file, for messages and metadata
  RenderSpec render;
  CameraSpec camera;
  SunSpec sun;
  SkySpec sky;
  imaging::OutputSpec output;
};

// The typed values of the scene description's parts.
CameraSpec camera_spec(const formats::CameraDesc& camera);
SunSpec sun_spec(const formats::SunDesc& sun);
SkySpec sky_spec(const formats::SkyDesc& sky);

// The typed input of the scene description `desc` (its choices already checked by the reader);
// InputError when its camera cannot form an image.
RenderInput render_input(const formats::SceneDesc& desc);

}  // namespace arbor::scene
