// Fuzz target: skeleton files, read and meshed.
#include "fuzz_target.h"
#include "formats/skeleton_file.h"

ARBOR_FUZZ_TARGET({
  arbor::fuzz::check_tree(arbor::formats::parse_skeleton_file(text, "fuzz.skel"));
})
