// Rendering a frame: tiles in parallel, samples placed by the tent filter (film.h), per-pixel mean
// and variance of the beauty in the output colour space, AOVs.
#pragma once

#include "formats/scene_desc.h"
#include "imaging/color.h"
#include "imaging/image.h"
#include "tracer/integrators/path.h"

namespace arbor {
class Progress;
}

namespace arbor::trace {

// Renders with the path integrator. Deterministic: each pixel's samples depend only on (pixel,
// sample index, seed), and each pixel is accumulated in sample order by one task.
Image render_path(const SceneDesc& scene, const World& world, const Sky& sky,
                  const ColorTransform& to_output, Progress* progress, RenderStats& stats);

// Renders with the treemaker integrator at scene.render.treemaker_spp samples per pixel (they
// only anti-alias: its shade has no noise). Fills extra_names/extra with the "treemaker" AOVs
// when scene.output.aovs asks for them.
Image render_treemaker(const SceneDesc& scene, const World& world, const Sky& sky,
                       const ColorTransform& to_output, Progress* progress, RenderStats& stats);

}  // namespace arbor::trace
