// Fuzz target: TREE-MAKER templates, read, grown (small) and meshed.
#include "fuzz_target.h"
#include "generator/models/treemaker/treemaker_template.h"
#include "formats/treemaker_template.h"

ARBOR_FUZZ_TARGET({
  arbor::generator::Species s;
  s.path = "fuzz.tmpl";
  s.params = arbor::formats::parse_treemaker_template(text, s.path);
  arbor::fuzz::grow_and_check(s);
})
