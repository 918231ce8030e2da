// Rendering in passes: the variance estimate across passes is honest (two seeds differ by what it
// says), the within-one-pass estimate it replaced is not, passes are independent scrambles, and
// adaptive sampling stops converged pixels, deterministically.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "tracer/embree/world.h"
#include "tracer/film.h"
#include "tracer/lights/sky.h"
#include "tracer/render.h"
#include "tracer/sampler.h"
#include "tracer/test_world.h"

namespace arbor::trace {

namespace {

const ColorTransform kIdentity = [](float*) {};

// An aspen against the sky and the ground, 48x36.
SceneDesc tree_scene(int spp, int pass_spp, std::uint64_t seed) {
  SceneDesc s;
  s.render.width = 48;
  s.render.height = 36;
  s.render.spp = spp;
  s.render.pass_spp = pass_spp;
  s.render.seed = seed;
  s.render.max_depth = 6;
  s.render.threads = 2;
  s.camera.position = {9.0, -12.0, 4.0};
  s.camera.look_at = {0.0, 0.0, 6.0};
  TreeDesc t;
  t.species = std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml";
  t.seed = 3;
  s.trees.push_back(t);
  return s;
}

Image render(const SceneDesc& s) {
  const EmbreeDevice device("threads=" + std::to_string(s.render.threads));
  const TestWorld test_world(s, device);
  const Sky sky(s.sky, s.sun, xyz_to_scene_linear(), 128);
  RenderStats stats;
  return render_image(s, test_world.world, sky, kIdentity, stats);
}

// Σ (a - b)² and Σ (var_a + var_b) over every pixel and channel of renders with seeds k and k + 1,
// for k = 1, 3, 5, 7: their ratio is 1 when the stated variance of the pixel means is what
// independent renders show. (One pair alone spreads by about ±15 %: a few bright pixels carry
// much of both sums.)
double stated_to_seen(int spp, int pass_spp) {
  double seen = 0, stated = 0;
  for (std::uint64_t k = 1; k < 9; k += 2) {
    const Image a = render(tree_scene(spp, pass_spp, k)), b = render(tree_scene(spp, pass_spp, k + 1));
    for (std::size_t p = 0; p < a.beauty.size(); ++p) {
      for (int c = 0; c < 3; ++c) {
        const double d = double(a.beauty[p][c]) - b.beauty[p][c];
        seen += d * d;
        stated += double(a.variance[p][c]) + b.variance[p][c];
      }
    }
  }
  return seen / stated;
}

}  // namespace

TEST(Passes, VarianceAcrossPassesIsWhatTwoSeedsShow) {
  // 64 spp in 8 passes of 8: within ±25 % of the empirical variance of the difference is what
  // issue 12 asks; we hold it to ±15 % (measured 0.995; a variance 30 % too large gives 0.765).
  const double honest = stated_to_seen(64, 8);
  EXPECT_GT(honest, 0.85);
  EXPECT_LT(honest, 1.15);
  // The same samples in one pass: the sample variance / n of scrambled Sobol' points overstates
  // the variance of the mean (issue 12 measured 0.31), and the test above would catch it.
  const double one_pass = stated_to_seen(64, 64);
  EXPECT_LT(one_pass, 0.6);
  std::printf("two seeds differ by %.3f of the stated variance (8 passes), %.3f (one pass)\n", honest, one_pass);
}

TEST(Passes, EachPassIsItsOwnScrambleAndPassZeroIsTheSinglePassOne) {
  const PixelSampler zero(77, 5), also_zero(77, 5, 0), one(77, 5, 1), two(77, 5, 2);
  for (std::uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(zero.get2d(i, 3), also_zero.get2d(i, 3));
    EXPECT_NE(zero.get2d(i, 3), one.get2d(i, 3));
    EXPECT_NE(one.get2d(i, 3), two.get2d(i, 3));
  }
  // A render of one pass is the render of the same samples before passes existed: its pixels
  // are pass 0's, and its variance the within-pass estimate.
  const Image single = render(tree_scene(8, 16, 4));
  const Image first = render(tree_scene(16, 8, 4));
  EXPECT_NE(std::memcmp(single.beauty.data(), first.beauty.data(), single.beauty.size() * sizeof(glm::vec3)), 0);
}

TEST(Passes, AdaptiveSamplingStopsConvergedPixelsDeterministically) {
  SceneDesc s = tree_scene(256, 16, 3);
  s.render.noise_threshold = 0.05;
  s.render.min_spp = 32;
  const Image a = render(s);
  s.render.threads = 1;
  const Image b = render(s);
  ASSERT_EQ(a.beauty.size(), b.beauty.size());
  EXPECT_EQ(std::memcmp(a.beauty.data(), b.beauty.data(), a.beauty.size() * sizeof(glm::vec3)), 0);
  EXPECT_EQ(std::memcmp(a.samples.data(), b.samples.data(), a.samples.size() * sizeof(float)), 0);
  const auto [lo, hi] = std::minmax_element(a.samples.begin(), a.samples.end());
  EXPECT_EQ(*lo, 32.0f);   // the sky converges at once: min_spp
  EXPECT_EQ(*hi, 256.0f);  // some leaves never reach 5 %
  double total = 0;
  int stopped = 0;
  for (std::size_t p = 0; p < a.samples.size(); ++p) {
    total += a.samples[p];
    if (a.samples[p] < 256.0f) {
      ++stopped;
      // A pixel stopped only once its relative standard error was at the threshold.
      for (int c = 0; c < 3; ++c) {
        const double se = std::sqrt(double(a.variance[p][c]));
        EXPECT_LE(se / std::max(std::fabs(double(a.beauty[p][c])), 0.01), 0.05 * 1.0001) << "pixel " << p;
      }
    }
  }
  EXPECT_GT(stopped, static_cast<int>(a.samples.size() / 4));
  EXPECT_LT(total / a.samples.size(), 200.0);
  // Without a threshold every pixel takes every sample.
  s.render.noise_threshold = 0;
  const Image uniform = render(s);
  EXPECT_TRUE(std::all_of(uniform.samples.begin(), uniform.samples.end(), [](float n) { return n == 256.0f; }));
}

}  // namespace arbor::trace
