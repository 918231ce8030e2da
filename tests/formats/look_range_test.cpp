// Each look value's range is stated once (generator/species.h look_range) and every reader of the
// value checks that one range: a species file, a tree's overrides in a scene and a mesh's
// materials accept the bounds and refuse a step beyond them, for every value.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/error.h"
#include "formats/scene_file.h"
#include "formats/species_file.h"
#include "generator/species.h"

namespace arbor::formats {

namespace {

struct LookValue {
  const char* table;     // [bark] or [leaf] of a species; tree.bark / tree.leaf in a scene
  const char* key;       // the key in both
  const char* mesh_key;  // the key in [mesh.material.X] (kind "leaf" or "bark"), or nullptr
  Range range;
  bool in_tree = true;  // also a tree's override in a scene (else the species' alone)
};

const std::vector<LookValue>& look_values() {
  namespace r = generator::look_range;
  static const std::vector<LookValue> values = {
      {"bark", "bump_height", nullptr, r::kBumpHeight},
      {"bark", "roughness", nullptr, r::kBarkRoughness},
      {"leaf", "cuticle_ior", "cuticle_ior", r::kCuticleIor},
      {"leaf", "cuticle_roughness", "cuticle_roughness", r::kCuticleRoughness},
      {"leaf", "variation", nullptr, r::kLeafVariation},
      {"leaf", "hue_variation", nullptr, r::kLeafVariation},
      {"leaf", "crown_gradient", nullptr, r::kCrownGradient},
      {"leaf", "veins", nullptr, r::kVeins},
      {"bark", "lenticels", nullptr, r::kLenticels, false},
      {"bark", "scars", nullptr, r::kScars, false},
      {"bark", "base_height", nullptr, r::kBaseHeight, false},
      {"leaf", "fold", nullptr, r::kLeafFold, false},
      {"leaf", "cup", nullptr, r::kLeafCup, false},
      {"leaf", "curl", nullptr, r::kLeafCurl, false},
      {"leaf", "twist", nullptr, r::kLeafTwist, false},
      {"leaf", "petiole_length", nullptr, r::kPetioleLength, false},
      {"leaf", "petiole_width", nullptr, r::kPetioleWidth, false},
      {"leaf", "tooth_depth", nullptr, r::kToothDepth, false},
  };
  return values;
}

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// The smallest step beyond a bound that a user could type and mean.
double beyond(double bound, double direction) {
  return bound + direction * std::max(1e-9, std::fabs(bound) * 1e-9);
}

bool species_accepts(const LookValue& v, double x) {
  try {
    parse_species_toml("model = \"weber-penn\"\n[" + std::string(v.table) + "]\n" + v.key + " = " +
                           number(x) + "\n",
                       "s.toml");
    return true;
  } catch (const InputError&) {
    return false;
  }
}

bool scene_accepts(const std::string& text) {
  try {
    parse_scene(text, "s.toml");
    return true;
  } catch (const InputError&) {
    return false;
  }
}

bool tree_accepts(const LookValue& v, double x) {
  return scene_accepts("[[tree]]\nspecies = \"a.toml\"\n[tree." + std::string(v.table) + "]\n" +
                       v.key + " = " + number(x) + "\n");
}

bool mesh_accepts(const LookValue& v, double x) {
  return scene_accepts("[[mesh]]\npath = \"m.obj\"\n[mesh.material.m]\nkind = \"leaf\"\n" +
                       std::string(v.mesh_key) + " = " + number(x) + "\n");
}

}  // namespace

TEST(LookRange, EveryReaderChecksTheOneRange) {
  for (const LookValue& v : look_values()) {
    SCOPED_TRACE(std::string(v.table) + "." + v.key);
    for (const auto& accepts : {species_accepts, tree_accepts}) {
      if (accepts == tree_accepts && !v.in_tree) continue;
      EXPECT_TRUE(accepts(v, v.range.lo));
      EXPECT_TRUE(accepts(v, v.range.hi));
      EXPECT_FALSE(accepts(v, beyond(v.range.lo, -1.0)));
      EXPECT_FALSE(accepts(v, beyond(v.range.hi, +1.0)));
    }
    if (v.mesh_key == nullptr) continue;
    EXPECT_TRUE(mesh_accepts(v, v.range.lo));
    EXPECT_TRUE(mesh_accepts(v, v.range.hi));
    EXPECT_FALSE(mesh_accepts(v, beyond(v.range.lo, -1.0)));
    EXPECT_FALSE(mesh_accepts(v, beyond(v.range.hi, +1.0)));
  }
}

TEST(LookRange, AMeshLeafDefaultsToASpeciesLeaf) {
  const spec::SceneDesc s =
      parse_scene("[[mesh]]\npath = \"m.obj\"\n[mesh.material.m]\nkind = \"leaf\"\n", "s.toml");
  const spec::MeshMaterialDesc& m = s.meshes.at(0).materials.at("m");
  const generator::LeafLook leaf;
  EXPECT_EQ(m.reflectance, leaf.reflectance);
  EXPECT_EQ(m.back_reflectance, leaf.back_reflectance);
  EXPECT_EQ(m.transmittance, leaf.transmittance);
  EXPECT_EQ(m.cuticle_ior, leaf.cuticle_ior);
  EXPECT_EQ(m.cuticle_roughness, leaf.cuticle_roughness);
}

TEST(LookRange, ALeafCreatesNoEnergyInAnyReader) {
  // Front 0.6 + transmittance 0.5 in green: refused by the species reader and the mesh reader.
  EXPECT_FALSE(generator::leaf_conserves_energy({0.1, 0.6, 0.1}, {0.1, 0.1, 0.1}, {0.1, 0.5, 0.1}));
  EXPECT_FALSE(generator::leaf_conserves_energy({0.1, 0.1, 0.1}, {0.1, 0.1, 0.6}, {0.1, 0.1, 0.5}));
  EXPECT_TRUE(generator::leaf_conserves_energy({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}));
  EXPECT_THROW(parse_species_toml("model = \"weber-penn\"\n[leaf]\nreflectance = [0.1, 0.6, 0.1]\n"
                                  "transmittance = [0.1, 0.5, 0.1]\n",
                                  "s.toml"),
               InputError);
  EXPECT_FALSE(
      scene_accepts("[[mesh]]\npath = \"m.obj\"\n[mesh.material.m]\nkind = \"leaf\"\n"
                    "back_reflectance = [0.1, 0.6, 0.1]\ntransmittance = [0.1, 0.5, 0.1]\n"));
  EXPECT_TRUE(
      scene_accepts("[[mesh]]\npath = \"m.obj\"\n[mesh.material.m]\nkind = \"leaf\"\n"
                    "back_reflectance = [0.1, 0.5, 0.1]\ntransmittance = [0.1, 0.5, 0.1]\n"));
}

}  // namespace arbor::formats
