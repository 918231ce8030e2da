// Renderer benchmarks on the default scene (scenes/default.toml), one thread each:
// - raw_embree_rays: incoherent random rays (origins in the tree's box, uniform directions)
//   through rtcIntersect1 on the world's Embree scene — the ceiling for the path tracer;
// - path_tracer: the default scene rendered at 160×120, 16 spp; rays/s and samples/s counters
//   (the scene's metered exposure replaced by a fixed one in every render here);
// - meter: the auto-exposure meter's preview of the default scene (tracer/exposure.h);
// - frame/path_64spp and frame/treemaker: the default scene's frame (its camera, 160×120) by the
//   path integrator at 64 spp and by the treemaker integrator at its default treemaker_spp —
//   bench/run.sh prints their ratio (issue 6's target: treemaker ≥ 50× faster);
// - ray_replay: the default scene at 160×120, 16 spp, rendered once with every ray it traces
//   recorded (World::log_rays), then exactly those rays replayed through rtcIntersect1 /
//   rtcOccluded1 on the same Embree scene (its leaf-card filter included); counters: the render's
//   rays per CPU-second, the replay's, and their ratio `of_raw_embree` — Embree's share of the
//   render, without arbor's shading, sampling and sky (issue 27's target: ≥ 0.8);
// - world_build: growing, meshing and BVH building for the default scene;
// - forest_1000: the world of 1,000 Black Tupelos from 8 variants (peak RSS counter; run alone
//   by bench/run.sh so the peak is its own).
#include <sys/resource.h>

#include <string>

#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>
#include <embree3/rtcore.h>

#include "common/math.h"
#include "common/rng.h"
#include "tracer/film.h"
#include "tracer/exposure.h"
#include "tracer/render.h"
#include "formats/scene_file.h"
#include "tracer/lights/sky.h"
#include "imaging/color.h"
#include "scene/scene.h"
#include "tracer/embree/embree_internal.h"
#include "tracer/embree/world.h"

