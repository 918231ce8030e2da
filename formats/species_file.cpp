// Species loading: dispatch on the file extension to the format readers.
#include "formats/species_file.h"

#include "common/input_file.h"
#include "common/strings.h"
#include "formats/lsystem_file.h"
#include "formats/skeleton_file.h"
#include "formats/treemaker_template.h"

namespace arbor::formats {

std::string read_text_file(const std::string& path) { return read_text_input(path, "species"); }

namespace {
// A species read from a model's own file format: named after its file.
generator::Species from_file(const std::string& path, generator::ModelParams params) {
  generator::Species sp;
  sp.path = path;
  sp.name = path;
  sp.params = std::move(params);
  return sp;
}
}  // namespace

generator::Species load_species(const std::string& path) {
  if (ends_with(path, ".toml"))
    return parse_species_toml(read_text_input(path, "species", kMaxTomlBytes), path);
  if (ends_with(path, ".xml")) return parse_arbaro_xml(read_text_file(path), path);
  if (ends_with(path, ".lsys")) {
    return from_file(path, parse_lsystem(read_text_file(path), path));
  }
  if (ends_with(path, ".skel")) {
    return from_file(path, parse_skeleton_file(read_text_file(path), path));
  }
  if (ends_with(path, ".tmpl")) {
    generator::Species sp = from_file(path, parse_treemaker_template(read_text_file(path), path));
    sp.treemaker_light = sp.treemaker().light;
    // Colours come from the template: the looks only scale them.
    sp.bark.albedo = {1.0, 1.0, 1.0};
    sp.bark.bump_height = 0.0;
    sp.leaf.reflectance = sp.leaf.back_reflectance = {0.6, 0.6, 0.6};
    sp.leaf.transmittance = {0.3, 0.3, 0.3};
    return sp;
  }
  throw InputError({path, 0, 0},
                   "unknown species format: expected .toml, .xml (Arbaro), .lsys, .skel or .tmpl");
}

}  // namespace arbor::formats
