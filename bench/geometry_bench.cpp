// Benchmarks of the renderer's tree geometry, per appendix species (seed 1, quality 1, one
// thread): building TreeGeometry from the skeleton, counting it without building it (what
// `grow --stats` does), building Embree's BVH for it, and the bytes
// of the limbs as exact curves against the same limbs tessellated to triangles (Lane's bound at
// 5 % of the radius, what `arbor grow -o tree.obj` writes).
#include <string>

#include <benchmark/benchmark.h>

#include "generator/species.h"
#include "generator/geometry/geometry_plan.h"
#include "generator/geometry/tree_mesh.h"
#include "generator/models/weber_penn/weber_penn.h"
#include "tracer/embree/embree_scene.h"
#include "formats/species_file.h"

namespace {

arbor::generator::Skeleton grow(const char* file) {
  const arbor::generator::Species species =
      arbor::formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/" + file);
  arbor::generator::GrowOptions options;
  options.seed = 1;
  return arbor::generator::grow_weber_penn(species.weber_penn(), options);
}

void build_geometry(benchmark::State& state, const char* file) {
  const arbor::generator::Skeleton skeleton = grow(file);
  arbor::generator::GeometryStats stats;
  for (auto _ : state) {
    const arbor::generator::TreeGeometry g = arbor::generator::build_tree_geometry(skeleton);
    stats = g.stats;
    benchmark::DoNotOptimize(g.curves.points.data());
  }
  state.counters["curve_segments"] = static_cast<double>(stats.curve_segments);
  state.counters["geometry_MB"] = static_cast<double>(stats.bytes) / 1e6;
}

// The same with Bloomenthal's ramiform at the forks (`[bark] ramiform = true`; issue 30): its
// cost over build_geometry, and the collars built and left out.
void build_geometry_ramiform(benchmark::State& state, const char* file) {
  const arbor::generator::Skeleton skeleton = grow(file);
  arbor::generator::GeometryOptions options;
  options.ramiform = true;
  arbor::generator::GeometryStats stats;
  for (auto _ : state) {
    const arbor::generator::TreeGeometry g =
        arbor::generator::build_tree_geometry(skeleton, options);
    stats = g.stats;
    benchmark::DoNotOptimize(g.ramiforms.positions.data());
  }
  state.counters["collars"] = static_cast<double>(stats.ramiforms);
  state.counters["forks_left_out"] = static_cast<double>(stats.ramiforms_skipped);
  state.counters["geometry_MB"] = static_cast<double>(stats.bytes) / 1e6;
}

// What `arbor grow --stats` does instead of building: counting the same geometry (issue 31).
void count_geometry(benchmark::State& state, const char* file) {
  const arbor::generator::Skeleton skeleton = grow(file);
  arbor::generator::GeometryStats stats;
  for (auto _ : state) {
    stats = arbor::generator::count_tree_geometry(skeleton, {});
    benchmark::DoNotOptimize(stats);
  }
  state.counters["curve_segments"] = static_cast<double>(stats.curve_segments);
}

void build_bvh(benchmark::State& state, const char* file) {
  const arbor::generator::TreeGeometry g = arbor::generator::build_tree_geometry(grow(file));
  const arbor::tracer::EmbreeDevice device("threads=1");
  for (auto _ : state) {
    const arbor::tracer::TreePrototype tree(device, g);
    benchmark::DoNotOptimize(tree.scene());
  }
}

// Bytes of the limbs (curves: Hermite points, tangents and per-segment metadata) against the
// same limbs as an indexed triangle mesh (positions, normals, uv, indices). Trunk grids are the
// same in both and reported apart.
void limb_bytes(benchmark::State& state, const char* file) {
  const arbor::generator::TreeGeometry g = arbor::generator::build_tree_geometry(grow(file));
  arbor::generator::TreeGeometry limbs_only = g;
  limbs_only.grids = {};
  limbs_only.leaves = {};
  std::size_t mesh_bytes = 0;
  for (auto _ : state) {
    const arbor::generator::TreeMesh mesh = arbor::generator::tessellate(limbs_only);
    mesh_bytes = mesh.positions.size() * (sizeof(glm::vec3) * 2 + sizeof(glm::vec2)) +
                 mesh.indices.size() * sizeof(std::uint32_t);
    benchmark::DoNotOptimize(mesh.indices.data());
  }
  const double curve_bytes = static_cast<double>(
      g.curves.points.size() * sizeof(glm::vec4) + g.curves.tangents.size() * sizeof(glm::vec4) +
      g.curves.segments.size() * sizeof(arbor::generator::CurveSegment));
  const double grid_bytes =
      static_cast<double>(g.grids.vertices.size() * (2 * sizeof(glm::vec3) + sizeof(glm::vec2)));
  state.counters["curve_MB"] = curve_bytes / 1e6;
  state.counters["limb_mesh_MB"] = static_cast<double>(mesh_bytes) / 1e6;
  state.counters["curve_to_mesh_ratio"] = curve_bytes / static_cast<double>(mesh_bytes);
  state.counters["trunk_grid_MB"] = grid_bytes / 1e6;
}

}  // namespace

#define ARBOR_SPECIES_BENCH(fn)                                                              \
  BENCHMARK_CAPTURE(fn, quaking_aspen, "quaking_aspen.toml")->Unit(benchmark::kMillisecond); \
  BENCHMARK_CAPTURE(fn, black_tupelo, "black_tupelo.toml")->Unit(benchmark::kMillisecond);   \
  BENCHMARK_CAPTURE(fn, ca_black_oak, "ca_black_oak.toml")->Unit(benchmark::kMillisecond);   \
  BENCHMARK_CAPTURE(fn, weeping_willow, "weeping_willow.toml")->Unit(benchmark::kMillisecond)

ARBOR_SPECIES_BENCH(build_geometry);
ARBOR_SPECIES_BENCH(count_geometry);
ARBOR_SPECIES_BENCH(build_bvh);
ARBOR_SPECIES_BENCH(limb_bytes);
BENCHMARK_CAPTURE(build_geometry_ramiform, quaking_aspen, "quaking_aspen.toml")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(build_geometry_ramiform, ca_black_oak, "ca_black_oak.toml")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

BENCHMARK_MAIN();
