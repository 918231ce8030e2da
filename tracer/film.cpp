// The render loop over tiles.
#include "tracer/film.h"

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

namespace arbor::trace {

float sample_tent(float u) {
  return u < 0.5f ? std::sqrt(2.0f * u) - 1.0f : 1.0f - std::sqrt(2.0f - 2.0f * u);
}

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
  Image img;
  img.width = w;
  img.height = h;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  const auto extras = static_cast<std::size_t>(extra_count);
  img.beauty.assign(n, glm::vec3(0.0f));
  img.variance.assign(n, glm::vec3(0.0f));
  img.albedo.assign(n, glm::vec3(0.0f));
  img.normal.assign(n, glm::vec3(0.0f));
  img.depth.assign(n, 0.0f);
  img.extra.assign(n * extras, 0.0f);
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
    std::vector<double> extra_sum(extras);
    for (int y = y0; y < std::min(h, y0 + kTile); ++y) {
      for (int x = x0; x < std::min(w, x0 + kTile); ++x) {
        const std::size_t p = static_cast<std::size_t>(y) * w + x;
        const PixelSampler sampler(static_cast<std::uint32_t>(p), rs.seed);
        glm::dvec3 mean(0.0), m2(0.0), albedo(0.0), normal(0.0);
        double depth = 0.0;
        std::fill(extra_sum.begin(), extra_sum.end(), 0.0);
        int count = 0;
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
          // Welford's running mean and squared deviations.
          ++count;
          const glm::dvec3 v(rgb[0], rgb[1], rgb[2]);
          const glm::dvec3 delta = v - mean;
          mean += delta / static_cast<double>(count);
          m2 += delta * (v - mean);
          albedo += glm::dvec3(alb[0], alb[1], alb[2]);
          normal += glm::dvec3(s.normal);
          depth += s.depth;
          for (std::size_t e = 0; e < extras; ++e) extra_sum[e] += sample_extra[e];
        }
        if (count > 0) {
          img.beauty[p] = glm::vec3(mean);
          img.variance[p] = count > 1 ? glm::vec3(m2 / (double(count - 1) * count)) : glm::vec3(0.0f);
          img.albedo[p] = glm::vec3(albedo / double(count));
          const glm::dvec3 nn = normal / double(count);
          img.normal[p] = glm::vec3(nn);
          img.depth[p] = static_cast<float>(depth / count);
          for (std::size_t e = 0; e < extras; ++e) img.extra[p * extras + e] = static_cast<float>(extra_sum[e] / count);
        }
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
    if (!keep) return t.shade;
    // The factors as they are; the colours exposed and in the output space like the beauty, so
    // that beauty = tm_rest + Σ weight_i × tm_i holds for the written pixels too.
    std::size_t k = 0;
    for (float term : t.terms) extra[k++] = term;
    auto put = [&](const glm::vec3& c) {
      float rgb[3] = {c.x * exposure, c.y * exposure, c.z * exposure};
      to_output(rgb);
      for (float v : rgb) extra[k++] = v;
    };
    for (const glm::vec3& c : t.contribution) put(c);
    put(t.rest);
    return t.shade;
  };
  Image img = render_frame(scene, scene.render.treemaker_spp, static_cast<int>(names.size()), trace,
                           to_output, progress, stats);
  img.extra_names = names;
  return img;
}

}  // namespace arbor::trace
