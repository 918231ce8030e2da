// Rendering in passes: with independent passes the variance estimate across passes is honest (two
// seeds differ by what it says) and the within-one-pass estimate is not; passes of one sequence are
// the single pass's samples, with less variance than independent passes and an estimate that bounds
// it from above; adaptive sampling stops converged pixels, deterministically.
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

namespace arbor::tracer {

namespace {

const imaging::ColorTransform kIdentity = [](float*) {};

// An aspen against the sky and the ground, 48x36.
spec::SceneDesc tree_scene(int spp, int pass_spp, std::uint64_t seed, bool independent = false) {
  spec::SceneDesc s;
  s.render.independent_passes = independent;
  s.render.width = 48;
  s.render.height = 36;
  s.render.spp = spp;
  s.render.pass_spp = pass_spp;
  s.render.seed = seed;
  s.render.max_depth = 6;
  s.render.threads = 2;
  s.camera.position = {9.0, -12.0, 4.0};
  s.camera.look_at = {0.0, 0.0, 6.0};
  spec::TreeDesc t;
  t.species = std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml";
  t.seed = 3;
  // Matte leaves: the tests below are of the passes' variance bookkeeping, whatever the BSDF, and
  // the cuticle's sun glints make the pixel values heavy-tailed, so that the ratio of sums over
  // four seed pairs spreads by ±25 % (0.78 to 0.96 measured; 20 pairs give 0.96).
  t.leaf.cuticle_ior = 1.0;
  s.trees.push_back(t);
  return s;
}

imaging::Image render(const spec::SceneDesc& s) {
  const EmbreeDevice device("threads=" + std::to_string(s.render.threads));
  const TestWorld test_world(s, device);
  const Sky sky(s.sky, s.sun, xyz_to_scene_linear(), 128);
  imaging::RenderStats stats;
  return render_image(scene::render_input(s), test_world.world, sky, kIdentity, stats);
}

// Σ (a - b)² and Σ (var_a + var_b) over every pixel and channel of renders with seeds k and k + 1,
// for k = 1, 3, 5, 7: their ratio is 1 when the stated variance of the pixel means is what
// independent renders show. (One pair alone spreads by about ±15 %: a few bright pixels carry
// much of both sums.)
struct Spread {
  double seen = 0, stated = 0;
  double ratio() const { return seen / stated; }
};
Spread stated_to_seen(int spp, int pass_spp, bool independent) {
  Spread r;
  double& seen = r.seen;
  double& stated = r.stated;
  for (std::uint64_t k = 1; k < 9; k += 2) {
    const imaging::Image a = render(tree_scene(spp, pass_spp, k, independent));
    const imaging::Image b = render(tree_scene(spp, pass_spp, k + 1, independent));
    for (std::size_t p = 0; p < a.beauty.size(); ++p) {
      for (int c = 0; c < 3; ++c) {
        const double d = double(a.beauty[p][c]) - b.beauty[p][c];
        seen += d * d;
        stated += double(a.variance[p][c]) + b.variance[p][c];
      }
    }
  }
  return r;
}

}  // namespace

TEST(Passes, IndependentPassesStateTheVarianceTwoSeedsShow) {
  // 64 spp in 8 independent passes of 8: within ±25 % of the empirical variance of the difference
  // is what issue 12 asks; we hold it to ±15 % (measured 0.995; a variance 30 % too large gives
  // 0.765).
  const double honest = stated_to_seen(64, 8, true).ratio();
  EXPECT_GT(honest, 0.85);
  EXPECT_LT(honest, 1.15);
  // The same samples in one pass: the sample variance / n of scrambled Sobol' points overstates
  // the variance of the mean (issue 12 measured 0.31), and the test above would catch it.
  const double one_pass = stated_to_seen(64, 64, true).ratio();
  EXPECT_LT(one_pass, 0.6);
  std::printf("two seeds differ by %.3f of the stated variance (8 passes), %.3f (one pass)\n",
              honest, one_pass);
}

TEST(Passes, PassesOfOneSequenceHaveLessVarianceWhichTheyOverstate) {
  // The default: 8 passes taking consecutive points of one sequence are stratified together, so
  // two seeds differ by less than with independent passes (the reason for the default), and the
  // spread of the pass means overstates the variance of their mean (an upper bound).
  const Spread sequence = stated_to_seen(64, 8, false), independent = stated_to_seen(64, 8, true);
  std::printf(
      "two seeds differ by %.3g (one sequence), %.3g (independent passes); stated %.3g, %.3g\n",
      sequence.seen, independent.seen, sequence.stated, independent.stated);
  EXPECT_LT(sequence.seen, 0.85 * independent.seen);
  EXPECT_LT(sequence.ratio(), 0.95);
  EXPECT_GT(sequence.ratio(), 0.3);
}

TEST(Passes, PassesOfOneSequenceAreTheSinglePassSamples) {
  // Independent passes: each its own scramble; pass 0 keeps the single-pass key.
  const PixelSampler zero(77, 5), also_zero(77, 5, 0), one(77, 5, 1), two(77, 5, 2);
  for (std::uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(zero.get2d(i, 3), also_zero.get2d(i, 3));
    EXPECT_NE(zero.get2d(i, 3), one.get2d(i, 3));
    EXPECT_NE(one.get2d(i, 3), two.get2d(i, 3));
  }
  const PassPlan sequence{16, 4, false}, independent{16, 4, true};
  EXPECT_EQ(sequence.scramble(3), 0u);
  EXPECT_EQ(sequence.first_sample(3), 12u);
  EXPECT_EQ(independent.scramble(3), 3u);
  EXPECT_EQ(independent.first_sample(3), 0u);
  // 16 samples in one pass and in four passes of one sequence are the same samples: the means
  // agree to float rounding (they are summed in another order); independent passes do not.
  const imaging::Image single = render(tree_scene(16, 16, 4));
  const imaging::Image split = render(tree_scene(16, 4, 4));
  const imaging::Image apart = render(tree_scene(16, 4, 4, true));
  double worst_split = 0, worst_apart = 0;
  for (std::size_t p = 0; p < single.beauty.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      const double scale = std::max(1.0, std::fabs(double(single.beauty[p][c])));
      worst_split = std::max(worst_split,
                             std::fabs(double(split.beauty[p][c]) - single.beauty[p][c]) / scale);
      worst_apart = std::max(worst_apart,
                             std::fabs(double(apart.beauty[p][c]) - single.beauty[p][c]) / scale);
    }
  }
  EXPECT_LT(worst_split, 1e-5);
  EXPECT_GT(worst_apart, 1e-2);
}

