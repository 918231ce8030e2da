// Fuzz target: L-systems, read, interpreted (small) and meshed.
#include "fuzz_target.h"
#include "generator/lsystem.h"

ARBOR_FUZZ_TARGET({
  const arbor::gen::LSystem sys = arbor::gen::parse_lsystem(text, "fuzz.lsys");
  arbor::gen::LSystemOptions o;
  o.max_segments = 5000;
  arbor::fuzz::check_tree(arbor::gen::grow_lsystem(sys, o));
})
