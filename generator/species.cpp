// The checks every species reader ends with.
#include "generator/species.h"

namespace arbor::generator {

void finish_species(Species& sp, const std::map<std::string, SourceLocation>& positions) {
  std::string key;
  const std::string problem =
      sp.model() == Model::WeberPenn ? check_consistency(sp.weber_penn(), key) : "";
  if (!problem.empty()) {
    const auto it = positions.find(key);
    throw InputError(it != positions.end() ? it->second : SourceLocation{sp.path, 1, 1}, problem);
  }
  if (sp.name.empty()) sp.name = sp.path;
}

}  // namespace arbor::generator
