// Fuzz target: L-systems, read, interpreted (small) and meshed.
#include "fuzz_target.h"
#include "generator/models/lsystem/lsystem.h"
#include "formats/lsystem_file.h"

ARBOR_FUZZ_TARGET({
  arbor::generator::Species s;
  s.path = "fuzz.lsys";
  s.params = arbor::formats::parse_lsystem(text, s.path);
  arbor::fuzz::grow_and_check(s);
})
