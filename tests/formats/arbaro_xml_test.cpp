// Tests of the Arbaro XML reader: parameters with level prefixes, Arbaro's extensions warned
// about, and every class of bad input an InputError naming the file and line.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "formats/species_file.h"
#include "generator/species.h"

namespace arbor::formats {

using namespace generator;  // the readers fill the generator's types

namespace {

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

}  // namespace arbor::formats
