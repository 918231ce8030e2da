// The render loop: passes over the window, tiles in parallel, each pixel's samples in order, for
// either integrator.
#include "tracer/render.h"

#include "tracer/exposure.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "common/progress.h"
#include "tracer/camera.h"
#include "tracer/integrators/treemaker.h"

namespace arbor::tracer {

namespace {
constexpr int kTile = 16;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The pass loop shared by the integrators. `trace(ray, sampler, index, extra)` returns the
// sample's PathSample (scene-linear radiance and albedo) and writes the film's extras, already
// in their output form, to `extra`. `full_width` numbers the pixels of the whole image, which
// key their samples: a crop renders each pixel exactly as the whole image does.
template <class Trace>
RenderOutcome render_passes(const scene::RenderInput& input, const RenderJob& job, Film& film,
                            const Trace& trace, const imaging::ColorTransform& to_output,
                            Progress* progress, imaging::RenderStats& stats) {
  const spec::RenderSettings& rs = input.render;
  const Window win = film.window();
  const int ww = win.width(), wh = win.height();
  const std::size_t extras = film.extras();
  const Camera camera(input.camera, rs.width, rs.height);
  const float exposure = std::exp2(static_cast<float>(input.camera.exposure));
  const bool transparent = input.output.transparent_sky;
  const int tiles_x = (ww + kTile - 1) / kTile, tiles_y = (wh + kTile - 1) / kTile;
  const int tiles = tiles_x * tiles_y;
  const int first = film.next_pass();
  const int last = std::max(first, job.pass_end);
  std::atomic<std::uint64_t> rays{0}, nonfinite{0}, samples{0};
  std::atomic<std::uint64_t> tiles_done{0};
  std::mutex progress_mutex;
  if (progress)
    progress->set_total(static_cast<std::uint64_t>(tiles) *
                        static_cast<std::uint64_t>(last - first));
  const auto start = Clock::now();
  auto last_checkpoint = start;
  RenderOutcome outcome;

  tbb::task_arena arena(rs.threads > 0 ? rs.threads : tbb::task_arena::automatic);
  for (int pass = first; pass < last; ++pass) {
    const int spp = job.plan.size(pass);
    const auto pass_start = Clock::now();
    film.begin_pass();
    auto render_tile = [&](int tile) {
      const int x0 = win.x0 + (tile % tiles_x) * kTile, y0 = win.y0 + (tile / tiles_x) * kTile;
      std::uint64_t tile_rays = 0, tile_bad = 0, tile_samples = 0;
      std::vector<float> sample_extra(extras);
      PixelAccumulator pixel(extras, film.keeps_ids());
      for (int y = y0; y < std::min(win.y1, y0 + kTile); ++y) {
        for (int x = x0; x < std::min(win.x1, x0 + kTile); ++x) {
          const std::size_t p = static_cast<std::size_t>(y - win.y0) * ww + (x - win.x0);
          if (film.done(p)) continue;
          const auto key = static_cast<std::uint32_t>(static_cast<std::size_t>(y) * rs.width + x);
          const PixelSampler sampler(key, rs.seed, job.plan.scramble(pass));
          pixel.reset();
          const std::uint32_t first_index = job.plan.first_sample(pass);
          for (int i = 0; i < spp; ++i) {
            const std::uint32_t index = first_index + static_cast<std::uint32_t>(i);
            const glm::vec2 uf = sampler.get2d(index, 0);
            const glm::vec2 pos(x + 0.5f + sample_tent(uf.x), y + 0.5f + sample_tent(uf.y));
            const Ray ray = camera.generate(pos, sampler.get2d(index, 1));
            PathSample s = trace(ray, sampler, index, sample_extra.data());
            if (transparent && !s.hit) {
              // [output] transparent_sky: an escaping camera ray adds nothing (alpha 0), so the
              // pixel is premultiplied by its coverage; the sky still lights the scene.
              s.radiance = glm::vec3(0.0f);
              std::fill(sample_extra.begin(), sample_extra.end(), 0.0f);
            }
            tile_rays += s.rays;
            if (!std::isfinite(s.radiance.x) || !std::isfinite(s.radiance.y) ||
                !std::isfinite(s.radiance.z)) {
              ++tile_bad;
              continue;
            }
            float rgb[3] = {s.radiance.x * exposure, s.radiance.y * exposure,
                            s.radiance.z * exposure};
            to_output(rgb);
            float alb[3] = {s.albedo.x, s.albedo.y, s.albedo.z};
            to_output(alb);
            pixel.add(rgb, alb, s.normal, s.depth, s.hit || !transparent ? 1.0f : 0.0f,
                      sample_extra.data(), s.object_id, s.material_id);
          }
          tile_samples += static_cast<std::uint64_t>(spp);
          film.add_pass(p, pixel);
        }
      }
      rays += tile_rays;
      nonfinite += tile_bad;
      samples += tile_samples;
      const std::uint64_t done = ++tiles_done;
      if (progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress->update(done);
      }
    };
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1),
                        [&](const tbb::blocked_range<int>& r) {
                          for (int t = r.begin(); t < r.end(); ++t) render_tile(t);
                        });
    });
    film.finish_pass(job.adaptive);
    if (pass + 1 == last) break;
    // Between passes: a signal, the time limit (the next pass, if it takes as long as this one,
    // would not fit), a checkpoint.
    if (job.stop && job.stop->load() != 0) {
      outcome.stopped = StopReason::Interrupted;
      break;
    }
    const double elapsed = seconds_since(start);
    if (job.time_limit > 0 &&
        elapsed + seconds_since(pass_start) * double(job.plan.size(pass + 1)) / spp >
            job.time_limit) {
      outcome.stopped = StopReason::TimeLimit;
      break;
    }
    if (job.checkpoint && job.checkpoint_seconds > 0 &&
        seconds_since(last_checkpoint) >= job.checkpoint_seconds) {
      stats.seconds = elapsed;
      job.checkpoint(film);
      last_checkpoint = Clock::now();
    }
  }
  stats.seconds = seconds_since(start);
  stats.samples = samples;
  stats.rays = rays;
  stats.nonfinite = nonfinite;
  return outcome;
}

}  // namespace

