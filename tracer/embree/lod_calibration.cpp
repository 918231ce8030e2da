// The crown's cover traced through the prototype at full detail and thinned, and the bisection.
#include "tracer/embree/lod_calibration.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "common/math.h"
#include "tracer/embree/embree_internal.h"

namespace arbor::tracer {

namespace {

constexpr int kGrid = 48;  // rays across each view

// How many of the rays of nine orthographic views of the bounds meet something in `scene`.
long cover(RTCScene scene, const glm::vec3& lo, const glm::vec3& hi) {
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float reach = glm::length(hi - lo);
  long total = 0;
  for (const double elevation : {0.0, 30.0, 60.0}) {
    for (const double azimuth : {0.0, 60.0, 120.0}) {
      const double e = elevation * kPi / 180.0, a = azimuth * kPi / 180.0;
      const glm::vec3 d(static_cast<float>(std::cos(e) * std::cos(a)),
                        static_cast<float>(std::cos(e) * std::sin(a)),
                        static_cast<float>(-std::sin(e)));
      const glm::vec3 u = glm::normalize(glm::cross(d, glm::vec3(0, 0, 1)));
      const glm::vec3 v = glm::cross(u, d);
      total += tbb::parallel_reduce(
          tbb::blocked_range<int>(0, kGrid), 0L,
          [&](const tbb::blocked_range<int>& rows, long hits) {
            for (int i = rows.begin(); i < rows.end(); ++i) {
              for (int j = 0; j < kGrid; ++j) {
                const float x = ((i + 0.5f) / kGrid - 0.5f) * reach;
                const float y = ((j + 0.5f) / kGrid - 0.5f) * reach;
                Ray ray;
                ray.origin = centre + u * x + v * y - d * reach;
                ray.direction = d;
                ray.t_min = 0.0f;
                ray.t_max = 2.0f * reach;
                RTCIntersectContext context;
                rtcInitIntersectContext(&context);
                RTCRay r = embree_ray(ray);
                rtcOccluded1(scene, &context, &r);
                hits += r.tfar < 0.0f ? 1 : 0;
              }
            }
            return hits;
          },
          [](long a, long b) { return a + b; });
    }
  }
  return total;
}

}  // namespace

double calibrate_leaf_area(const EmbreeDevice& device, RTCSceneTy* prototype,
                           const generator::TreeGeometry& geometry,
                           std::vector<scene::InstanceLod>& instances) {
  const std::uint32_t leaves = geometry.lod_items[scene::kLodLeaves];
  if (instances.empty() || leaves < 4) return 1.0;
  // One instance of the prototype as geometry 0 of a scene of its own.
  SceneHandle top = new_scene(device);
  RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(g, prototype);
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, identity);
  attach(top.get(), g);
  rtcCommitScene(top.get());
  device.check("building the level-of-detail calibration");
  const scene::InstanceLod borrowed = instances[0];
  scene::InstanceLod& trial = instances[0];
  trial = scene::InstanceLod{};
  trial.active = true;
  const long full = cover(top.get(), geometry.bounds_min, geometry.bounds_max);
  // Far away: one leaf in four, and of the limbs only the trunk (lod_numbers beyond r2 = 2000s).
  trial.keep[scene::kLodLeaves] =
      scene::lod_keep(1.0, scene::kLodMassSize[scene::kLodLeaves], leaves);
  for (const scene::LodLevel level : {scene::kLodMainBranches, scene::kLodBranches})
    trial.keep[level] = scene::lod_keep(0.0, scene::kLodMassSize[level], 1);
  const std::uint32_t kept = scene::lod_kept(trial.keep[scene::kLodLeaves], leaves);
  double lo = 1.0, hi = scene::kLodMaxLeafScale;
  trial.leaf_scale = static_cast<float>(hi);
  if (cover(top.get(), geometry.bounds_min, geometry.bounds_max) <= full) {
    lo = hi;  // even the largest leaves stop no more than the full crown
  } else {
    for (int step = 0; step < 10; ++step) {
      const double mid = 0.5 * (lo + hi);
      trial.leaf_scale = static_cast<float>(mid);
      (cover(top.get(), geometry.bounds_min, geometry.bounds_max) > full ? hi : lo) = mid;
    }
  }
  instances[0] = borrowed;
  const double scale = 0.5 * (lo + hi);
  return scale * scale * kept / leaves;
}

float calibrated_leaf_scale(double alpha, std::uint32_t kept, std::uint32_t total) {
  if (total == 0 || kept >= total || kept == 0) return 1.0f;
  const double f = static_cast<double>(kept) / total;
  const double a = 1.0 - (1.0 - alpha) * (1.0 - f) / 0.75;
  return static_cast<float>(std::clamp(std::sqrt(a / f), 1.0, double{scene::kLodMaxLeafScale}));
}

}  // namespace arbor::tracer
