// The scene file's key reference (docs/scene-format.md) and the render settings' text, both from
// the key tables (scene_keys.h).
#include <string>
#include <vector>

#include "spec/scene_desc.h"
#include "formats/scene_keys.h"

namespace arbor::formats {

namespace {

struct Section {
  std::string title, intro;
  std::vector<KeyDoc> keys;
  std::string owners = "models";  // the column naming what each key belongs to, when any does
};

std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string markdown(const Section& s) {
  bool models = false;
  for (const KeyDoc& k : s.keys) models = models || !k.belongs.empty();
  std::string md = "## " + s.title + "\n\n" + s.intro +
                   "\n\n| key | type | range | default | meaning |" +
                   (models ? " " + s.owners + " |" : "") + "\n|---|---|---|---|---|" +
                   (models ? "---|" : "") + "\n";
  for (const KeyDoc& k : s.keys) {
    md += "| `" + k.name + "` | " + k.kind + " | " + cell(k.range) + " | " + cell(k.default_value) +
          " | " + cell(k.meaning) + " |";
    if (models) md += " " + (k.belongs.empty() ? std::string("all") : k.belongs) + " |";
    md += "\n";
  }
  return md + "\n";
}

}  // namespace

std::string scene_key_reference() {
  const std::vector<Section> sections = {
      {"The tables", "A scene file is TOML; its top level holds these tables and no other key.",
       key_docs(scene_keys())},
      {"[render]",
       "The image and how it is sampled (docs/rendering.md); a key of the other integrator than "
       "the one in use is an error.",
       key_docs(render_keys()), "integrators"},
      {"[camera]", "A pinhole, or a thin lens with `aperture_radius` > 0.",
       key_docs(camera_keys())},
      {"[sun]", "A disk of the sun's angular size.", key_docs(sun_keys())},
      {"[sky]",
       "A key of another model than the one in use is an error at its line and column "
       "(docs/rendering.md, \"Lights\").",
       key_docs(sky_keys())},
      {"[ground]", "The plane z = 0 (docs/rendering.md, \"Materials\").", key_docs(ground_keys())},
      {"[terrain]",
       "A height field the scene stands on (docs/landscape.md); a key of another kind than the "
       "one in use is an error.",
       key_docs(terrain_keys())},
      {"[meadow]", "Grass blades as geometry (docs/rendering.md, \"Meadow\").",
       key_docs(meadow_keys())},
      {"[[tree]]", "One tree; a scene may hold any number.", key_docs(tree_keys())},
      {"[[forest]]", "Trees of one species scattered over an area, as instances of a few variants.",
       key_docs(forest_keys())},
      {"[community]",
       "Plants of several species grown together as circles of influence (docs/landscape.md).",
       key_docs(community_keys())},
      {"[[community.species]]", "One species of the community, its habitat and its growth.",
       key_docs(community_species_keys())},
      {"[rocks]",
       "Boulders and stones of a few noise-displaced shapes, instanced, on rock faces and scree "
       "and partly buried (docs/landscape.md, \"Rocks\").",
       key_docs(rocks_keys())},
      {"[tree.bark], [forest.bark]", "The species' bark overridden; unset keys keep the species'.",
       key_docs(bark_keys())},
      {"[tree.leaf], [forest.leaf]",
       "The species' leaves overridden; unset keys keep the species'. Reflectance plus "
       "transmittance stays at most 1 per channel.",
       key_docs(leaf_keys())},
      {"[tree.treemaker], [forest.treemaker]",
       "TREE-MAKER's shading weights (§III) for the treemaker integrator; unset keys keep the "
       "template's `light {}` values, or arbor's defaults for trees of other models.",
       key_docs(treemaker_keys())},
      {"[[mesh]]", "A Wavefront OBJ (docs/rendering.md, \"What is built\").",
       key_docs(mesh_keys())},
      {"[mesh.material.NAME]",
       "The material of the faces whose `usemtl` or group is NAME; with any such table, an "
       "unmapped face is an error.",
       key_docs(mesh_material_keys())},
      {"[output]", "The files written (docs/outputs.md).", key_docs(output_keys())},
      {"[animation]", "Frame N at N / fps seconds (docs/farm.md).", key_docs(animation_keys())},
  };
  std::string md =
      "# Scene file keys\n\n"
      "Generated from the key tables in formats/scene_keys.cpp and "
      "formats/scene_keys_trees.cpp (`ARBOR_WRITE_REFERENCE=1 build/tests/formats_tests "
      "--gtest_filter=SceneKeys.TheReferencePageIsTheTables` rewrites it; that test fails when "
      "this page and the tables differ). Every key is "
      "checked where it is read: a value out of its range, of the wrong type, or a key unknown "
      "to its table is an error at its file, line and column (exit 2). Paths are relative to the "
      "scene file. Numbers are metres, degrees and seconds unless the range says otherwise.\n\n";
  for (const Section& s : sections) md += markdown(s);
  return md;
}

std::string render_settings_text(const spec::RenderSettings& r) {
  return values_text(render_keys(), r);
}

}  // namespace arbor::formats
