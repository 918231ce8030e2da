// Fuzz target: Weber & Penn species in TOML, read and, when small, grown and meshed.
#include "fuzz_target.h"
#include "formats/species_file.h"

ARBOR_FUZZ_TARGET({
  arbor::fuzz::grow_and_check(arbor::formats::parse_species_toml(text, "fuzz.toml"));
})
