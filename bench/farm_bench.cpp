// The cost of splitting a render into farm work units (docs/farm.md): the default scene at
// 480×360 and 64 spp (4 passes of 16) rendered once by `arbor render`, and as the units of
// `arbor plan` run one after another, each a process of its own as on a farm (so each loads the
// scene, grows the tree and builds the BVH again), then merged. Benchmarks, one iteration each:
// - whole: the single render;
// - units:N: the N units' summed time (N = 4: 2x2 tiles; 16: 4x4 tiles; 64: 4x4 tiles × 4 pass
//   groups), counters merge_seconds and units.
// bench/run.sh prints each sum over the single render: the split's overhead.
#include <chrono>
#include <cstdio>
#include <stdio.h>  // popen
#include <cstdlib>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

namespace {

const std::string kScene = std::string(ARBOR_SOURCE_DIR) + "/scenes/default.toml";
const std::string kArbor = ARBOR_BINARY;
const std::string kDir = "/tmp/arbor_farm_bench/";
const std::string kSettings = " --spp 64 --threads 0";

double run(const std::string& command) {
  const auto start = std::chrono::steady_clock::now();
  if (std::system((command + " > /dev/null 2>&1").c_str()) != 0) {
    std::fprintf(stderr, "farm_bench: failed: %s\n", command.c_str());
    std::exit(1);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<std::string> plan(const std::string& tiles, int groups) {
  const std::string command = kArbor + " plan " + kScene + " --spp 64 --tiles " + tiles +
                              " --pass-groups " + std::to_string(groups) + " -o " + kDir +
                              "split.exr";
  std::vector<std::string> lines;
  if (std::FILE* f = popen(command.c_str(), "r")) {
    char buf[8192];
    while (std::fgets(buf, sizeof buf, f)) {
      std::string l(buf);
      if (!l.empty() && l.back() == '\n') l.pop_back();
      lines.push_back(l);
    }
    pclose(f);
  }
  if (lines.size() < 2) {
    std::fprintf(stderr, "farm_bench: no plan from: %s\n", command.c_str());
    std::exit(1);
  }
  return lines;
}

void whole(benchmark::State& state) {
  std::system(("rm -rf " + kDir + " && mkdir -p " + kDir).c_str());
  for (auto _ : state) {
    state.SetIterationTime(
        run(kArbor + " render " + kScene + kSettings + " -o " + kDir + "whole.exr"));
  }
}

void units(benchmark::State& state, const std::string& tiles, int groups) {
  for (auto _ : state) {
    std::system(("rm -rf " + kDir + "split.parts").c_str());
    std::vector<std::string> lines = plan(tiles, groups);
    const std::string merge = lines.back();
    lines.pop_back();
    double sum = 0.0;
    for (const std::string& l : lines) sum += run(l + " --threads 0");
    state.SetIterationTime(sum);
    state.counters["merge_seconds"] = run(merge);
    state.counters["units"] = static_cast<double>(lines.size());
  }
}

}  // namespace

BENCHMARK(whole)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(units, 4, "2x2", 1)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(units, 16, "4x4", 1)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(units, 64, "4x4", 4)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK_MAIN();
