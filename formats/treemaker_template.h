// Reading a TREE-MAKER template file (Neighbors & Hodges 1990, Figures 4-6) into the model's
// parameters.
#pragma once

#include <string>

#include "generator/models/treemaker/treemaker_template.h"

namespace arbor::formats {

// Parses a template; every malformed input is an InputError with path:line:col.
generator::TreeMakerTemplate parse_treemaker_template(const std::string& text,
                                                      const std::string& path);

}  // namespace arbor::formats
