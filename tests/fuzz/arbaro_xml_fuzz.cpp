// Fuzz target: Arbaro XML parameter files.
#include "fuzz_target.h"
#include "formats/species_file.h"

ARBOR_FUZZ_TARGET({
  arbor::fuzz::grow_and_check(arbor::formats::parse_arbaro_xml(text, "fuzz.xml"));
})
