// `arbor export`: a scene file written as a complete pbrt-v4 scene (docs/rendering.md, "pbrt-v4
// export"): camera, film, sampler, the sun and the sky, materials, every tree and mesh, the ground.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace arbor::trace {

struct ExportRequest {
  std::string scene;
  std::string out;                  // OUT.pbrt; the sky goes beside it as OUT.sky.exr
  int width = 0, height = 0, spp = 0;  // 0: the scene's
  std::optional<double> time;       // seconds of wind for every [[tree]]
  std::optional<int> frame;         // the [animation]'s frame N (its clock and seed)
  int sky_resolution = 512;         // texels along each side of the sky's equal-area square
  std::string ocio_config;          // the run's OCIO config (default_ocio_config())
};

// Writes OUT.pbrt and its sky; returns the exit status (0). InputError for bad input,
// RuntimeFailure when the work fails. Both files are written atomically.
int export_command(const ExportRequest& request);

// The sky image beside OUT.pbrt: OUT.sky.exr for OUT.pbrt.
std::string sky_path_for(const std::string& pbrt_path);

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

}  // namespace arbor::trace
