// Writing a Skeleton as a skeleton file (.skel, docs/skeleton-format.md).
#pragma once

#include <string>

#include "generator/skeleton.h"

namespace arbor::generator {

// Writes any Skeleton (atomically); formats/skeleton_file.h reads it back as the same skeleton.
void write_skeleton_file(const Skeleton& skeleton, const std::string& path);

}  // namespace arbor::generator
