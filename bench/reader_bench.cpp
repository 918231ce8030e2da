// The hostile inputs that once hung or crashed the readers, timed: a skeleton point with 100,000
// limbs, limbs nested 20,000 deep, the largest TREE-MAKER template's size estimate, and an OBJ
// polygon of 100,000 vertices. Each should take well under a second.
#include <cmath>
#include <string>

#include <benchmark/benchmark.h>

#include "formats/skeleton_file.h"
#include "generator/models/treemaker/treemaker.h"
#include "generator/models/treemaker/treemaker_template.h"
#include "formats/obj_mesh.h"
#include "formats/treemaker_template.h"

namespace {

std::string many_children(int children) {
  std::string text = "radius 0.01\npoint 0 0 0 0\npoint 1 0 0 10\nconnect 0 1\n";
  for (int k = 0; k < children; ++k) {
    const std::string id = std::to_string(k + 2);
    text += "point " + id + " " + std::to_string(1 + k % 7) + " " + std::to_string(k / 7) +
            " 5 0.001\nconnect 1 " + id + "\n";
  }
  return text;
}

std::string deeply_nested(int depth) {
  std::string text = "radius 0.001\npoint 0 0 0 0\n";
  for (int k = 0; k < depth; ++k) {
    const std::string at = std::to_string(k == 0 ? 0 : 2 * k - 1), a = std::to_string(2 * k + 1),
                      b = std::to_string(2 * k + 2), z = std::to_string(k + 1);
    text += "point " + a + " 0 0 " + z + "\npoint " + b + " 1 0 " + z + "\nconnect " + at + " " +
            a + "\nconnect " + at + " " + b + "\n";
  }
  return text;
}

void BM_SkeletonManyChildrenOfOnePoint(benchmark::State& state) {
  const std::string text = many_children(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(arbor::formats::parse_skeleton_file(text, "b.skel"));
}
BENCHMARK(BM_SkeletonManyChildrenOfOnePoint)->Arg(100000)->Unit(benchmark::kMillisecond);

void BM_SkeletonNestedDeep(benchmark::State& state) {
  const std::string text = deeply_nested(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(arbor::formats::parse_skeleton_file(text, "b.skel"));
}
BENCHMARK(BM_SkeletonNestedDeep)->Arg(20000)->Unit(benchmark::kMillisecond);

void BM_TreemakerEstimateOfTheLargestTemplate(benchmark::State& state) {
  std::string text = "iterations { i= 1000 }\ncolor { green= 0,1,0 }\n";
  for (int level = 1; level <= 1000; level += 37) {
    text += "branch { level= " + std::to_string(level) +
            " number= 1 to 2 (p=1 angle= 30 to 40 dir= 0 to 360 factor= 1 to 1) }\n";
  }
  text +=
      "particle { pos=0,0,0 mag= 10 to 12 dir= 0,0,1:5 growth= 0.2 color= green brightness= 0.5 to "
      "0.6 }\n"
      "leaf { p= 1 coord= limb out= 10 up= 10 color= green brightness= 0.5 to 0.6 tri= 0,0,0 1,0,1 "
      "-1,0,1 }\n";
  const arbor::generator::TreeMakerTemplate t =
      arbor::formats::parse_treemaker_template(text, "b.tmpl");
  for (auto _ : state) benchmark::DoNotOptimize(arbor::generator::treemaker_estimate(t));
}
BENCHMARK(BM_TreemakerEstimateOfTheLargestTemplate)->Unit(benchmark::kMillisecond);

void BM_ObjHugePolygon(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::string text;
  for (int k = 0; k < n; ++k) {
    const double a = 6.283185307179586 * k / n;
    text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
  }
  text += "f";
  for (int k = 1; k <= n; ++k) text += " " + std::to_string(k);
  text += "\n";
  for (auto _ : state) benchmark::DoNotOptimize(arbor::formats::parse_obj(text, "b.obj"));
}
BENCHMARK(BM_ObjHugePolygon)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
