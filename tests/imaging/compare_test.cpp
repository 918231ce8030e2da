// Tests of image comparison: the metrics on images with known differences, the z-test's
// behaviour on synthetic noise of known variance (it passes pure noise, fails a bias), the
// normal quantile, and the refusal of bad images.
#include <cmath>
#include <random>
#include <string>

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "expect_input_error.h"
#include "imaging/compare.h"
#include "imaging/statistics.h"

namespace arbor::imaging {
namespace {

CompareImage flat(int w, int h, float value, float variance = -1.0f) {
  CompareImage im;
  im.path = "flat";
  im.width = w;
  im.height = h;
  im.rgb.assign(static_cast<std::size_t>(w) * h * 3, value);
  if (variance >= 0) im.variance.assign(im.rgb.size(), variance);
  return im;
}

TEST(Compare, NormalQuantileMatchesTables) {
  EXPECT_NEAR(normal_two_sided_critical(0.05), 1.959964, 1e-5);
  EXPECT_NEAR(normal_two_sided_critical(0.01), 2.575829, 1e-5);
  EXPECT_NEAR(normal_two_sided_critical(1e-6), 4.891638, 1e-5);
}

TEST(Compare, MetricsOfAConstantOffset) {
  const CompareImage b = flat(8, 4, 0.5f), a = flat(8, 4, 0.6f);
  const CompareMetrics m = compare_images(a, b);
  EXPECT_NEAR(m.rmse, 0.1, 1e-6);
  EXPECT_NEAR(m.mean_abs, 0.1, 1e-6);
  EXPECT_NEAR(m.max_abs, 0.1, 1e-6);
  EXPECT_NEAR(m.psnr, 20.0, 1e-4);  // 20 log10(1 / 0.1)
  EXPECT_NEAR(m.rel_mse, 0.01 / (0.25 + 0.01), 1e-6);
}

TEST(Compare, MetricsFindTheWorstPixel) {
  const CompareImage b = flat(8, 4, 0.5f);
  CompareImage a = b;
  a.rgb[3 * (2 * 8 + 5) + 1] = 0.9f;  // pixel (5, 2), green
  const CompareMetrics m = compare_images(a, b);
  EXPECT_NEAR(m.max_abs, 0.4, 1e-6);
  EXPECT_EQ(m.max_x, 5);
  EXPECT_EQ(m.max_y, 2);
  EXPECT_NEAR(m.mean_abs, 0.4 / (8 * 4 * 3), 1e-7);
  const CompareMetrics same = compare_images(b, b);
  EXPECT_EQ(same.rmse, 0.0);
  EXPECT_TRUE(std::isinf(same.psnr));
}

TEST(Compare, DifferentSizesAreRefused) {
  EXPECT_THROW(compare_images(flat(8, 4, 0.5f), flat(4, 8, 0.5f)), InputError);
}

// A is the reference mean plus Gaussian noise of exactly the variance both images state.
CompareImage noisy(const CompareImage& mean, float variance, float bias, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, std::sqrt(2.0f * variance));
  CompareImage a = mean;
  a.path = "noisy";
  for (float& v : a.rgb) v += bias + noise(rng);
  a.variance.assign(a.rgb.size(), variance);
  return a;
}

TEST(Compare, ZTestPassesNoiseOfTheStatedVariance) {
  const CompareImage b = flat(64, 64, 1.0f, 1e-4f);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const ZTest t = reference_z_test(noisy(b, 1e-4f, 0.0f, seed), b);
    EXPECT_TRUE(t.passed) << "seed " << seed << ": " << t.pass_fraction;
    EXPECT_GT(t.pass_fraction, 0.999);
    EXPECT_EQ(t.pixels, 64 * 64);
  }
}

TEST(Compare, ZTestUsesTheSidakCorrection) {
  const CompareImage b = flat(64, 64, 1.0f, 1e-4f);
  const ZTest t = reference_z_test(b, b);
  const double n = 3.0 * 64 * 64;
  EXPECT_NEAR(t.alpha_channel, 1.0 - std::pow(1.0 - 0.01, 1.0 / n), 1e-12);
  EXPECT_NEAR(std::erfc(t.z_critical / std::sqrt(2.0)), t.alpha_channel, 1e-9);
  EXPECT_EQ(t.failed, 0);
}

