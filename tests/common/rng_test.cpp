// Tests of the keyed random streams.
#include "common/rng.h"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

namespace arbor {

TEST(Rng, SameKeyGivesSameSequence) {
  Rng a(42), b(42);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next_u64(), b.next_u64());
}

TEST(Rng, DerivedKeysAreDistinctAndOrderSensitive) {
  std::set<std::uint64_t> keys;
  for (std::uint64_t label = 0; label < 1000; ++label) keys.insert(derive_key(7, label));
  EXPECT_EQ(keys.size(), 1000u);
  EXPECT_NE(derive_key(derive_key(1, 2), 3), derive_key(derive_key(1, 3), 2));
}

TEST(Rng, UniformHasTheMomentsOfU01) {
  Rng r(3);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
  }
  // Mean 1/2 (sd of the mean 0.29/sqrt(n) ≈ 6.5e-4) and second moment 1/3.
  EXPECT_NEAR(sum / n, 0.5, 4e-3);
  EXPECT_NEAR(sum2 / n, 1.0 / 3.0, 4e-3);
}

TEST(Rng, VaryStaysWithinTheVariation) {
  Rng r(9);
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < 10000; ++i) {
    const double v = r.vary(10.0, 2.0);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_GE(lo, 8.0);
  EXPECT_LT(hi, 12.0);
  EXPECT_LT(lo, 8.05);  // the whole range is reached
  EXPECT_GT(hi, 11.95);
}

}  // namespace arbor
