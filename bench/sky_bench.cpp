// The sky models against the Monte Carlo simulation of their atmosphere (tracer/lights/
// sky_monte_carlo.h), and what a model costs to build (issue 28). Benchmarks, one iteration each:
// - build/model:M/sun:E: constructing the model (M = 0 Nishita's single scattering, 1 every
//   order: the exact second order and the tables of the further ones, ground albedo 0.3; 2 the
//   same for aerial perspective alone, as a render whose map is cached builds it) for a sun at E
//   degrees, dust 3;
// - accuracy/model:M/sun:E: the model's Y over the simulation's (the same ground; 40,000 paths a
//   direction, errors 0.6–2.3 %; M = 2: the atmosphere's first two orders against the
//   simulation's paths of at most two events) in 7 directions — the zenith, the horizon at 5°
//   towards, across and away from the sun, 30° up at 45° and 135° from it, 15° above the sun —
//   counters d0 … d6 (each direction's ratio, in that order), ratio_min, ratio_max and worst (the
//   largest |ratio − 1|);
// - shape/model:M/sun:E: at Linke turbidity 3 (Nishita: its dust, 2.65) over the default ground
//   (albedo 0.14), as ratios to the direct sun's normal irradiance at the ground, per sr: zenith,
//   horizon (3°) 90° and 180° from the sun, and the diffuse fraction of the horizontal irradiance
//   (16 bands × 32 azimuths) — docs/rendering.md's table of four sun elevations; and the zenith's
//   and that horizon's chromaticity x, y and its distance above the CIE daylight locus;
// - aerial/sun:E: the aerial perspective table (tracer/lights/aerial.h) of the atmosphere model at
//   Linke turbidity 3 (the model built outside the timing);
// - map/model:M: the whole 512 × 256 sky map a render makes (M = 0 nishita, 1 atmosphere; sun 40°,
//   dust 3 / turbidity 3, the disk cache off), on one thread.
//   build/sky_bench --benchmark_out=sky.json --benchmark_out_format=json
#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include "common/math.h"
#include "spec/scene_desc.h"
#include "tracer/lights/aerial.h"
#include "tracer/lights/sky_model.h"
#include "tracer/lights/nishita.h"
#include "tracer/lights/sky_monte_carlo.h"