TEST(Compare, ZTestFailsABiasAndNoiseUnderstated) {
  const CompareImage b = flat(64, 64, 1.0f, 1e-4f);
  // A bias of 10 standard deviations of the difference fails nearly every pixel.
  const ZTest biased = reference_z_test(noisy(b, 1e-4f, 10.0f * std::sqrt(2e-4f), 3), b);
  EXPECT_FALSE(biased.passed);
  EXPECT_LT(biased.pass_fraction, 0.01);
  // Noise 4x the stated standard deviation: a few percent of pixels fail, enough to fail.
  CompareImage loud = noisy(b, 16e-4f, 0.0f, 4);
  loud.variance.assign(loud.rgb.size(), 1e-4f);
  EXPECT_FALSE(reference_z_test(loud, b).passed);
}

TEST(Compare, ZeroVariancePixelsTolerateFloatRoundingOnly) {
  // A constant sky seen directly has no variance: another renderer's 0.59999996 for 0.6 (one
  // float ulp) passes, and so does 0 against 0; an error of 1e-5 (about 170 ulps) fails.
  const CompareImage b = flat(8, 8, 0.6f, 0.0f);
  EXPECT_TRUE(reference_z_test(flat(8, 8, 0.59999996f, 0.0f), b).passed);
  EXPECT_TRUE(reference_z_test(flat(8, 8, 0.0f, 0.0f), flat(8, 8, 0.0f, 0.0f)).passed);
  EXPECT_FALSE(reference_z_test(flat(8, 8, 0.6f * (1.0f + 1e-5f), 0.0f), b).passed);
}

// Monte Carlo pixels are heavy-tailed: a rare bright path that B's few passes missed leaves B's
// pixel variance near 0 there, while A, which caught it, says so in its own variance. Such pixels
// pass (each image's own estimate counts); a local error A's variance does not explain still fails.
TEST(Compare, ZTestTakesEachImagesOwnVarianceAndStillFindsALocalError) {
  const CompareImage b = flat(64, 64, 1.0f, 1e-4f);
  CompareImage a = noisy(b, 1e-4f, 0.0f, 7);
  CompareImage spiky = b;
  for (int k = 0; k < 60; ++k) {  // 1.5 % of the pixels: three times what the test allows
    const std::size_t p = static_cast<std::size_t>(k) * 67 % (64 * 64);
    spiky.variance[3 * p] = 1e-9f;  // B never saw the path: its estimate is ~0
    a.rgb[3 * p] += 0.2f;           // A caught it in one of its passes: 0.2 off, and it says so
    a.variance[3 * p] = 0.2f * 0.2f;
  }
  EXPECT_TRUE(reference_z_test(a, spiky).pixels_passed);
  // 25 pixels 20 % too bright, with the variance of ordinary noise: found.
  CompareImage wrong = noisy(b, 1e-4f, 0.0f, 8);
  for (int y = 30; y < 35; ++y) {
    for (int x = 30; x < 35; ++x) wrong.rgb[3 * (static_cast<std::size_t>(y) * 64 + x) + 1] += 0.2f;
  }
  const ZTest t = reference_z_test(wrong, b);
  EXPECT_EQ(t.failed, 25);
  EXPECT_FALSE(t.passed);
}

TEST(Compare, ZTestNeedsTheReferenceVariance) {
  try {
    reference_z_test(flat(4, 4, 1.0f), flat(4, 4, 1.0f));
    ADD_FAILURE() << "accepted a reference without variance";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("variance"), std::string::npos);
  }
}

TEST(Compare, ReadingRefusesNonFinitePixels) {
  const std::string path = ::testing::TempDir() + "compare_nan.exr";
  OIIO::ImageBuf buf(OIIO::ImageSpec(4, 3, 3, OIIO::TypeDesc::FLOAT));
  const float nan_px[3] = {0.0f, std::nanf(""), 0.0f};
  buf.setpixel(2, 1, nan_px);
  ASSERT_TRUE(buf.write(path));
  arbor::testing::expect_input_error([&] { read_compare_image(path); }, path, 0, 0,
                                     "pixel (2, 1) is not a finite number");
  arbor::testing::expect_input_error([&] { read_compare_image(path + ".missing"); },
                                     path + ".missing", 0, 0, "image does not exist");
}

