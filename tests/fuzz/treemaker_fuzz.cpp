// Fuzz target: TREE-MAKER templates, read, grown (small) and meshed.
#include "fuzz_target.h"
#include "generator/treemaker.h"
#include "generator/treemaker_template.h"

ARBOR_FUZZ_TARGET({
  const arbor::gen::TreeMakerTemplate t = arbor::gen::parse_treemaker_template(text, "fuzz.tmpl");
  arbor::gen::TreeMakerOptions o;
  o.max_stems = 2000;
  arbor::fuzz::check_tree(arbor::gen::grow_treemaker(t, o));
})
