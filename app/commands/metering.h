// `[camera] exposure = "auto"`, metered once per scene for `arbor render` and `arbor export`: an
// animation's frames all take the exposure of its frame 0, so they do not flicker.
#pragma once

#include <cstdint>
#include <string>

#include "spec/scene_desc.h"
#include "scene/render_input.h"
#include "tracer/embree/embree_device.h"
#include "tracer/embree/world.h"
#include "tracer/lights/sky.h"

namespace arbor::app {

// How the meter builds frame 0 when the render shows another frame.
struct MeterBuild {
  const tracer::EmbreeDevice* device = nullptr;
  std::string ocio_config;
  std::uint64_t geometry_budget = 0;  // scene::build_scene's
  unsigned threads = 0;
};

// True when `scene` (a frame applied or not) is not its own frame 0: its exposure is metered on
// frame 0, built for the purpose (frame_zero_exposure), before the render builds its own world.
bool meters_frame_zero(const spec::SceneDesc& scene, const scene::RenderInput& input);

// The metered exposure (stops) of the scene at clock 0: its trees, meadow and wind as at frame 0,
// the same camera and light.
double frame_zero_exposure(const spec::SceneDesc& scene, const scene::RenderInput& input,
                           const tracer::Sky& sky, const MeterBuild& how);

// `input` with its camera's exposure metered (tracer::metered_exposure on `world`, or `frame_zero`
// when meters_frame_zero), or `input` itself when it gives stops; says on stderr what it metered.
scene::RenderInput with_scene_exposure(const spec::SceneDesc& scene,
                                       const scene::RenderInput& input, const tracer::World& world,
                                       const tracer::Sky& sky, double frame_zero);

}  // namespace arbor::app
