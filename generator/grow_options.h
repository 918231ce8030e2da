// What every tree model is grown with: the seed, the time for wind, quality and size limits.
#pragma once

#include <cstdint>

namespace arbor {
class Progress;
}

namespace arbor::gen {

struct GrowOptions {
  std::uint64_t seed = 1;
  double time = 0.0;      // seconds, for wind sway (§4.7)
  double quality = 1.0;   // §4.5 quality factor: leaf count × quality, leaf size / sqrt(quality)
  bool force = false;     // grow even when the size estimate is over the limits below
  double max_stems = 1e7;
  double max_leaves = 1e8;
  Progress* progress = nullptr;
};

}  // namespace arbor::gen
