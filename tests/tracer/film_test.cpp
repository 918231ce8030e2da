// The film's reconstruction (tracer/film.h): the tent filter's sampling.
#include "tracer/film.h"

#include <cmath>

#include <gtest/gtest.h>

namespace arbor::tracer {
namespace {

// sample_tent maps stratified u onto the tent 1 - |x| on (-1, 1): every one of 8 bins holds the
// tent's mass over it, ∫ (1 - |x|) dx (1/32, 3/32, 5/32, 7/32 and mirrored), to 1/n.
TEST(Film, TentFilterSamplesTheTent) {
  constexpr int kBins = 8;
  int bins[kBins] = {};
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const float x = sample_tent((i + 0.5f) / n);
    ASSERT_GT(x, -1.0f);
    ASSERT_LT(x, 1.0f);
    ++bins[static_cast<int>((x + 1.0f) * kBins / 2.0f)];
  }
  auto cdf = [](double x) {
    return x < 0.0 ? 0.5 * (1.0 + x) * (1.0 + x) : 1.0 - 0.5 * (1.0 - x) * (1.0 - x);
  };
  for (int b = 0; b < kBins; ++b) {
    const double lo = -1.0 + 2.0 * b / kBins, hi = lo + 2.0 / kBins;
    EXPECT_NEAR(bins[b] / double(n), cdf(hi) - cdf(lo), 2.0 / n) << "bin " << b;
  }
}

}  // namespace
}  // namespace arbor::tracer

namespace arbor::tracer {
namespace {

// The memory estimate asks the film for its sizes (Film::costs()): they are what a film of any
// kind keeps a pixel — its states and sums, and a pass record of record_size() values.
TEST(Film, CostsAreWhatAFilmKeeps) {
  const scene::FilmCosts c = Film::costs();
  for (const bool ids : {false, true}) {
    for (const std::size_t extras : {std::size_t{0}, std::size_t{5}}) {
      Film film({0, 0, 16, 8}, extras, 2, true, ids);
      const std::size_t pixels = 16 * 8;
      const std::uint64_t kept =
          film.states().size() * sizeof(PixelState) + film.sums().size() * sizeof(double);
      const std::uint64_t sums = c.sums + extras + (ids ? c.id_sums : 0);
      EXPECT_EQ(kept, pixels * (c.state + c.sum * sums)) << "extras " << extras << " ids " << ids;
      EXPECT_EQ(film.record_size(), sums + c.record_extra);
    }
  }
}

}  // namespace
}  // namespace arbor::tracer