TEST(Passes, AdaptiveSamplingStopsConvergedPixelsDeterministically) {
  spec::SceneDesc s = tree_scene(256, 16, 3);
  s.render.noise_threshold = 0.05;
  s.render.min_spp = 32;
  const imaging::Image a = render(s);
  s.render.threads = 1;
  const imaging::Image b = render(s);
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
        EXPECT_LE(se / std::max(std::fabs(double(a.beauty[p][c])), 0.01), 0.05 * 1.0001)
            << "pixel " << p;
      }
    }
  }
  EXPECT_GT(stopped, static_cast<int>(a.samples.size() / 4));
  EXPECT_LT(total / a.samples.size(), 200.0);
  // Without a threshold every pixel takes every sample.
  s.render.noise_threshold = 0;
  const imaging::Image uniform = render(s);
  EXPECT_TRUE(std::all_of(uniform.samples.begin(), uniform.samples.end(),
                          [](float n) { return n == 256.0f; }));
}

}  // namespace arbor::tracer

namespace arbor::tracer {

TEST(Sampler, TheSecondSobolDimensionsTablesAreItsBitLoop) {
  std::uint32_t x = 12345u;
  for (int k = 0; k < 200000; ++k) {
    x = x * 1664525u + 1013904223u;
    ASSERT_TRUE(PixelSampler::sobol_tables_agree(x)) << x;
  }
  for (std::uint32_t i : {0u, 1u, 255u, 256u, 65535u, 0x80000000u, 0xffffffffu}) {
    EXPECT_TRUE(PixelSampler::sobol_tables_agree(i)) << i;
  }
}

}  // namespace arbor::tracer
