// Tests of the species TOML reader and of reading a species file by its extension: the shipped
// files load, and every class of bad input is an InputError naming the file, line and column.
#include <filesystem>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "formats/species_file.h"
#include "generator/grow.h"
#include "generator/species.h"

namespace arbor::formats {

using namespace generator;  // the readers fill the generator's types

namespace {

std::string species_dir() { return std::string(ARBOR_SOURCE_DIR) + "/species/"; }

const char* const kMinimal = "model = \"weber-penn\"\n";

// Expects parsing `text` to fail at line:column with a message containing `fragment`.
void expect_toml_error(const std::string& text, int line, int column, const std::string& fragment) {
  testing::expect_input_error([&] { formats::parse_species_toml(text, "t.toml"); }, "t.toml", line,
                              column, fragment);
}

}  // namespace

TEST(SpeciesToml, ShippedSpeciesLoad) {
  const Species aspen = formats::load_species(species_dir() + "quaking_aspen.toml");
  EXPECT_EQ(aspen.name, "Quaking Aspen");
  const WeberPennParams& p = aspen.weber_penn();
  EXPECT_EQ(p.shape, 7);
  EXPECT_DOUBLE_EQ(p.base_size, 0.4);
  EXPECT_DOUBLE_EQ(p.level[1].down_angle_v, -50.0);
  EXPECT_DOUBLE_EQ(p.level[1].branches, 50.0);
  EXPECT_EQ(p.level[2].curve_res, 3);
  EXPECT_DOUBLE_EQ(p.leaf_scale, 0.17);
  EXPECT_DOUBLE_EQ(aspen.bark.albedo[0], 0.58);
  const Species willow = formats::load_species(species_dir() + "weeping_willow.toml");
  EXPECT_EQ(willow.weber_penn().level[0].base_splits, 2);
  EXPECT_DOUBLE_EQ(willow.weber_penn().level[1].rotate, -120.0);
  EXPECT_DOUBLE_EQ(willow.weber_penn().prune_power_low, 0.001);
  EXPECT_DOUBLE_EQ(willow.weber_penn().level[3].branches, 300.0);
}

TEST(SpeciesToml, ShippedWeberPennSpeciesSwayInTheirBreezeExceptTheCactus) {
  // Issue 14: --time must change the shipped trees. Half a second moves some limb of each by a
  // centimetre or more; the Saguaro has no wind.
  for (const char* name :
       {"quaking_aspen", "black_tupelo", "weeping_willow", "ca_black_oak", "sassafras",
        "lombardy_poplar", "black_spruce", "balsam_fir", "queen_palm", "saguaro_cactus"}) {
    const Species sp = formats::load_species(species_dir() + name + ".toml");
    GrowOptions now, later;
    later.time = 0.5;
    const Skeleton a = grow_tree(sp, now), b = grow_tree(sp, later);
    ASSERT_EQ(a.points.size(), b.points.size()) << name;
    double moved = 0.0;
    for (size_t i = 0; i < a.points.size(); ++i) {
      moved = std::max(moved, double(glm::length(a.points[i].position - b.points[i].position)));
    }
    if (std::string(name) == "saguaro_cactus") {
      EXPECT_EQ(moved, 0.0);
    } else {
      EXPECT_GT(moved, 0.01) << name;
      EXPECT_LT(moved, 3.0) << name;  // a breeze, not a storm
    }
  }
}

TEST(SpeciesToml, MinimalFileGetsDefaults) {
  const Species s = formats::parse_species_toml(kMinimal, "m.toml");
  EXPECT_EQ(s.weber_penn().levels, 1);
  EXPECT_EQ(s.name, "m.toml");
}

// [leaf] season and autumn: read, checked; absent, the leaves are summer's and evergreen.
TEST(SpeciesToml, LeafSeasonAndAutumnColour) {
  const Species plain = formats::parse_species_toml(kMinimal, "m.toml");
  EXPECT_EQ(plain.leaf.season, generator::Season::Summer);
  EXPECT_FALSE(plain.leaf.autumn.has_value());
  const Species autumn = formats::parse_species_toml(
      std::string(kMinimal) + "[leaf]\nseason = \"autumn\"\nautumn = [0.55, 0.33, 0.03]\n",
      "m.toml");
  EXPECT_EQ(autumn.leaf.season, generator::Season::Autumn);
  ASSERT_TRUE(autumn.leaf.autumn.has_value());
  EXPECT_EQ((*autumn.leaf.autumn)[0], 0.55);
  expect_toml_error(std::string(kMinimal) + "[leaf]\nseason = \"fall\"\n", 3, 10,
                    "leaf.season must be one of");
  expect_toml_error(std::string(kMinimal) + "[leaf]\nautumn = [1.5, 0.3, 0.0]\n", 3, 11,
                    "leaf.autumn");
}

TEST(SpeciesToml, SyntaxErrorsCarryTheirPosition) {
  expect_toml_error("model = \"weber-penn\"\nShape = = 3\n", 2, 9, "");
}

TEST(SpeciesToml, UnknownKeysAreErrors) {
  expect_toml_error(std::string(kMinimal) + "Shap = 3\n", 2, 1, "unknown key 'Shap'");
  expect_toml_error(std::string(kMinimal) + "[level.1]\nLenght = 0.3\n", 3, 1,
                    "unknown key 'Lenght' in [level.1]");
  expect_toml_error(std::string(kMinimal) + "[bark]\ncolour = [1, 1, 1]\n", 3, 1,
                    "unknown key 'colour' in [bark]");
  expect_toml_error(std::string(kMinimal) + "Length = 1\n", 2, 1, "per-level parameter");
}

TEST(SpeciesToml, MissingOrWrongModelIsAnError) {
  expect_toml_error("Shape = 3\n", 1, 1, "missing key 'model'");
  expect_toml_error("model = \"spruce\"\n", 1, 9, "model 'spruce'");
}

TEST(SpeciesToml, WrongTypesAreErrors) {
  expect_toml_error(std::string(kMinimal) + "Scale = \"big\"\n", 2, 9, "Scale must be a number");
  expect_toml_error(std::string(kMinimal) + "Levels = 2.5\n", 2, 10, "whole number");
  expect_toml_error(std::string(kMinimal) + "level = 3\n", 2, 9, "must be a table");
  expect_toml_error(std::string(kMinimal) + "[leaf]\nreflectance = [0.1, 0.2]\n", 3, 15,
                    "array of 3 numbers");
}

TEST(SpeciesToml, OutOfRangeAndNonFiniteValuesAreErrors) {
  expect_toml_error(std::string(kMinimal) + "Shape = 9\n", 2, 9, "out of range [0, 8]");
  expect_toml_error(std::string(kMinimal) + "BaseSize = 1.5\n", 2, 12, "out of range");
  expect_toml_error(std::string(kMinimal) + "Scale = nan\n", 2, 9, "finite");
  expect_toml_error(std::string(kMinimal) + "Ratio = inf\n", 2, 9, "finite");
  expect_toml_error(std::string(kMinimal) + "[level.2]\nTaper = 3.5\n", 3, 9, "2Taper = 3.5");
  expect_toml_error(std::string(kMinimal) + "[level.1]\nCurveRes = 0\n", 3, 12, "1CurveRes");
  expect_toml_error(std::string(kMinimal) + "[bark]\nalbedo = [0.5, 1.5, 0.5]\n", 3, 16, "[0, 1]");
}

TEST(SpeciesToml, LevelRulesAreChecked) {
  expect_toml_error(std::string(kMinimal) + "[level.4]\nLength = 1\n", 2, 8, "levels are 0");
  expect_toml_error(std::string(kMinimal) + "[level.1]\nBaseSplits = 2\n", 3, 1, "trunk parameter");
  expect_toml_error(std::string(kMinimal) + "[level.0]\nDownAngle = 20\n", 3, 1,
                    "no meaning for the trunk");
}

TEST(SpeciesToml, InconsistentParametersPointAtTheKey) {
  expect_toml_error(std::string(kMinimal) + "Scale = 5\nScaleV = 6\n", 3, 10, "ScaleV");
  // CA Black Oak has ScaleV = Scale: allowed.
  EXPECT_NO_THROW(
      formats::parse_species_toml(std::string(kMinimal) + "Scale = 10\nScaleV = 10\n", "o"));
}

TEST(SpeciesToml, LeafHingeAngleIsReadAndBounded) {
  const Species s =
      formats::parse_species_toml(std::string(kMinimal) + "[leaf]\nhinge_angle = 25\n", "h");
  EXPECT_DOUBLE_EQ(s.leaf.hinge_angle, 25.0);
  expect_toml_error(std::string(kMinimal) + "[leaf]\nhinge_angle = 120\n", 3, 15, "[0, 90]");
}

TEST(SpeciesToml, LeafCuticleIsReadAndBoundedWithAGlossyDefault) {
  const Species s = formats::parse_species_toml(
      std::string(kMinimal) + "[leaf]\ncuticle_ior = 1.5\ncuticle_roughness = 0.25\n", "c");
  EXPECT_DOUBLE_EQ(s.leaf.cuticle_ior, 1.5);
  EXPECT_DOUBLE_EQ(s.leaf.cuticle_roughness, 0.25);
  const Species d = formats::parse_species_toml(kMinimal, "c");
  EXPECT_DOUBLE_EQ(d.leaf.cuticle_ior, 1.45);  // wax, docs/species-format.md
  EXPECT_DOUBLE_EQ(d.leaf.cuticle_roughness, 0.5);
  EXPECT_NO_THROW(formats::parse_species_toml(std::string(kMinimal) + "[leaf]\ncuticle_ior = 1.0\n",
                                              "c"));  // matte
  expect_toml_error(std::string(kMinimal) + "[leaf]\ncuticle_ior = 0.9\n", 3, 15, "[1, 3]");
  expect_toml_error(std::string(kMinimal) + "[leaf]\ncuticle_roughness = 1.2\n", 3, 21, "[0, 1]");
  expect_toml_error(std::string(kMinimal) + "[leaf]\ncuticle_roughness = nan\n", 3, 21, "finite");
}

TEST(SpeciesToml, RootButtressesAreReadAndBounded) {
  const Species s = formats::parse_species_toml(
      std::string(kMinimal) + "[roots]\nbuttresses = 5\nheight = 4\nspread = 1.5\n", "r");
  EXPECT_EQ(s.roots.buttresses, 5);
  EXPECT_DOUBLE_EQ(s.roots.height, 4.0);
  EXPECT_DOUBLE_EQ(s.roots.spread, 1.5);
  EXPECT_EQ(formats::parse_species_toml(kMinimal, "r").roots.buttresses, 0);  // off by default
  expect_toml_error(std::string(kMinimal) + "[roots]\nbuttresses = 2.5\n", 3, 14,
                    "whole number in [0, 16]");
  expect_toml_error(std::string(kMinimal) + "[roots]\nbuttresses = 17\n", 3, 14, "[0, 16]");
  expect_toml_error(std::string(kMinimal) + "[roots]\nheight = 0\n", 3, 10, "(0, 50]");
  expect_toml_error(std::string(kMinimal) + "[roots]\nreach = \"far\"\n", 3, 1,
                    "unknown key 'reach' in [roots]");
}

TEST(SpeciesToml, LeafMustNotCreateEnergy) {
  expect_toml_error(std::string(kMinimal) +
                        "[leaf]\nreflectance = [0.6, 0.2, 0.1]\ntransmittance = [0.5, 0.1, 0.1]\n",
                    2, 1, "at most 1");
}

TEST(SpeciesFile, UnreadableAndUnknownFormatsAreErrors) {
  try {
    formats::load_species("/nonexistent/tree.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().path, "/nonexistent/tree.toml");
    EXPECT_NE(e.message().find("species does not exist"), std::string::npos) << e.message();
  }
  EXPECT_THROW(formats::load_species("tree.obj"), InputError);
}

}  // namespace arbor::formats
