// Rendering a frame: tiles in parallel, a tent reconstruction filter by importance sampling,
// per-pixel mean and variance of the beauty in the output colour space, AOVs.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "tracer/integrator_path.h"
#include "tracer/scene_desc.h"

namespace arbor {
class Progress;
}

namespace arbor::trace {

struct Image {
  int width = 0, height = 0;
  std::vector<glm::vec3> beauty;    // mean, output colour space
  std::vector<glm::vec3> variance;  // variance of the mean (sample variance / n), per channel
  std::vector<glm::vec3> albedo;    // first hit, output colour space
  std::vector<glm::vec3> normal;    // first hit, world space
  std::vector<float> depth;         // distance to the first hit along the camera ray
  // Integrator-specific AOVs (the treemaker integrator's), pixel means: extra_names.size()
  // floats per pixel; colour triples are in the output colour space, like the beauty.
  std::vector<std::string> extra_names;
  std::vector<float> extra;
};

struct RenderStats {
  double seconds = 0.0;
  std::uint64_t samples = 0, rays = 0;
  std::uint64_t nonfinite = 0;  // samples whose radiance was NaN or infinite (left out, counted)
};

// Converts a scene-linear colour to the output colour space in place (thread-safe).
using ColorTransform = std::function<void(float rgb[3])>;

// Renders with the path integrator. Deterministic: each pixel's samples depend only on (pixel,
// sample index, seed), and each pixel is accumulated in sample order by one task.
Image render_path(const SceneDesc& scene, const World& world, const Sky& sky,
                  const ColorTransform& to_output, Progress* progress, RenderStats& stats);

// Renders with the treemaker integrator at scene.render.treemaker_spp samples per pixel (they
// only anti-alias: its shade has no noise). Fills extra_names/extra with the "treemaker" AOVs
// when scene.output.aovs asks for them.
Image render_treemaker(const SceneDesc& scene, const World& world, const Sky& sky,
                       const ColorTransform& to_output, Progress* progress, RenderStats& stats);

// Tent filter of radius 1 pixel: maps u in [0,1) to an offset in (-1, 1) distributed ∝ 1 - |x|.
float sample_tent(float u);

}  // namespace arbor::trace
