// The render loop: tiles in parallel, each pixel's samples in order, for either integrator.
#include "tracer/render.h"

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
#include "tracer/film.h"
#include "tracer/integrators/treemaker.h"

namespace arbor::trace {

namespace {
constexpr int kTile = 16;

// The frame loop shared by the integrators. `trace(ray, sampler, index, extra)` returns the
// sample's PathSample (scene-linear radiance and albedo) and writes `extra_count` AOV floats,
// already in their output form, to `extra`.
template <class Trace>
Image render_frame(const SceneDesc& scene, int spp, int extra_count, const Trace& trace,
                   const ColorTransform& to_output, Progress* progress, RenderStats& stats) {
  const RenderSettings& rs = scene.render;
  const int w = rs.width, h = rs.height;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  const auto extras = static_cast<std::size_t>(extra_count);
  Image img = make_image(w, h, extras);
  const Camera camera(scene.camera, w, h);
  const float exposure = std::exp2(static_cast<float>(scene.camera.exposure));
  const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
  const int tiles = tiles_x * tiles_y;
  std::atomic<std::uint64_t> rays{0}, nonfinite{0};
  std::atomic<int> tiles_done{0};
  std::mutex progress_mutex;
  if (progress) progress->set_total(static_cast<std::uint64_t>(tiles));
  const auto start = std::chrono::steady_clock::now();

  auto render_tile = [&](int tile) {
    const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
    std::uint64_t tile_rays = 0, tile_bad = 0;
    std::vector<float> sample_extra(extras);
    PixelAccumulator pixel(extras);
    for (int y = y0; y < std::min(h, y0 + kTile); ++y) {
      for (int x = x0; x < std::min(w, x0 + kTile); ++x) {
        const std::size_t p = static_cast<std::size_t>(y) * w + x;
        const PixelSampler sampler(static_cast<std::uint32_t>(p), rs.seed);
        pixel.reset();
        for (int i = 0; i < spp; ++i) {
          const auto index = static_cast<std::uint32_t>(i);
          const glm::vec2 uf = sampler.get2d(index, 0);
          const glm::vec2 film(x + 0.5f + sample_tent(uf.x), y + 0.5f + sample_tent(uf.y));
          const Ray ray = camera.generate(film, sampler.get2d(index, 1));
          const PathSample s = trace(ray, sampler, index, sample_extra.data());
          tile_rays += s.rays;
          if (!std::isfinite(s.radiance.x) || !std::isfinite(s.radiance.y) ||
              !std::isfinite(s.radiance.z)) {
            ++tile_bad;
            continue;
          }
          float rgb[3] = {s.radiance.x * exposure, s.radiance.y * exposure, s.radiance.z * exposure};
          to_output(rgb);
          float alb[3] = {s.albedo.x, s.albedo.y, s.albedo.z};
          to_output(alb);
          pixel.add(rgb, alb, s.normal, s.depth, sample_extra.data());
        }
        pixel.store(img, p);
      }
    }
    rays += tile_rays;
    nonfinite += tile_bad;
    const int done = ++tiles_done;
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress->update(static_cast<std::uint64_t>(done));
    }
  };

  tbb::task_arena arena(rs.threads > 0 ? rs.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const tbb::blocked_range<int>& r) {
      for (int t = r.begin(); t < r.end(); ++t) render_tile(t);
    });
  });
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.samples = static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(spp);
  stats.rays = rays;
  stats.nonfinite = nonfinite;
  return img;
}

}  // namespace

Image render_path(const SceneDesc& scene, const World& world, const Sky& sky,
                  const ColorTransform& to_output, Progress* progress, RenderStats& stats) {
  const PathIntegrator integrator(world, sky, scene.render.max_depth);
  auto trace = [&](const Ray& ray, const PixelSampler& sampler, std::uint32_t index, float*) {
    return integrator.trace(ray, sampler, index);
  };
  return render_frame(scene, scene.render.spp, 0, trace, to_output, progress, stats);
}

Image render_treemaker(const SceneDesc& scene, const World& world, const Sky& sky,
                       const ColorTransform& to_output, Progress* progress, RenderStats& stats) {
  const TreemakerIntegrator integrator(world, sky);
  const float exposure = std::exp2(static_cast<float>(scene.camera.exposure));
  // The AOVs cost 23 floats a pixel: kept only when the output asks for them.
  const auto& aovs = scene.output.aovs;
  const bool keep = std::find(aovs.begin(), aovs.end(), "treemaker") != aovs.end();
  const std::vector<std::string> names = keep ? treemaker_channel_names() : std::vector<std::string>();
  auto trace = [&](const Ray& ray, const PixelSampler&, std::uint32_t, float* extra) {
    const TreemakerSample t = integrator.trace(ray);
    if (keep) t.write_aovs(exposure, to_output, extra);
    return t.shade;
  };
  Image img = render_frame(scene, scene.render.treemaker_spp, static_cast<int>(names.size()), trace,
                           to_output, progress, stats);
  img.extra_names = names;
  return img;
}

}  // namespace arbor::trace