namespace {

using namespace arbor;
using namespace arbor::tracer;

glm::dvec3 direction(double elevation_deg, double azimuth_deg) {
  const double e = radians(elevation_deg), a = radians(azimuth_deg);
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

Atmosphere air(bool multiple) {
  Atmosphere a{1.0, 3.0, 1.0, 0.0};
  a.multiple_scattering = multiple;
  a.ground_albedo = 0.3;
  return a;
}

void build(benchmark::State& state) {
  Atmosphere a = air(state.range(0) != 0);
  a.sky = state.range(0) != 2;
  const glm::dvec3 sun = direction(static_cast<double>(state.range(1)), 0.0);
  for (auto _ : state) benchmark::DoNotOptimize(NishitaSky(a, sun, 1.0).sun_irradiance_xyz());
}

void accuracy(benchmark::State& state) {
  Atmosphere a = air(state.range(0) != 0);
  a.orders = state.range(0) == 2 ? 2 : 0;
  const double elevation = static_cast<double>(state.range(1));
  const glm::dvec3 sun = direction(elevation, 0.0);
  double lo = HUGE_VAL, hi = 0.0;
  for (auto _ : state) {
    const NishitaSky model(a, sun, 1.0);
    SkyMonteCarloOptions o;
    o.paths = 40000;
    o.ground_albedo = a.ground_albedo;
    o.max_orders = a.orders;
    std::uint64_t seed = 1;
    int n = 0;
    for (const auto& [e, az] : std::vector<std::pair<double, double>>{
             {90, 0}, {5, 0}, {5, 90}, {5, 180}, {30, 45}, {30, 135}, {elevation + 15.0, 0}}) {
      const glm::dvec3 view = direction(std::min(e, 90.0), az);
      o.seed = seed++;
      const double ratio =
          model.radiance_xyz(view, 256).y / simulate_sky_radiance(model, a, sun, view, o).xyz.y;
      state.counters["d" + std::to_string(n++)] = ratio;
      lo = std::min(lo, ratio);
      hi = std::max(hi, ratio);
    }
  }
  state.counters["ratio_min"] = lo;
  state.counters["ratio_max"] = hi;
  state.counters["worst"] = std::max(1.0 - lo, hi - 1.0);
}

void shape(benchmark::State& state) {
  Atmosphere a{1.0, atmosphere::dust_for_turbidity(3.0), 1.0, 0.0};
  a.multiple_scattering = state.range(0) != 0;
  a.ground_albedo = a.multiple_scattering ? spec::mean_albedo({}) : 0.0;
  const double elevation = static_cast<double>(state.range(1));
  for (auto _ : state) {
    const NishitaSky m(a, direction(elevation, 0.0), 1.0);
    const double beam = m.sun_irradiance_xyz().y;
    double e = 0.0;
    for (int i = 0; i < 16; ++i) {
      const double mu = (i + 0.5) / 16, el = degrees(std::asin(mu));
      for (int j = 0; j < 32; ++j)
        e += m.radiance_xyz(direction(el, 360.0 * (j + 0.5) / 32), 24).y * mu *
             (2.0 * kPi / (16 * 32));
    }
    state.counters["zenith"] = m.radiance_xyz({0, 0, 1}).y / beam;
    state.counters["horizon90"] = m.radiance_xyz(direction(3, 90)).y / beam;
    state.counters["horizon180"] = m.radiance_xyz(direction(3, 180)).y / beam;
    state.counters["diffuse"] = e / (e + beam * std::sin(radians(elevation)));
    // Chromaticity, and its distance above the CIE daylight locus y = −3x² + 2.87x − 0.275.
    for (const auto& [name, v] : {std::pair<const char*, glm::dvec3>{"zenith", {0, 0, 1}},
                                  {"horizon90", direction(3, 90)}}) {
      const glm::dvec3 xyz = m.radiance_xyz(v);
      const double x = xyz.x / (xyz.x + xyz.y + xyz.z), y = xyz.y / (xyz.x + xyz.y + xyz.z);
      state.counters[std::string(name) + "_x"] = x;
      state.counters[std::string(name) + "_y"] = y;
      state.counters[std::string(name) + "_above_locus"] = y - (-3.0 * x * x + 2.87 * x - 0.275);
    }
  }
}

void aerial(benchmark::State& state) {
  Atmosphere a = air(true);
  a.dust_density = atmosphere::dust_for_turbidity(3.0);
  const NishitaSky model(a, direction(static_cast<double>(state.range(0)), 0.0), 1.0);
  const auto xyz = [](const glm::dvec3& v) { return glm::vec3(v); };
  for (auto _ : state) {
    const AerialPerspective table(model, xyz, model.extraterrestrial_xyz().y);
    benchmark::DoNotOptimize(table.at(glm::vec3(1.0f, 0.0f, 0.0f), 5000.0f));
  }
}

void map(benchmark::State& state) {
  setenv("ARBOR_CACHE_DIR", "off", 1);
  spec::SkyDesc sky;
  sky.model = state.range(0) ? spec::SkyModel::Atmosphere : spec::SkyModel::Nishita;
  sky.dust_density = 3.0;
  sky.turbidity = 3.0;
  sky.ground_albedo = spec::mean_albedo({});
  const spec::SunDesc sun{true, 40.0, 0.0, 3.0, 0.53};
  const imaging::ColorTransform identity = [](float*) {};
  tbb::task_arena one(1);
  for (auto _ : state) {
    one.execute([&] {
      benchmark::DoNotOptimize(
          make_sky_map({sky, sun, direction(40.0, 0.0), identity, 512, 0.0f}).texels.data());
    });
  }
}

}  // namespace

BENCHMARK(map)->ArgName("model")->DenseRange(0, 1)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(shape)
    ->ArgNames({"model", "sun"})
    ->ArgsProduct({{0, 1}, {10, 25, 40, 60}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(aerial)->ArgName("sun")->Arg(40)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(build)
    ->ArgNames({"model", "sun"})
    ->ArgsProduct({{0, 1, 2}, {10, 40, 60}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(accuracy)
    ->ArgNames({"model", "sun"})
    ->ArgsProduct({{0, 1, 2}, {10, 40, 60}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

BENCHMARK_MAIN();