namespace {

using namespace arbor;

const std::string kOcioConfig = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";

// The scene built and put in Embree, as `arbor render` does.
struct BuiltWorld {
  BuiltWorld(const spec::SceneDesc& desc, const tracer::EmbreeDevice& device)
      : scene(scene::build_scene(desc, kOcioConfig)), world(*scene, device) {}
  std::unique_ptr<const scene::Scene> scene;
  tracer::World world;
};

spec::SceneDesc default_scene() {
  spec::SceneDesc s = formats::load_scene(std::string(ARBOR_SOURCE_DIR) + "/scenes/default.toml");
  s.render.threads = 1;
  // A fixed exposure: the renders measure the path tracer, not the meter (`meter` does).
  s.camera.auto_exposure = false;
  return s;
}

void raw_embree_rays(benchmark::State& state) {
  const spec::SceneDesc scene = default_scene();
  const tracer::EmbreeDevice device("threads=1");
  const BuiltWorld built(scene, device);
  const tracer::World& world = built.world;
  Rng rng(1);
  std::vector<RTCRayHit> rays(1 << 16);
  for (RTCRayHit& r : rays) {
    r = {};
    r.ray.org_x = static_cast<float>(rng.vary(0.0, 4.0));
    r.ray.org_y = static_cast<float>(rng.vary(0.0, 4.0));
    r.ray.org_z = static_cast<float>(rng.uniform() * 13.0);
    const double z = rng.symmetric(), phi = 2 * kPi * rng.uniform();
    const double s = std::sqrt(std::max(0.0, 1 - z * z));
    r.ray.dir_x = static_cast<float>(s * std::cos(phi));
    r.ray.dir_y = static_cast<float>(s * std::sin(phi));
    r.ray.dir_z = static_cast<float>(z);
  }
  std::size_t traced = 0;
  for (auto _ : state) {
    for (RTCRayHit r : rays) {
      r.ray.tnear = 0.0f;
      r.ray.tfar = 1e30f;
      r.ray.mask = ~0u;
      r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      rtcIntersect1(world.embree_scene(), &context, &r);
      benchmark::DoNotOptimize(r.hit.geomID);
    }
    traced += rays.size();
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(traced), benchmark::Counter::kIsRate);
}

// Renders the default scene's view at 160×120 with `spp` path samples (the treemaker integrator
// at its own treemaker_spp) for every iteration; rays/s, samples/s and spp counters.
void render_frames(benchmark::State& state, int spp, bool treemaker) {
  spec::SceneDesc scene = default_scene();
  scene.render.width = 160;
  scene.render.height = 120;
  scene.render.spp = spp;
  if (treemaker) scene.render.integrator = spec::Integrator::Treemaker;
  const tracer::EmbreeDevice device("threads=1");
  const BuiltWorld built(scene, device);
  const tracer::World& world = built.world;
  const tracer::Sky sky(scene.sky, scene.sun,
                        imaging::ColorPipeline(kOcioConfig).xyz_to_scene_linear());
  std::uint64_t rays = 0, samples = 0;
  for (auto _ : state) {
    imaging::RenderStats stats;
    const imaging::Image img = tracer::render_image(
        scene::render_input(scene), world, sky, [](float*) {}, stats);
    benchmark::DoNotOptimize(img.beauty.data());
    rays += stats.rays;
    samples += stats.samples;
  }
  state.counters["spp"] = treemaker ? scene.render.treemaker_spp : scene.render.spp;
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["samples_per_s"] =
      benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
}

void path_tracer(benchmark::State& state) { render_frames(state, 16, false); }

// `[camera] exposure = "auto"`'s meter (tracer/exposure.h) on the default scene at its size.
void meter(benchmark::State& state) {
  const spec::SceneDesc scene = default_scene();
  const tracer::EmbreeDevice device("threads=1");
  const BuiltWorld built(scene, device);
  const tracer::Sky sky(scene.sky, scene.sun,
                        imaging::ColorPipeline(kOcioConfig).xyz_to_scene_linear());
  const scene::RenderInput input = scene::render_input(scene);
  tbb::task_arena one(1);  // its rows run on one thread, so CPU time is all of it
  for (auto _ : state) {
    one.execute(
        [&] { benchmark::DoNotOptimize(tracer::metered_exposure(input, built.world, sky)); });
  }
}

void frame(benchmark::State& state, bool treemaker) { render_frames(state, 64, treemaker); }

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void ray_replay(benchmark::State& state) {
  spec::SceneDesc scene = default_scene();
  scene.render.width = 160;
  scene.render.height = 120;
  scene.render.spp = 16;
  const tracer::EmbreeDevice device("threads=1");
  BuiltWorld built(scene, device);
  tracer::World& world = built.world;
  const tracer::Sky sky(scene.sky, scene.sun,
                        imaging::ColorPipeline(kOcioConfig).xyz_to_scene_linear());
  // The render is deterministic: the logged render traced the rays the timed one did, so both
  // timings are over the same `rays`.
  double rays = 0.0, render_cpu = 0.0, replay_cpu = 0.0;
  for (auto _ : state) {
    // The render alone (no log), then once more with the log to know its rays.
    imaging::RenderStats stats;
    double t0 = cpu_seconds();
    benchmark::DoNotOptimize(tracer::render_image(
        scene::render_input(scene), world, sky, [](float*) {}, stats));
    render_cpu += cpu_seconds() - t0;
    tracer::RayLog log;
    world.log_rays(&log);
    imaging::RenderStats logged;
    tracer::render_image(
        scene::render_input(scene), world, sky, [](float*) {}, logged);
    world.log_rays(nullptr);
    t0 = cpu_seconds();
    for (const tracer::Ray& ray : log.closest) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      RTCRayHit rh = tracer::embree_ray_hit(ray);
      rtcIntersect1(world.embree_scene(), &context, &rh);
      benchmark::DoNotOptimize(rh.hit.geomID);
    }
    for (const tracer::Ray& ray : log.shadow) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      RTCRay r = tracer::embree_ray(ray);
      rtcOccluded1(world.embree_scene(), &context, &r);
      benchmark::DoNotOptimize(r.tfar);
    }
    replay_cpu += cpu_seconds() - t0;
    rays += static_cast<double>(log.closest.size() + log.shadow.size());
    state.counters["rays_counted_by_render"] = static_cast<double>(logged.rays);
    state.counters["shadow_fraction"] = static_cast<double>(log.shadow.size()) /
                                        static_cast<double>(log.closest.size() + log.shadow.size());
  }
  state.counters["render_rays_per_cpu_s"] = rays / render_cpu;
  state.counters["replay_rays_per_cpu_s"] = rays / replay_cpu;
  state.counters["of_raw_embree"] = replay_cpu / render_cpu;
}

void world_build(benchmark::State& state) {
  const spec::SceneDesc scene = default_scene();
  const tracer::EmbreeDevice device("threads=1");
  for (auto _ : state) {
    const BuiltWorld built(scene, device);
    benchmark::DoNotOptimize(built.world.embree_scene());
  }
}

void forest_1000(benchmark::State& state) {
  spec::SceneDesc scene;
  spec::ForestDesc f;
  f.species = std::string(ARBOR_SOURCE_DIR) + "/species/black_tupelo.toml";
  f.count = 1000;
  f.variants = 8;
  f.area = {-200.0, -200.0, 200.0, 200.0};
  scene.forests.push_back(f);
  const tracer::EmbreeDevice device("threads=1");
  for (auto _ : state) {
    const BuiltWorld built(scene, device);
    state.counters["instances"] = static_cast<double>(built.scene->stats.instances);
    state.counters["prototypes"] = static_cast<double>(built.scene->stats.prototypes);
    state.counters["geometry_MB"] = static_cast<double>(built.scene->stats.geometry_bytes) / 1e6;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace

BENCHMARK(raw_embree_rays)->Unit(benchmark::kMillisecond);
BENCHMARK(path_tracer)->Unit(benchmark::kMillisecond);
BENCHMARK(meter)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(frame, path_64spp, false)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(frame, treemaker, true)->Unit(benchmark::kMillisecond);
BENCHMARK(ray_replay)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(world_build)->Unit(benchmark::kMillisecond);
BENCHMARK(forest_1000)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
