// Fuzz target: Ünal fractal trees in TOML, read, grown (small) and meshed.
#include "fuzz_target.h"
#include "formats/species_file.h"

ARBOR_FUZZ_TARGET({
  const arbor::generator::Species s = arbor::formats::parse_species_toml(text, "fuzz.toml");
  if (s.model() != arbor::generator::Model::Fractal) return 0;
  arbor::fuzz::grow_and_check(s);
})