std::vector<std::string> integrator_aov_names(const scene::RenderInput& input) {
  // The treemaker AOVs cost 23 values a pixel: kept only when the output asks for them.
  if (input.render.integrator == spec::Integrator::Treemaker &&
      input.output.aovs.has(imaging::Aov::Treemaker)) {
    return imaging::treemaker_channel_names();
  }
  return {};
}

RenderOutcome render_path(const scene::RenderInput& input, const World& world, const Sky& sky,
                          const imaging::ColorTransform& to_output, const RenderJob& job,
                          Film& film, Progress* progress, imaging::RenderStats& stats) {
  const PathIntegrator integrator(world, sky, input.render.max_depth, input.render.regularize);
  auto trace = [&](const Ray& ray, const PixelSampler& sampler, std::uint32_t index, float*) {
    return integrator.trace(ray, sampler, index);
  };
  return render_passes(input, job, film, trace, to_output, progress, stats);
}

RenderOutcome render_treemaker(const scene::RenderInput& input, const World& world, const Sky& sky,
                               const imaging::ColorTransform& to_output, const RenderJob& job,
                               Film& film, Progress* progress, imaging::RenderStats& stats) {
  const TreemakerIntegrator integrator(world, sky);
  const float exposure = std::exp2(static_cast<float>(input.camera.exposure));
  const bool keep = film.extras() > 0;
  auto trace = [&](const Ray& ray, const PixelSampler&, std::uint32_t, float* extra) {
    const TreemakerSample t = integrator.trace(ray);
    if (keep) t.write_aovs(exposure, to_output, extra);
    return t.shade;
  };
  return render_passes(input, job, film, trace, to_output, progress, stats);
}

const char* name_of(StopReason reason) {
  switch (reason) {
    case StopReason::None: return "";
    case StopReason::Interrupted: return "interrupted";
    case StopReason::TimeLimit: return "time limit";
    case StopReason::InProgress: return "in progress";
  }
  return "";
}

PassPlan pass_plan_for(const spec::RenderSettings& r) {
  return {r.samples(), r.pass_spp, r.independent_passes};
}

imaging::Image render_image(const scene::RenderInput& asked, const World& world, const Sky& sky,
                            const imaging::ColorTransform& to_output, imaging::RenderStats& stats) {
  const scene::RenderInput input = with_exposure(asked, world, sky);
  const spec::RenderSettings& r = input.render;
  const bool treemaker = r.integrator == spec::Integrator::Treemaker;
  RenderJob job;
  job.plan = pass_plan_for(r);
  job.pass_end = job.plan.passes();
  job.adaptive = {r.noise_threshold, r.min_spp};
  const std::vector<std::string> names = integrator_aov_names(input);
  Film film({0, 0, r.width, r.height}, names.size(), 0, false, input.output.wants_ids());
  if (treemaker) {
    render_treemaker(input, world, sky, to_output, job, film, nullptr, stats);
  } else {
    render_path(input, world, sky, to_output, job, film, nullptr, stats);
  }
  imaging::Image img = film.image(names.size());
  img.extra_names = names;
  img.object_names = world.scene().object_names;
  img.material_names = world.scene().material_names;
  return img;
}

}  // namespace arbor::tracer
