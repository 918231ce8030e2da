// Growing a tree from any species, whichever model it uses: the one entry point of the
// generator for the command line and the renderer.
#pragma once

#include "generator/skeleton.h"
#include "generator/species.h"
#include "generator/grow_options.h"

namespace arbor::generator {

// Grows the species' tree with its own model. Throws RuntimeFailure when the size estimate is
// over the options' limits (and !force).
Skeleton grow_tree(const Species& species, const GrowOptions& options);

}  // namespace arbor::generator
