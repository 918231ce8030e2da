// The path tracer's efficiency on whole scenes (issue 13): samples/s, rays/s and efficiency,
// 1 / (variance × render time), without adaptive sampling. The variance is measured, not
// estimated: two renders with seeds 1 and 2, var = mean over pixels and channels of (a − b)² / 2,
// the variance of one render's pixel. 2 threads; also the geometry arbor holds (its arrays, not
// Embree's BVH) and the process's peak RSS. Compare commits by running a scene from each
// (interleaved) and taking the ratio of their efficiency.
// - scene/default_curves: bench/scenes/issue13_default.toml (scenes/default.toml as it was when
//   issue 13 set its target, matte leaves) at 240×180, 64 spp (limbs as curves) — the efficiency
//   issue 13 sets its target on;
// - scene/default_glossy: the same with the species' leaf cuticle (issue 14): the coat's cost;
// - scene/default_triangles: the same tree exported by `arbor grow` as OBJ (limbs tessellated,
//   leaves triangulated) and rendered through [[mesh]] with the species' colours as Lambertian
//   bark and two-sided leaf materials; same camera, lights and settings;
// - scene/willow: one Weeping Willow (7 M triangles before leaf cards) at 240×180, 64 spp;
// - scene/forest_10000: scenes/forest_10000.toml (10,000 Black Tupelos from 8 variants) at its
//   640×360, 8 spp.
// bench/run.sh runs each in its own process so that peak_rss_MB is that scene's.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "formats/scene_file.h"
#include "formats/species_file.h"
#include "generator/export/export_mesh.h"
#include "generator/geometry/tree_geometry.h"
#include "generator/geometry/tree_mesh.h"
#include "generator/grow.h"
#include "imaging/color.h"
#include "scene/scene.h"
#include "tracer/embree/world.h"
#include "tracer/lights/sky.h"
#include "tracer/render.h"

namespace {

const std::string kSource = ARBOR_SOURCE_DIR;
const std::string kOcioConfig = kSource + "/imaging/ocio/config.ocio";

arbor::spec::SceneDesc default_scene() {
  arbor::spec::SceneDesc s =
      arbor::formats::load_scene(kSource + "/bench/scenes/issue13_default.toml");
  s.render.width = 240;
  s.render.height = 180;
  s.render.spp = 64;
  return s;
}

arbor::spec::SceneDesc default_glossy() {
  arbor::spec::SceneDesc s = default_scene();
  s.trees.at(0).leaf.cuticle_ior.reset();  // the species' own cuticle
  return s;
}

// The default scene's tree as an OBJ (written once per process) in a [[mesh]].
arbor::spec::SceneDesc default_triangles() {
  arbor::spec::SceneDesc s = default_scene();
  const arbor::spec::TreeDesc tree = s.trees.at(0);
  const arbor::generator::Species species = arbor::formats::load_species(tree.species);
  arbor::generator::GrowOptions grow;
  grow.seed = tree.seed;
  const arbor::generator::TreeGeometry geometry = arbor::generator::build_tree_geometry(
      arbor::generator::grow_tree(species, grow), arbor::generator::geometry_options_for(species));
  const std::string obj = "/tmp/arbor_scene_bench_tree.obj";
  arbor::generator::write_obj(arbor::generator::tessellate(geometry), obj,
                              {species.name, species.bark, species.leaf});
  arbor::spec::MeshDesc mesh;
  mesh.path = obj;
  arbor::spec::MeshMaterialDesc bark, leaf;
  bark.kind = "bark";
  bark.albedo = species.bark.albedo;
  leaf.kind = "leaf";
  leaf.reflectance = species.leaf.reflectance;
  leaf.back_reflectance = species.leaf.back_reflectance;
  leaf.transmittance = species.leaf.transmittance;
  leaf.cuticle_ior = 1.0;  // matte, as the scene's tree
  mesh.materials["bark"] = bark;
  mesh.materials["leaf"] = leaf;
  s.trees.clear();
  s.meshes.push_back(mesh);
  return s;
}

arbor::spec::SceneDesc willow() {
  arbor::spec::SceneDesc s = default_scene();
  s.trees.at(0).species = kSource + "/species/weeping_willow.toml";
  s.camera.position = {16.0, -22.0, 3.0};
  s.camera.look_at = {0.0, 0.0, 5.5};
  return s;
}

arbor::spec::SceneDesc forest() {
  arbor::spec::SceneDesc s = arbor::formats::load_scene(kSource + "/scenes/forest_10000.toml");
  s.render.spp = 8;
  return s;
}

void scene(benchmark::State& state, arbor::spec::SceneDesc (*make)()) {
  arbor::spec::SceneDesc s = make();
  s.render.threads = 2;
  s.render.noise_threshold = 0;
  const arbor::tracer::EmbreeDevice device("threads=2");
  const auto build_start = std::chrono::steady_clock::now();
  const std::unique_ptr<const arbor::scene::Scene> built =
      arbor::scene::build_scene(s, kOcioConfig);
  const arbor::tracer::World world(*built, device);
  const double build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
  const arbor::imaging::ColorPipeline color(kOcioConfig);
  const arbor::tracer::Sky sky(s.sky, s.sun, color.xyz_to_scene_linear());
  const arbor::imaging::ColorTransform to_output = color.to_output(s.output.colorspace);
  double seconds = 0, variance = 0;
  std::uint64_t samples = 0, rays = 0;
  int renders = 0;
  for (auto _ : state) {
    arbor::imaging::Image images[2];
    for (int k = 0; k < 2; ++k) {
      s.render.seed = static_cast<std::uint64_t>(k + 1);
      arbor::imaging::RenderStats stats;
      const auto start = std::chrono::steady_clock::now();
      images[k] =
          arbor::tracer::render_image(arbor::scene::render_input(s), world, sky, to_output, stats);
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
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double per_render = seconds / renders;
  state.counters["build_seconds"] = build_seconds;
  state.counters["seconds"] = per_render;
  state.counters["samples_per_s"] = double(samples) / seconds;
  state.counters["rays_per_s"] = double(rays) / seconds;
  state.counters["variance"] = variance;
  state.counters["efficiency"] = 1.0 / (variance * per_render);
  state.counters["triangles"] = double(built->stats.triangles);
  state.counters["geometry_MB"] = double(built->stats.geometry_bytes) / 1e6;
  state.counters["peak_rss_MB"] = double(usage.ru_maxrss) / 1024.0;
}

}  // namespace

BENCHMARK_CAPTURE(scene, default_curves, default_scene)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(scene, default_glossy, default_glossy)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(scene, default_triangles, default_triangles)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK_CAPTURE(scene, willow, willow)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(scene, forest_10000, forest)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
