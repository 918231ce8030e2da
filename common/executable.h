// Where the running program is, and the data installed beside it.
#pragma once

#include <string>

namespace arbor {

// The absolute path of the running executable (/proc/self/exe); empty when it cannot be read.
std::string executable_path();

// `<prefix>/share/arbor/<relative>` for the executable `<prefix>/bin/arbor` (any folder name in
// place of bin: the build tree's app/ works the same). `relative` as given when the executable's
// path is unknown.
std::string installed_data_path(const std::string& relative);

}  // namespace arbor
