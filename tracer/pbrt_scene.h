// A scene written as a complete pbrt-v4 scene (docs/rendering.md, "pbrt-v4 export"): camera,
// film, sampler, the sun and the sky, materials, every tree and mesh, the ground.
#pragma once

#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "imaging/color.h"
#include "scene/render_input.h"
#include "scene/scene.h"

namespace arbor::tracer {

// What write_pbrt_scene wrote and what it had to change.
struct PbrtExport {
  std::vector<std::string> written;  // OUT.pbrt, then its sky and ground images when written
  std::vector<std::string> clamped;  // reflectances clamped to [0, 1] in pbrt's space, described
  std::string space;                 // pbrt's colour space the colours are in
};

// Writes the built scene, seen and lit as `input` says, to `out` (.pbrt) as a complete pbrt-v4
// scene, its sky beside it
// (sky_path_for) as an equal-area square `sky_resolution` texels a side, and the ground's
// patches near the camera (ground_path_for) when it has them; each file atomically, the images
// first. InputError when the OCIO config's scene_linear has no known primaries.
PbrtExport write_pbrt_scene(const scene::Scene& scene, const scene::RenderInput& input,
                            const imaging::ColorPipeline& color, const std::string& out,
                            int sky_resolution);

// The sky image beside OUT.pbrt: OUT.sky.exr for OUT.pbrt.
std::string sky_path_for(const std::string& pbrt_path);
// The ground's image beside OUT.pbrt: OUT.ground.exr.
std::string ground_path_for(const std::string& pbrt_path);

// pbrt-v4's equal-area square ↔ sphere map (Clarberg 2008, as pbrt-v4's EqualAreaSquareToSphere):
// the direction of the point uv ∈ [0, 1]² of an "infinite" light's image (u along a row, v down
// the rows), in the light's space (z up). Equal areas of the square are equal solid angles.
glm::vec3 equal_area_square_to_sphere(glm::vec2 uv);

// A pbrt-v4 colour space (its `ColorSpace` name) and its chromaticities (r, g, b, white xy).
struct PbrtColorSpace {
  const char* name;
  std::vector<float> chromaticities;
};
// The pbrt-v4 space colours are written in for a scene_linear of chromaticities `c`: the same
// space when pbrt-v4 knows it (srgb, rec2020, aces2065-1, dci-p3, within 1e-3), else aces2065-1
// (ACES AP0 holds every real colour, so no value turns negative).
PbrtColorSpace pbrt_color_space_for(const std::vector<float>& c);
// The pbrt-v4 space for the config's scene_linear; InputError when its primaries are unknown.
PbrtColorSpace pbrt_color_space_of(const imaging::ColorPipeline& color);

}  // namespace arbor::tracer
