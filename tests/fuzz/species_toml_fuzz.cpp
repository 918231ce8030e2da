// Fuzz target: Weber & Penn species in TOML, read and, when small, grown and meshed.
#include "fuzz_target.h"
#include "generator/grow.h"
#include "generator/species.h"

ARBOR_FUZZ_TARGET({
  const arbor::gen::Species s = arbor::gen::parse_species_toml(text, "fuzz.toml");
  arbor::gen::GrowOptions o;
  o.max_stems = 2000;
  o.max_leaves = 20000;
  arbor::fuzz::check_tree(arbor::gen::grow_tree(s, o), arbor::gen::geometry_options_for(s.leaf));
})
