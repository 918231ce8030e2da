// What every tree model is grown with: the seed, the time for wind, quality and size limits.
#pragma once

#include <cstdint>

namespace arbor {
class Progress;
}

namespace arbor::generator {

struct GrowOptions {
  std::uint64_t seed = 1;
  double time = 0.0;     // seconds, for wind sway (§4.7)
  double quality = 1.0;  // §4.5 quality factor: leaf count × quality, leaf size / sqrt(quality)
  bool force = false;    // grow even when the size estimate is over the limits below
  double max_stems = 1e7;
  double max_leaves = 1e8;
  Progress* progress = nullptr;
};

// The size limits every model enforces (unless GrowOptions::force), with the same words:
// - before growing: RuntimeFailure "<subject> about N <things> (limit L); use --force to grow it
//   anyway" when the model's estimate is over the limit ("more than 1e308" when it overflows);
// - while growing, in case an estimate was low: RuntimeFailure "<subject> N <things>; use --force
//   to grow it anyway" once the count passes twice the limit.
void refuse_estimate(bool force, double estimate, double limit, const char* subject,
                     const char* things);
void refuse_growth(bool force, double count, double limit, const char* subject, const char* things);

}  // namespace arbor::generator
