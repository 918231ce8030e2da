// The auto-exposure meter: a small preview of the whole frame, its log-average luminance with
// centre weights, set to middle grey.
#include "tracer/exposure.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/math.h"
#include "tracer/camera.h"
#include "tracer/embree/world.h"
#include "tracer/integrators/path.h"
#include "tracer/lights/sky.h"
#include "tracer/sampler.h"

namespace arbor::tracer {

namespace {

constexpr int kPreviewWidth = 64, kPreviewSpp = 16;
constexpr std::uint64_t kMeterSeed = 0x6d65746572ull;  // "meter": the preview's own
constexpr double kMiddleGrey = 0.18, kCentreSigma = 0.5;

}  // namespace

double metered_exposure(const scene::RenderInput& input, const World& world, const Sky& sky) {
  const int w = std::min(kPreviewWidth, input.render.width);
  const int h =
      std::max(1, static_cast<int>(std::lround(static_cast<double>(w) * input.render.height /
                                               input.render.width)));
  const Camera camera(input.camera, w, h);
  // The scene's light, not one output's: the path tracer (whatever the render's integrator),
  // without regularisation, every pixel counted (a transparent sky is the same exposure).
  const PathIntegrator path(world, sky, input.render.max_depth, false);
  std::vector<double> y(static_cast<std::size_t>(w) * h, 0.0);
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j < rows.end(); ++j) {
      for (int i = 0; i < w; ++i) {
        const auto key = static_cast<std::uint32_t>(j * w + i);
        const PixelSampler sampler(key, kMeterSeed, 0);
        double sum = 0.0;
        int seen = 0;
        for (std::uint32_t s = 0; s < kPreviewSpp; ++s) {
          const glm::vec2 u = sampler.get2d(s, 0);
          const Ray ray = camera.generate({i + u.x, j + u.y}, sampler.get2d(s, 1));
          const PathSample p = path.trace(ray, sampler, s);
          const double l = luminance<double>(p.radiance.x, p.radiance.y, p.radiance.z);
          if (!std::isfinite(l)) continue;
          sum += l;
          ++seen;
        }
        y[static_cast<std::size_t>(j) * w + i] = seen > 0 ? sum / seen : -1.0;
      }
    }
  });
  // The centre-weighted log average, summed in pixel order (the same on any thread count).
  double num = 0.0, den = 0.0;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const double v = y[static_cast<std::size_t>(j) * w + i];
      if (v < 0.0) continue;
      const double x = 2.0 * (i + 0.5) / w - 1.0, z = 2.0 * (j + 0.5) / h - 1.0;
      const double weight = std::exp(-(x * x + z * z) / (2.0 * kCentreSigma * kCentreSigma));
      num += weight * std::log(v + 1e-6);
      den += weight;
    }
  }
  if (den <= 0.0) return 0.0;  // nothing seen: no reason to change the exposure
  return std::clamp(std::log2(kMiddleGrey / std::exp(num / den)), -64.0, 64.0);
}

scene::RenderInput with_exposure(const scene::RenderInput& input, const World& world,
                                 const Sky& sky) {
  if (!input.camera.auto_exposure) return input;
  scene::RenderInput metered = input;
  metered.camera.exposure = metered_exposure(input, world, sky);
  return metered;
}

}  // namespace arbor::tracer
