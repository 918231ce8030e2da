// The Weber & Penn 1995 parametric tree model: grows a Skeleton from WeberPennParams.
#pragma once

#include <cstdint>

#include "generator/skeleton.h"
#include "generator/weber_penn_params.h"

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

// An upper estimate of a tree's size, made before growing it (children shared among clones as
// the generator does, clone growth compounded per segment).
struct SizeEstimate {
  double stems = 0.0;
  double leaves = 0.0;
};
SizeEstimate estimate_size(const WeberPennParams& params, double quality);

// Grows the tree. Throws RuntimeFailure when the estimate is over the limits and !force.
// Same params, seed, time and quality ⇒ bit-identical skeleton.
Skeleton grow_weber_penn(const WeberPennParams& params, const GrowOptions& options);

}  // namespace arbor::gen
