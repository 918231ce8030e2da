// Fuzz target: Ünal fractal trees in TOML, read, grown (small) and meshed.
#include "fuzz_target.h"
#include "generator/fractal.h"
#include "generator/species.h"

ARBOR_FUZZ_TARGET({
  const arbor::gen::Species s = arbor::gen::parse_species_toml(text, "fuzz.toml");
  if (s.model != arbor::gen::Model::Fractal) return 0;
  arbor::gen::FractalOptions o;
  o.max_stems = 2000;
  arbor::fuzz::check_tree(arbor::gen::grow_fractal(s.fractal, o), arbor::gen::geometry_options_for(s.leaf));
})
