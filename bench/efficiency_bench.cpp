// The path tracer's efficiency (issue 13): 1 / (variance × render time) on the default scene at
// 240×180, 64 spp, 2 threads, without adaptive sampling. The variance is measured, not estimated:
// two renders with seeds 1 and 2, var = mean over pixels and channels of (a − b)² / 2, the
// variance of one render's pixel. Each iteration renders both; counters: seconds (one render),
// samples_per_s, rays_per_s, variance, efficiency. Compare commits by running this benchmark
// from each (interleaved) and taking the ratio of their efficiency.
#include <chrono>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "formats/scene_desc.h"
#include "imaging/color.h"
#include "scene/scene.h"
#include "tracer/embree/world.h"
#include "tracer/lights/sky.h"
#include "tracer/render.h"

namespace {

using namespace arbor;

const std::string kOcioConfig = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";

void efficiency(benchmark::State& state) {
  trace::SceneDesc s = trace::load_scene(std::string(ARBOR_SOURCE_DIR) + "/scenes/default.toml");
  s.render.width = 240;
  s.render.height = 180;
  s.render.spp = 64;
  s.render.threads = 2;
  s.render.noise_threshold = 0;
  const trace::EmbreeDevice device("threads=2");
  const std::unique_ptr<const trace::Scene> scene = trace::build_scene(s, kOcioConfig);
  const trace::World world(*scene, device);
  const trace::ColorPipeline color(kOcioConfig);
  const trace::Sky sky(s.sky, s.sun, color.xyz_to_scene_linear());
  const trace::ColorTransform to_output = color.to_output(s.output.colorspace);
  double seconds = 0, variance = 0;
  std::uint64_t samples = 0, rays = 0;
  int renders = 0;
  for (auto _ : state) {
    trace::Image images[2];
    for (int k = 0; k < 2; ++k) {
      s.render.seed = static_cast<std::uint64_t>(k + 1);
      trace::RenderStats stats;
      const auto start = std::chrono::steady_clock::now();
      images[k] = trace::render_image(s, world, sky, to_output, stats);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      samples += stats.samples;
      rays += stats.rays;
      ++renders;
    }
    double sum = 0;
    for (std::size_t p = 0; p < images[0].beauty.size(); ++p) {
      for (int c = 0; c < 3; ++c) {
        const double d = double(images[0].beauty[p][c]) - images[1].beauty[p][c];
        sum += 0.5 * d * d;
      }
    }
    variance = sum / (3.0 * double(images[0].beauty.size()));
  }
  const double per_render = seconds / renders;
  state.counters["seconds"] = per_render;
  state.counters["samples_per_s"] = double(samples) / seconds;
  state.counters["rays_per_s"] = double(rays) / seconds;
  state.counters["variance"] = variance;
  state.counters["efficiency"] = 1.0 / (variance * per_render);
}

}  // namespace

BENCHMARK(efficiency)->Unit(benchmark::kMillisecond)->Iterations(3);

BENCHMARK_MAIN();
