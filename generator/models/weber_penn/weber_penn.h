// The Weber & Penn 1995 parametric tree model: grows a Skeleton from WeberPennParams.
#pragma once

#include <cstdint>

#include "generator/grow_options.h"
#include "generator/skeleton.h"
#include "generator/models/weber_penn/weber_penn_params.h"

namespace arbor::generator {

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

}  // namespace arbor::generator
