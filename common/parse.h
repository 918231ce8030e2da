// Parsing of small values given on the command line.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace arbor {

// Whole numbers separated by `sep` ("0:8", "0,0,240,360", "4x2"), `count` of them, each in
// [0, 2^31); InputError naming `option` and the expected `form` otherwise.
std::vector<int> parse_integers(const std::string& text, char sep, std::size_t count,
                                const char* option, const char* form);

}  // namespace arbor
