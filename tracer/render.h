// Rendering a frame in passes: each pass takes its samples from its own scramble over the whole
// window, tiles in parallel; the film folds pass after pass (film.h). Between passes the loop
// may stop (a signal, a time limit), write a checkpoint, or retire converged pixels (adaptive).
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "imaging/color.h"
#include "imaging/image.h"
#include "scene/render_input.h"
#include "tracer/film.h"
#include "tracer/integrators/path.h"

namespace arbor {
class Progress;
}

namespace arbor::tracer {

// Which passes to render and when to stop early.
struct RenderJob {
  PassPlan plan;
  int pass_end = 0;  // renders passes film.next_pass() .. pass_end - 1
  AdaptiveSettings adaptive;
  double time_limit = 0;          // seconds of this run; 0: none. At least one pass is rendered.
  double checkpoint_seconds = 0;  // 0: no checkpoints
  std::function<void(const Film&)> checkpoint;  // writes what the film holds (between passes)
  const std::atomic<int>* stop = nullptr;       // nonzero: stop after the running pass
};

// The passes of the scene's render: the sample count of its integrator in passes of pass_spp.
PassPlan pass_plan_for(const spec::RenderSettings& render);

// Why a render's outputs hold fewer passes than it asked for: it did not stop early, a signal
// stopped it, its time limit did, or it is a checkpoint of a render still running.
enum class StopReason { None, Interrupted, TimeLimit, InProgress };
// "", "interrupted", "time limit", "in progress": the EXR's arbor:stopped and the messages.
const char* name_of(StopReason reason);

// Why the loop ended before pass_end (StopReason::None: it did not).
struct RenderOutcome {
  StopReason stopped = StopReason::None;
};

// The integrator AOV names of the scene's render ("treemaker" asked of the treemaker
// integrator), which size the film's extras.
std::vector<std::string> integrator_aov_names(const scene::RenderInput& input);

// Renders with the path integrator. Deterministic: each pixel's samples depend only on (pixel,
// pass, sample index, seed), and each pixel is accumulated in sample and pass order by one task.
RenderOutcome render_path(const scene::RenderInput& input, const World& world, const Sky& sky,
                          const imaging::ColorTransform& to_output, const RenderJob& job,
                          Film& film, Progress* progress, imaging::RenderStats& stats);

// Renders with the treemaker integrator (its samples only anti-alias: its shade has no noise);
// fills the film's extras with the "treemaker" AOVs when integrator_aov_names asks for them.
RenderOutcome render_treemaker(const scene::RenderInput& input, const World& world, const Sky& sky,
                               const imaging::ColorTransform& to_output, const RenderJob& job,
                               Film& film, Progress* progress, imaging::RenderStats& stats);

// A whole image at the scene's settings in one go, for tests and benchmarks.
imaging::Image render_image(const scene::RenderInput& input, const World& world, const Sky& sky,
                            const imaging::ColorTransform& to_output, imaging::RenderStats& stats);

}  // namespace arbor::tracer
