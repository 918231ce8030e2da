// The fitted single-precision trigonometry against the library's double precision, on dense grids.
#include "common/fast_trig.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

namespace arbor {
namespace {

// Power: the arc tangent's leading coefficient rounded to 0.99999 (an error of 1e-5 rad, 0.0006°)
// fails this test, as does the sine's cubic term off by one in its sixth digit.
TEST(FastTrig, ArcTangentWithinAThirdOfAMicroradianInEveryQuadrant) {
  double worst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double angle = -M_PI + 2.0 * M_PI * (i + 0.5) / 20000.0;
    for (const double radius : {1e-6, 0.3, 1.0, 7.0, 3e4}) {
      const float x = static_cast<float>(radius * std::cos(angle));
      const float y = static_cast<float>(radius * std::sin(angle));
      const double exact = std::atan2(static_cast<double>(y), static_cast<double>(x));
      worst = std::max(worst, std::fabs(fast_atan2(y, x) - exact));
    }
  }
  EXPECT_LT(worst, 3.5e-7);
  EXPECT_EQ(fast_atan2(0.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(fast_atan2(0.0f, -1.0f), static_cast<float>(M_PI));
  EXPECT_FLOAT_EQ(fast_atan2(-1.0f, 0.0f), static_cast<float>(-M_PI / 2.0));
}

TEST(FastTrig, SineAndCosineWithinTwoTenthsOfAMicroUpToAThousandRadians) {
  double worst_small = 0.0, worst_large = 0.0;
  const auto check = [&](float a) {
    float s = 0.0f, c = 0.0f;
    fast_sincos(a, s, c);
    const double err =
        std::max(std::fabs(s - std::sin(double(a))), std::fabs(c - std::cos(double(a))));
    double& worst = std::fabs(a) <= 4.0f ? worst_small : worst_large;
    worst = std::max(worst, err);
  };
  for (int i = 0; i <= 200000; ++i) check(static_cast<float>(-1000.0 + 2000.0 * i / 200000.0));
  for (int i = 0; i <= 100000; ++i) check(static_cast<float>(-4.0 + 8.0 * i / 100000.0));
  EXPECT_LT(worst_small, 2e-7) << worst_small;
  EXPECT_LT(worst_large, 2e-7) << worst_large;
}

}  // namespace
}  // namespace arbor
