// Reading an L-system file (.lsys) into the model's rules and directives.
#pragma once

#include <string>

#include "generator/models/lsystem/lsystem.h"

namespace arbor::formats {

// Parses the language; throws InputError with path:line:col for every malformed input.
generator::LSystem parse_lsystem(const std::string& text, const std::string& path);

}  // namespace arbor::formats
