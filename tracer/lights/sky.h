// The lights of a scene: the sky (Preetham, Nishita, constant, environment map or none; each
// model's map made in its own file, sky_model.h) as one importance-sampled lat-long radiance map,
// and the sun as a disk of given angular diameter and irradiance (with Nishita's sky, attenuated
// and coloured by the same atmosphere).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "tracer/lights/distribution.h"
#include "tracer/lights/sky_model.h"
#include "imaging/color.h"
#include "scene/render_input.h"

namespace arbor::tracer {

struct LightSample {
  glm::vec3 direction{0.0f};  // towards the light
  glm::vec3 radiance{0.0f};
  float pdf = 0.0f;  // solid angle
};

// The sky map's width in texels (its height is half) where the render does not choose another.
inline constexpr int kSkyMapWidth = 512;

class Sky {
 public:
  // Builds the map at `width` × width/2; throws InputError for an unreadable environment map.
  // `xyz_to_scene_linear` converts the Preetham model's XYZ (ColorPipeline::xyz_to_scene_linear).
  // With `aerial_perspective` ([render]'s key), the nishita and atmosphere skies build the air's
  // table (aerial()).
  Sky(const spec::SkyDesc& sky, const spec::SunDesc& sun,
      const imaging::ColorTransform& xyz_to_scene_linear, int width = kSkyMapWidth,
      bool aerial_perspective = false);

  glm::vec3 radiance(const glm::vec3& direction) const;  // sky only, not the sun
  LightSample sample(glm::vec2 u) const;
  float pdf(const glm::vec3& direction) const;
  // radiance() and pdf() of one direction together (its map coordinates found once); direction
  // is `direction`.
  LightSample lookup(const glm::vec3& direction) const;
  bool empty() const { return !present_; }
  // Irradiance of the sky (without the sun) on an upward-facing horizontal plane, unoccluded:
  // ∫ L(ω) max(0, cos θ) dω over the map. A constant sky of radiance L gives πL.
  glm::vec3 irradiance_up() const { return irradiance_up_; }
  // The relative variance per sample of the luminance of irradiance_up() estimated by cosine-
  // weighted directions (what a Lambertian surface's BSDF sampling does):
  // π ∫ Y² cos θ dω / (∫ Y cos θ dω)² − 1 over the upper hemisphere. 0 for a constant sky; large
  // for a sky whose light comes from a small bright region (an environment map's sun).
  float cosine_variance_up() const { return cosine_variance_up_; }

  // The sun: a disk of half-angle `sun_half_angle` around `sun_direction`.
  bool has_sun() const { return sun_present_; }
  glm::vec3 sun_direction() const { return sun_direction_; }
  glm::vec3 sun_radiance() const { return sun_radiance_; }  // the disk's mean
  // The radiance of the disk along `direction` (inside it) as a camera sees it: the mean × the
  // limb darkening there, per channel (limb_darkening.h), with the same irradiance as the uniform
  // disk. As a light (sample_sun, and paths that hit the disk after a bounce) the sun is the
  // uniform disk: the light it casts is the same except inside penumbrae and in glossy images of
  // the disk, and its shadow rays carry no noise from the profile (Blender's Nishita sky shows
  // its limb darkening the same way, in the disk seen).
  glm::vec3 sun_radiance(const glm::vec3& direction) const;
  // On a plane facing it, at the ground (after the atmosphere, for Nishita's sky): the mean of
  // its colour's channels, and the colour; 0 without a sun.
  float sun_irradiance() const { return sun_irradiance_; }
  glm::vec3 sun_irradiance_color() const { return sun_irradiance_color_; }
  LightSample sample_sun(glm::vec2 u) const;
  float sun_pdf() const;  // uniform over the disk's cone
  bool in_sun(const glm::vec3& direction) const;
  // The air between the camera and a surface (`[render] aerial_perspective` with the nishita or
  // atmosphere sky), else null.
  const AerialPerspective* aerial() const { return aerial_.get(); }

 private:
  glm::vec2 to_map(const glm::vec3& d) const;
  glm::vec3 from_map(glm::vec2 p) const;
  glm::vec3 map_at(glm::vec2 p) const;  // the map's cell at map coordinates p

  int width_ = 0, height_ = 0;
  std::vector<glm::vec3> map_;
  Distribution2D distribution_;
  bool present_ = false;
  glm::vec3 irradiance_up_{0.0f};
  float cosine_variance_up_ = 0.0f;
  float rotation_ = 0.0f;  // radians about z
  bool sun_present_ = false;
  glm::vec3 sun_direction_{0.0f, 0.0f, 1.0f}, sun_radiance_{0.0f};
  float sun_irradiance_ = 0.0f;
  glm::vec3 sun_irradiance_color_{0.0f};
  double sun_one_minus_cos_ = 0.0;  // 1 - cos α, the cone's solid angle / 2π
  std::vector<glm::vec3> limb_;     // the limb darkening over s = θ / α from 0 to 1
  glm::vec3 limb_at(double one_minus_cos) const;
  glm::dvec3 sun_direction_d_{0.0, 0.0, 1.0};
  std::shared_ptr<const AerialPerspective> aerial_;
};

}  // namespace arbor::tracer