TEST(Compare, ReadingFindsVarianceChannels) {
  const std::string path = ::testing::TempDir() + "compare_var.exr";
  OIIO::ImageSpec spec(2, 2, 6, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B", "variance.R", "variance.G", "variance.B"};
  OIIO::ImageBuf buf(spec);
  const float px[6] = {0.25f, 0.5f, 0.75f, 1e-3f, 2e-3f, 3e-3f};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) buf.setpixel(x, y, px);
  ASSERT_TRUE(buf.write(path));
  const CompareImage im = read_compare_image(path);
  ASSERT_EQ(im.variance.size(), 12u);
  EXPECT_FLOAT_EQ(im.rgb[1], 0.5f);
  EXPECT_FLOAT_EQ(im.variance[2], 3e-3f);
  EXPECT_FALSE(im.half_beauty);
}

}  // namespace
}  // namespace arbor::imaging

namespace arbor::imaging {
namespace {

TEST(Statistics, StudentTAndChiSquareMatchTables) {
  EXPECT_NEAR(student_t_two_sided_critical(0.05, 10), 2.228139, 1e-5);
  EXPECT_NEAR(student_t_two_sided_critical(0.01, 3), 5.840909, 1e-5);
  EXPECT_NEAR(student_t_two_sided_critical(0.05, 1), 12.706205, 1e-4);
  // Many degrees of freedom: the normal's value.
  EXPECT_NEAR(student_t_two_sided_critical(1e-6, 1e7), normal_two_sided_critical(1e-6), 1e-4);
  EXPECT_NEAR(student_t_two_sided_tail(2.228139, 10), 0.05, 1e-6);
  EXPECT_NEAR(chi_square_upper_tail(3.841459, 1), 0.05, 1e-6);
  EXPECT_NEAR(chi_square_upper_tail(18.307038, 10), 0.05, 1e-6);
  EXPECT_NEAR(chi_square_upper_tail(124.342113, 100), 0.05, 1e-6);
  // Many degrees of freedom: the mean k sits just above the median k (1 - 2/(9k))³.
  EXPECT_GT(chi_square_upper_tail(1e4, 1e4), 0.49);
  EXPECT_LT(chi_square_upper_tail(1e4, 1e4), 0.5);
  EXPECT_LT(chi_square_upper_tail(2000, 1000), 1e-40);
}

// What the pooled tests add: a 2 % shift of a quarter of the image, far below one pixel's noise
// (a tenth of its standard deviation), fails; the same image without it passes.
TEST(Compare, PooledTestsCatchATwoPercentShiftOfARegion) {
  const CompareImage b = flat(128, 128, 0.5f, 2.5e-3f / 2.0f);  // sd of a - b: 0.05, 10 %
  CompareImage a = noisy(b, 2.5e-3f / 2.0f, 0.0f, 11);
  const ZTest clean = reference_z_test(a, b);
  EXPECT_TRUE(clean.passed) << clean.mean_z[0] << " " << clean.block_p;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      for (int c = 0; c < 3; ++c) a.rgb[3 * (static_cast<std::size_t>(y) * 128 + x) + c] *= 1.02f;
    }
  }
  const ZTest shifted = reference_z_test(a, b);
  EXPECT_TRUE(shifted.pixels_passed);  // no single pixel shows it
  EXPECT_FALSE(shifted.blocks_passed) << shifted.block_p;
  EXPECT_FALSE(shifted.passed);
}

// The false-alarm rate of the whole test on noise of the stated variance: at most its alpha
// (0.01 for the pixels, 0.005 for each pooled test; measured 0.5 % over 400 images).
TEST(Compare, FalseAlarmRateOnNoiseOfTheStatedVariance) {
  const CompareImage b = flat(48, 48, 0.5f, 1e-3f);
  int alarms = 0;
  for (unsigned seed = 100; seed < 500; ++seed)
    alarms += reference_z_test(noisy(b, 1e-3f, 0.0f, seed), b).passed ? 0 : 1;
  EXPECT_LE(alarms, 12);  // 3 %: the binomial's 99.9 % bound for a rate of 1 %
}

}  // namespace
}  // namespace arbor::imaging
