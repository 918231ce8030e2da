// Skeleton files (.skel, docs/skeleton-format.md): Bloomenthal's points and connections as plain
// text, with optional records that make `arbor grow -o tree.skel` round-trip exactly.
#pragma once

#include <string>

#include "generator/skeleton.h"

namespace arbor::formats {

// Reads and validates a skeleton file (all points connected, at most one incoming limb per
// point, exactly one root). Throws InputError naming the offending point and line.
generator::Skeleton parse_skeleton_file(const std::string& text, const std::string& path);

}  // namespace arbor::formats
