// Fuzz target: Arbaro XML parameter files.
#include "fuzz_target.h"
#include "generator/grow.h"
#include "generator/species.h"

ARBOR_FUZZ_TARGET({
  const arbor::gen::Species s = arbor::gen::parse_arbaro_xml(text, "fuzz.xml");
  arbor::gen::GrowOptions o;
  o.max_stems = 2000;
  o.max_leaves = 20000;
  arbor::fuzz::check_tree(arbor::gen::grow_tree(s, o), arbor::gen::geometry_options_for(s.leaf));
})
