// Reading species files: arbor's TOML, Arbaro's XML, and each model's own format (.lsys, .tmpl,
// .skel), into a Species.
#pragma once

#include <string>
#include <string_view>

#include "generator/species.h"

namespace arbor::formats {

// Reads a species file, choosing the format by extension: .toml (arbor's format, `model =`
// says which model) or .xml (an Arbaro Weber & Penn parameter file). Throws InputError with
// the position of the problem.
generator::Species load_species(const std::string& path);

// The two readers, from text already in memory (path is used in messages).
generator::Species parse_species_toml(std::string_view text, const std::string& path);
generator::Species parse_arbaro_xml(std::string_view text, const std::string& path);

// Reads a whole species file (read_text_input: regular files only, bounded in size).
std::string read_text_file(const std::string& path);

}  // namespace arbor::formats
