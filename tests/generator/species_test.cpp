// Tests of the species readers: the shipped files load, and every class of bad input is an
// InputError naming the file, line and column.
#include "generator/species.h"

#include <filesystem>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "formats/species_file.h"
#include "generator/grow.h"

namespace arbor::generator {

namespace {

std::string species_dir() { return std::string(ARBOR_SOURCE_DIR) + "/species/"; }

const char* const kMinimal = "model = \"weber-penn\"\n";

// Expects parsing `text` to fail at line:column with a message containing `fragment`.
void expect_toml_error(const std::string& text, int line, int column, const std::string& fragment) {
  testing::expect_input_error([&] { formats::parse_species_toml(text, "t.toml"); }, "t.toml", line,
                              column, fragment);
}

void expect_xml_error(const std::string& text, int line, const std::string& fragment) {
  try {
    formats::parse_arbaro_xml(text, "t.xml");
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().path, "t.xml");
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_NE(e.message().find(fragment), std::string::npos) << e.what();
  }
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

TEST(ArbaroXml, ReadsParametersWithLevelPrefixes) {
  const Species s = formats::parse_arbaro_xml(
      "<?xml version='1.0'?>\n<arbaro>\n<species name='test'>\n"
      "<param name='Shape' value='4'/>\n<param name='Levels' value='3'/>\n"
      "<param name='1DownAngle' value='60'/>\n<param name='0BaseSplits' value='2'/>\n"
      "<param name='3Branches' value='12'/>\n<param name='0Scale' value='1.2'/>\n"
      "</species>\n</arbaro>\n",
      "t.xml");
  EXPECT_EQ(s.name, "test");
  EXPECT_EQ(s.weber_penn().shape, 4);
  EXPECT_DOUBLE_EQ(s.weber_penn().level[1].down_angle, 60.0);
  EXPECT_EQ(s.weber_penn().level[0].base_splits, 2);
  EXPECT_DOUBLE_EQ(s.weber_penn().level[3].branches, 12.0);
  EXPECT_DOUBLE_EQ(s.weber_penn().level[0].scale, 1.2);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(ArbaroXml, ArbaroExtensionsAreWarnedAboutAndIgnored) {
  const Species s = formats::parse_arbaro_xml(
      "<arbaro><species name='x'>\n<param name='Smooth' value='0.5'/>\n"
      "<param name='1BranchDist' value='1'/>\n<param name='0DownAngle' value='0'/>\n"
      "</species></arbaro>",
      "t.xml");
  ASSERT_EQ(s.warnings.size(), 3u);
  EXPECT_EQ(s.warnings[0].rfind("t.xml:2:", 0), 0u) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("warning: Arbaro's parameter 'Smooth'"), std::string::npos);
}

TEST(ArbaroXml, ErrorsCarryTheirLine) {
  expect_xml_error(
      "<arbaro><species>\n<param name='Shape' value='3'/>\n<param name='Shap' "
      "value='3'/>\n</species></arbaro>",
      3, "unknown parameter 'Shap'");
  expect_xml_error("<arbaro><species>\n\n<param name='Ratio' value='abc'/></species></arbaro>", 3,
                   "not a number");
  expect_xml_error("<arbaro><species>\n<param name='1Taper' value='4'/></species></arbaro>", 2,
                   "1Taper = 4 is out of range");
  expect_xml_error("<arbaro><species>\n<param name='5Length' value='1'/></species></arbaro>", 2,
                   "levels are 0 to 3");
  expect_xml_error("<arbaro><species>\n<param name='2BaseSplits' value='1'/></species></arbaro>", 2,
                   "only for the trunk");
  expect_xml_error("<arbaro><species>\n<param value='1'/></species></arbaro>", 2, "needs 'name'");
  expect_xml_error("<arbaro>\n<species>\n<param name='Shape' value='1'>\n</species></arbaro>", 4,
                   "malformed XML");
  expect_xml_error("<tree/>", 1, "expected an <arbaro>");
  expect_xml_error("<arbaro><species>\n<param name='Scale' value='nan'/></species></arbaro>", 2,
                   "finite");
}

}  // namespace arbor::generator

namespace arbor::generator {

// Text before the root element was once accepted; text is not part of the format anywhere.
TEST(ArbaroXml, TextOutsideTheElementsIsRefused) {
  const std::string body =
      "<arbaro><species name='x'>\n<param name='Shape' value='3'/>\n</species></arbaro>\n";
  expect_xml_error("garbage\n" + body, 1, "unexpected text outside the <arbaro> element");
  expect_xml_error(body + "\ntrailing words\n", 5, "unexpected text outside");
  expect_xml_error("<arbaro>stray<species name='x'>\n</species></arbaro>\n", 1,
                   "unexpected text in <arbaro>");
  expect_xml_error(
      "<arbaro><species name='x'>\n<param name='Shape' value='3'/>\nwords\n</species></arbaro>\n",
      3, "unexpected text in <species>");
  expect_xml_error(body + "<arbaro/>\n", 4, "a second root element");
  // Declarations, comments and white space stay allowed.
  EXPECT_NO_THROW(formats::parse_arbaro_xml(
      "<?xml version='1.0'?>\n<!-- a tree -->\n" + body + "  \n", "t.xml"));
}

}  // namespace arbor::generator

namespace arbor::generator {

// Every shipped species, whatever its model, grows a skeleton that satisfies the invariants the
// geometry relies on (one root, parents before children, finite points, children no thicker
// than their parents where they start, leaves on stems) and has a sane scale.
TEST(Species, EveryShippedSpeciesGrowsAValidSkeleton) {
  const std::string folder = std::string(ARBOR_SOURCE_DIR) + "/species";
  int grown = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const Species species = formats::load_species(entry.path().string());
    for (std::uint64_t seed : {1u, 8u}) {
      GrowOptions options;
      options.seed = seed;
      options.quality = 0.5;  // half the leaves: the invariants do not depend on their number
      const Skeleton sk = grow_tree(species, options);
      const std::string name = entry.path().filename().string() + " seed " + std::to_string(seed);
      EXPECT_EQ(validate(sk), "") << name;
      EXPECT_EQ(scale_problem(sk), "") << name;
      EXPECT_GE(sk.stems.size(), 1u) << name;
    }
    ++grown;
  }
  EXPECT_GE(grown, 20);  // the shipped species of every model
}

}  // namespace arbor::generator
