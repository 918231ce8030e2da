// Benchmark: `grow` of the four appendix species of Weber & Penn 1995 and of the shipped
// L-systems, fractal trees, TREE-MAKER templates and skeleton file (seed 1, quality 1, one thread),
// reporting stems and leaves grown and the peak resident memory of the process; and the build of
// scenes/forest.toml's tree prototypes (its 4 Black Tupelo variants) on one thread and on every
// core (forest_build/threads:1 and /threads:0; CPU seconds and wall time both reported).
#include <sys/resource.h>

#include <string>

#include <benchmark/benchmark.h>

#include "generator/grow.h"
#include "generator/species.h"
#include "formats/scene_file.h"
#include "formats/species_file.h"
#include "scene/scene.h"

namespace {

void grow_species(benchmark::State& state, const char* file) {
  const arbor::generator::Species species =
      arbor::formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/" + file);
  arbor::generator::GrowOptions options;
  options.seed = 1;
  size_t stems = 0, leaves = 0;
  for (auto _ : state) {
    arbor::generator::Skeleton skeleton = arbor::generator::grow_tree(species, options);
    stems = skeleton.stems.size();
    leaves = skeleton.leaves.size();
    benchmark::DoNotOptimize(skeleton.points.data());
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["stems"] = static_cast<double>(stems);
  state.counters["leaves"] = static_cast<double>(leaves);
  state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// The prototypes of a scene with a forest: species read, variants grown and their geometry built
// (build_scene with `threads`; Embree is not involved).
void forest_build(benchmark::State& state) {
  const arbor::spec::SceneDesc desc =
      arbor::formats::load_scene(std::string(ARBOR_SOURCE_DIR) + "/scenes/forest.toml");
  const std::string ocio = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";
  std::size_t prototypes = 0;
  for (auto _ : state) {
    const auto scene =
        arbor::scene::build_scene(desc, ocio, nullptr, 0, static_cast<unsigned>(state.range(0)));
    prototypes = scene->prototypes.size();
  }
  state.counters["prototypes"] = static_cast<double>(prototypes);
}

}  // namespace

BENCHMARK_CAPTURE(grow_species, quaking_aspen, "quaking_aspen.toml")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, black_tupelo, "black_tupelo.toml")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, ca_black_oak, "ca_black_oak.toml")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, weeping_willow, "weeping_willow.toml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, lsystem_2d_branching, "lsystem_2d_branching.lsys")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, lsystem_weed, "lsystem_weed.lsys")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, lsystem_bush, "lsystem_bush.lsys")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, lsystem_realistic_tree, "lsystem_realistic_tree.lsys")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, lsystem_almost_real, "lsystem_almost_real.lsys")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, fractal_basic, "fractal_basic.toml")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, fractal_broadleaf, "fractal_broadleaf.toml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, young_tree_skel, "young_tree.skel")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, dogwood_tmpl, "dogwood.tmpl")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, young_pine_tmpl, "young_pine.tmpl")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grow_species, weeping_cherry_tmpl, "weeping_cherry.tmpl")
    ->Unit(benchmark::kMillisecond);

BENCHMARK(forest_build)
    ->Arg(1)
    ->Arg(0)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

BENCHMARK_MAIN();
