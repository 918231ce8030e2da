// Auto exposure (`[camera] exposure = "auto"`): the exposure a photographer's meter would choose,
// from a small preview of the whole frame made before the render (docs/rendering.md, "Exposure").
//
// The rule: a 64-pixel-wide preview of the frame (the render's camera, the path tracer at the
// scene's max_depth without regularisation, 16 samples a pixel, a fixed seed of its own), each
// pixel's luminance Y (Rec. 709 weights of the scene-linear radiance, before exposure), averaged as
// logarithms with centre weights w = exp(−(x² + y²) / (2 · 0.5²)), x and y from −1 to 1 across
// the frame; the exposure puts that average at middle grey:
// stops = log2(0.18 / exp(Σ w ln(Y + 10⁻⁶) / Σ w)), within [−64, 64].
// It meters the scene, not an output of it: the integrator (path or treemaker), a transparent sky,
// --regularize, the render's seed, crop, passes and thread count change nothing, so the beauty pass
// and its compositing plate, the exact render and TREE-MAKER's, every farm unit and a resumed
// render share one exposure, bit for bit. An animation meters its frame 0
// (app/commands/render.cpp).
#pragma once

#include "scene/render_input.h"

namespace arbor::tracer {

class World;
class Sky;

// The metered exposure in stops.
double metered_exposure(const scene::RenderInput& input, const World& world, const Sky& sky);

// `input` itself, or with camera.exposure metered when it asks for "auto".
scene::RenderInput with_exposure(const scene::RenderInput& input, const World& world,
                                 const Sky& sky);

}  // namespace arbor::tracer
