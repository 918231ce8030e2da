// Adaptive sampling against uniform sampling on the default scene's view (120×90, one thread),
// at equal error: the 95th percentile over pixels of the relative error
// max_c |x_c - ref_c| / max(|ref_c|, 0.01) against a 1024-spp reference (seed 99, two threads,
// not timed). Benchmarks, each one iteration:
// - uniform/spp:N: every pixel N samples; counters p95_error, mean_spp;
// - adaptive/threshold:T/spp:N: noise_threshold T/1000, at most N samples, min_spp 16;
//   counters p95_error, mean_spp.
// bench/run.sh interpolates the uniform renders' time at each adaptive render's p95 error
// (log-log between the neighbouring spp) and prints the ratio.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "formats/scene_file.h"
#include "imaging/color.h"
#include "scene/scene.h"
#include "tracer/embree/world.h"
#include "tracer/lights/sky.h"
#include "tracer/render.h"

namespace {

using namespace arbor;

const std::string kOcioConfig = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";

spec::SceneDesc view(int spp, int threads) {
  spec::SceneDesc s = formats::load_scene(std::string(ARBOR_SOURCE_DIR) + "/scenes/default.toml");
  s.render.width = 120;
  s.render.height = 90;
  s.render.spp = spp;
  s.render.threads = threads;
  s.camera.auto_exposure = false;  // a fixed exposure: the renders compare sampling, not the meter
  return s;
}

imaging::Image render(const spec::SceneDesc& s) {
  const tracer::EmbreeDevice device("threads=" + std::to_string(s.render.threads));
  const std::unique_ptr<const scene::Scene> scene = scene::build_scene(s, kOcioConfig);
  const tracer::World world(*scene, device);
  const imaging::ColorPipeline color(kOcioConfig);
  const tracer::Sky sky(s.sky, s.sun, color.xyz_to_scene_linear());
  imaging::RenderStats stats;
  return tracer::render_image(scene::render_input(s), world, sky,
                              color.to_output(s.output.colorspace), stats);
}

const imaging::Image& reference() {
  static const imaging::Image ref = [] {
    spec::SceneDesc s = view(1024, 2);
    s.render.seed = 99;
    return render(s);
  }();
  return ref;
}

double p95_error(const imaging::Image& img) {
  const imaging::Image& ref = reference();
  std::vector<double> e(img.beauty.size());
  for (std::size_t p = 0; p < e.size(); ++p) {
    double worst = 0;
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::fabs(double(img.beauty[p][c]) - ref.beauty[p][c]) /
                                  std::max(std::fabs(double(ref.beauty[p][c])), 0.01));
    }
    e[p] = worst;
  }
  std::nth_element(e.begin(), e.begin() + static_cast<long>(0.95 * double(e.size())), e.end());
  return e[static_cast<std::size_t>(0.95 * double(e.size()))];
}

void report(benchmark::State& state, const imaging::Image& img) {
  double total = 0;
  for (float n : img.samples) total += n;
  state.counters["p95_error"] = p95_error(img);
  state.counters["mean_spp"] = total / double(img.samples.size());
}

void uniform(benchmark::State& state) {
  reference();
  const spec::SceneDesc s = view(static_cast<int>(state.range(0)), 1);
  imaging::Image img;
  for (auto _ : state) img = render(s);
  report(state, img);
}

void adaptive(benchmark::State& state) {
  reference();
  spec::SceneDesc s = view(static_cast<int>(state.range(1)), 1);
  s.render.noise_threshold = static_cast<double>(state.range(0)) / 1000.0;
  s.render.min_spp = 16;
  imaging::Image img;
  for (auto _ : state) img = render(s);
  report(state, img);
}

}  // namespace

BENCHMARK(uniform)->ArgName("spp")->Arg(32)->Arg(64)->Arg(128)->Arg(256)->Iterations(1)->Unit(
    benchmark::kMillisecond);
BENCHMARK(adaptive)
    ->ArgNames({"threshold", "spp"})
    ->ArgsProduct({{150, 100, 70, 50}, {256}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
