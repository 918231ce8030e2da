// TREE-MAKER growth (Neighbors & Hodges §II, §IV): a particle system with probabilistic branching,
// gravity and aging, leaves at every branch end. Grows a Skeleton from a template.
#pragma once

#include <cstdint>

#include "generator/grow_options.h"
#include "generator/skeleton.h"
#include "generator/models/treemaker/treemaker_template.h"

namespace arbor::generator {

// Template units are centimetres (the paper's dogwood then grows to about 3 m with 9 cm leaves).
constexpr double kTreeMakerUnit = 0.01;

// TREE-MAKER reads seed, max_stems (branches) and force.
using TreeMakerOptions = GrowOptions;

// Upper estimate of the branches a template can grow (each level at its rule's largest count).
double treemaker_estimate(const TreeMakerTemplate& t);

Skeleton grow_treemaker(const TreeMakerTemplate& t, const TreeMakerOptions& options);

}  // namespace arbor::generator
