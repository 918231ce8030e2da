// Tests of the TREE-MAKER weight fit: it recovers weights that made an image exactly, keeps
// weights non-negative with the optimality (KKT) conditions of the constrained problem, skips
// pixels without a tree, and refuses mismatched inputs.
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "imaging/treemaker_fit.h"

namespace arbor::imaging {
namespace {

constexpr int kW = 12, kH = 9;

// Random contributions in [0, 0.3) per factor and channel; a quarter of the pixels show no tree.
TreemakerAovs random_aovs(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 0.3f);
  TreemakerAovs t;
  t.path = "tm.exr";
  t.width = kW;
  t.height = kH;
  const std::size_t n = kW * kH;
  t.coverage.resize(n);
  t.contribution.assign(n * 15, 0.0f);
  t.rest.resize(3 * n);
  t.beauty.assign(3 * n, 0.0f);
  for (std::size_t p = 0; p < n; ++p) {
    t.coverage[p] = p % 4 == 0 ? 0.0f : 1.0f;
    for (int c = 0; c < 3; ++c) {
      t.rest[3 * p + c] = p % 4 == 0 ? 0.4f : 0.0f;
      if (t.coverage[p] > 0.0f) {
        for (int i = 0; i < 5; ++i) t.contribution[(p * 5 + i) * 3 + c] = u(rng);
      }
    }
  }
  return t;
}

CompareImage made_with(const TreemakerAovs& t, const double w[5]) {
  CompareImage im;
  im.path = "exact.exr";
  im.width = t.width;
  im.height = t.height;
  im.rgb.resize(t.rest.size());
  for (std::size_t p = 0; p < t.coverage.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      double v = t.rest[3 * p + c];
      for (int i = 0; i < 5; ++i) v += w[i] * t.contribution[(p * 5 + i) * 3 + c];
      im.rgb[3 * p + c] = static_cast<float>(v);
    }
  }
  return im;
}

}  // namespace

TEST(TreemakerFit, RecoversTheWeightsThatMadeTheImage) {
  const TreemakerAovs t = random_aovs(1);
  const double w[5] = {0.1, 0.4, 0.4, 0.3, 0.2};  // the dogwood's
  const TreemakerFit fit = fit_treemaker(made_with(t, w), t);
  EXPECT_EQ(fit.pixels, kW * kH - (kW * kH + 3) / 4);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(fit.weights[static_cast<size_t>(i)], w[i], 1e-5) << i;
  EXPECT_LT(fit.rmse, 1e-6);
  // The treemaker image's own beauty (all zero here) is scored too.
  EXPECT_GT(fit.render_rmse, 0.1);
  // Pixels without a tree keep their rest in the fitted image.
  EXPECT_FLOAT_EQ(fit.fitted[0], 0.4f);
}

TEST(TreemakerFit, WeightsStayNonNegativeAtTheConstrainedOptimum) {
  const TreemakerAovs t = random_aovs(2);
  const double w[5] = {0.3, -0.5, 0.2, 0.0, 0.6};  // no template can have lambert < 0
  const CompareImage exact = made_with(t, w);
  const TreemakerFit fit = fit_treemaker(exact, t);
  for (double v : fit.weights) EXPECT_GE(v, 0.0);
  EXPECT_GT(fit.rmse, 1e-3);  // the negative weight cannot be matched
  // KKT: the gradient of the squared error, Xᵀ(Xw − y), is 0 on positive weights and ≥ 0 on
  // zero ones (moving a zero weight up cannot help).
  for (int i = 0; i < 5; ++i) {
    double grad = 0.0, scale = 0.0;
    for (std::size_t p = 0; p < t.coverage.size(); ++p) {
      if (t.coverage[p] <= 0.0f) continue;
      for (int c = 0; c < 3; ++c) {
        const double x = t.contribution[(p * 5 + i) * 3 + c];
        grad += x * (double(fit.fitted[3 * p + c]) - exact.rgb[3 * p + c]);
        scale += x * x;
      }
    }
    if (fit.weights[static_cast<size_t>(i)] > 1e-9) {
      EXPECT_NEAR(grad, 0.0, 1e-5 * scale) << i;
    } else {
      EXPECT_GE(grad, -1e-5 * scale) << i;
    }
  }
  EXPECT_EQ(fit.weights[1], 0.0);
}

TEST(TreemakerFit, AFactorThatIsZeroEverywhereIsNotDetermined) {
  TreemakerAovs t = random_aovs(3);
  for (std::size_t p = 0; p < t.coverage.size(); ++p) {
    for (int c = 0; c < 3; ++c) t.contribution[(p * 5 + 1) * 3 + c] = 0.0f;  // no lambert
  }
  const double w[5] = {0.2, 0.0, 0.3, 0.1, 0.5};
  const TreemakerFit fit = fit_treemaker(made_with(t, w), t);
  EXPECT_FALSE(fit.determined[1]);
  EXPECT_TRUE(fit.determined[0]);
  EXPECT_EQ(fit.weights[1], 0.0);
  EXPECT_NEAR(fit.weights[4], 0.5, 1e-5);
}

TEST(TreemakerFit, RefusesMismatchedInputs) {
  const TreemakerAovs t = random_aovs(4);
  const double w[5] = {0.1, 0.1, 0.1, 0.1, 0.1};
  CompareImage exact = made_with(t, w);
  exact.width = kW - 1;
  testing::expect_input_error([&] { fit_treemaker(exact, t); }, "tm.exr", 0, 0, "same view");
  exact = made_with(t, w);
  exact.colorspace = "ACEScg";
  TreemakerAovs other = t;
  other.colorspace = "Linear Rec.709 (sRGB)";
  testing::expect_input_error([&] { fit_treemaker(exact, other); }, "tm.exr", 0, 0,
                              "same colour space");
  TreemakerAovs empty = t;
  std::fill(empty.coverage.begin(), empty.coverage.end(), 0.0f);
  testing::expect_input_error([&] { fit_treemaker(made_with(empty, w), empty); }, "tm.exr", 0, 0,
                              "shows no tree");
}

}  // namespace arbor::imaging
