// Look-ups on a TREE-MAKER template: colours by name, the branching rule of a level (§IV).
#include "generator/models/treemaker/treemaker_template.h"

namespace arbor::generator {

const TmColor* TreeMakerTemplate::color(const std::string& name) const {
  for (const TmColor& c : colors) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

const TmBranchRule* TreeMakerTemplate::rule_for(int level) const {
  const TmBranchRule* best = nullptr;
  for (const TmBranchRule& r : branches) {
    if (r.level <= level && (!best || r.level > best->level)) best = &r;
  }
  return best;
}

}  // namespace arbor::generator
