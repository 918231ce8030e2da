// The OBJ reader: what it keeps, and every malformed record refused at its line and column.
#include "formats/obj_mesh.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "generator/grow.h"
#include "generator/species.h"
#include "generator/geometry/tree_geometry.h"
#include "generator/geometry/tree_mesh.h"
#include "formats/species_file.h"
#include "generator/export/export_mesh.h"

namespace arbor::formats {
namespace {

void expect_error(const std::string& text, int line, int column, const std::string& fragment) {
  testing::expect_input_error([&] { parse_obj(text, "m.obj"); }, "m.obj", line, column, fragment);
}

const char* const kQuad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

TEST(ObjMesh, ReadsFacesGroupsAndMaterials) {
  const ObjMesh m =
      parse_obj(std::string("# a quad and a triangle\nmtllib x.mtl\n") + kQuad +
                    "vt 0 0\nvt 1 0 0\nvn 0 0 1\ng floor\ns off\nf 1/1/1 2/2/1 3//1 4\n"
                    "usemtl bark\nf -4 -3 -1\n",
                "m.obj");
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[2], glm::vec3(1, 1, 0));
  ASSERT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 1, 3}));
  ASSERT_EQ(m.part, (std::vector<std::uint32_t>{0, 0, 1}));
  ASSERT_EQ(m.parts.size(), 2u);
  EXPECT_EQ(m.parts[0].group, "floor");
  EXPECT_EQ(m.parts[0].material, "");
  EXPECT_EQ(m.parts[1].group, "floor");
  EXPECT_EQ(m.parts[1].material, "bark");
  EXPECT_EQ(m.part_line, (std::vector<int>{12, 14}));
  // The normals are kept (unit length) and indexed per triangle corner; a corner without one is
  // kNoNormal.
  ASSERT_EQ(m.normals.size(), 1u);
  EXPECT_EQ(m.normals[0], glm::vec3(0, 0, 1));
  const std::uint32_t none = ObjMesh::kNoNormal;
  EXPECT_EQ(m.normal_indices, (std::vector<std::uint32_t>{0, 0, 0, 0, 0, none, none, none, none}));
  // A file without normals keeps none.
  EXPECT_TRUE(parse_obj(std::string(kQuad) + "f 1 2 3\n", "m.obj").normal_indices.empty());
  const ObjMesh scaled = parse_obj(std::string(kQuad) + "vn 0 3 4\nf 1//1 2//1 3//1\n", "m.obj");
  EXPECT_NEAR(scaled.normals[0].y, 0.6f, 1e-6f);
  EXPECT_NEAR(scaled.normals[0].z, 0.8f, 1e-6f);
  // Faces may name vertices defined after them.
  EXPECT_EQ(parse_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "m.obj").indices.size(), 3u);
}

TEST(ObjMesh, BadNumbersAndIndicesAreRefusedWithTheirPosition) {
  const std::string q = kQuad;
  expect_error("v 0 nan 0\n", 1, 5, "'nan' is not a finite number");
  expect_error("v 0 0 inf\n", 1, 7, "not a finite number");
  expect_error("v 0 0 1e999\n", 1, 7, "not a number");
  // Found by fuzzing: 1e308 is a finite double but an infinite float.
  expect_error("v 1 0.1e309 0\n", 1, 5, "'0.1e309' is out of range [-1e9, 1e9]");
  expect_error("v 0 0\n", 1, 1, "'v' needs 3 numbers");
  expect_error("v 0 0 x\n", 1, 7, "'x' is not a number");
  expect_error("vn 0 0 nan\n", 1, 8, "not a finite number");
  expect_error("vt nan\n", 1, 4, "not a finite number");
  expect_error("vn 0 0 0\n", 1, 1, "a vertex normal of zero length");
  expect_error(q + "f 1 2 5\n", 5, 7, "refers to vertex 5, but the file defines 4");
  expect_error(q + "f 1 2 0\n", 5, 7, "not a vertex index");
  expect_error(q + "f 1 2 -5\n", 5, 7, "only 4 are defined");
  expect_error(q + "f 1 2 12345678901234567890\n", 5, 7, "not a vertex index");
  expect_error(q + "f 1 2 3x\n", 5, 7, "not a vertex index");
  expect_error(q + "vt 0 0\nf 1/1 2/2 3/1\n", 6, 9,
               "refers to texture coordinate 2, but the file defines 1");
  expect_error(q + "vn 0 0 1\nf 1//1 2//1 3//-2\n", 6, 16, "refers to normal -2");
  expect_error(q + "f 1/1/1/1 2 3\n", 5, 3, "more than v/vt/vn");
  expect_error(q + "f 1 2\n", 5, 1, "at least three vertices");
  expect_error(q + "curv 0 1 1 2\n", 5, 1, "unknown OBJ statement 'curv'");
}

// A polygon of 100,000 vertices once hung the import; it is a fan of 99,998 triangles.
TEST(ObjMesh, HugePolygonsAreFannedInLinearTime) {
  const int n = 100000;
  std::string text;
  text.reserve(static_cast<std::size_t>(n) * 40);
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * 3.14159265358979 * k / n;
    text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
  }
  text += "f";
  for (int k = 1; k <= n; ++k) text += " " + std::to_string(k);
  text += "\n";
  const ObjMesh m = parse_obj(text, "m.obj");
  EXPECT_EQ(m.indices.size(), 3u * (n - 2));
}

// What arbor exports, arbor reads back: the same vertices and triangles.
TEST(ObjMesh, ReadsArborsOwnExport) {
  const generator::Species s =
      load_species(std::string(ARBOR_SOURCE_DIR) + "/species/dogwood.tmpl");
  const generator::TreeMesh tree = generator::tessellate(generator::build_tree_geometry(
      generator::grow_tree(s, generator::GrowOptions{}), generator::geometry_options_for(s)));
  const std::string path = ::testing::TempDir() + "export_roundtrip.obj";
  generator::write_obj(tree, path, {s.name, s.bark, s.leaf});
  const ObjMesh m = load_obj(path);
  ASSERT_EQ(m.positions.size(), tree.positions.size());
  EXPECT_EQ(m.indices, tree.indices);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    ASSERT_NEAR(m.positions[i].x, tree.positions[i].x,
                1e-5f * (1.0f + std::fabs(tree.positions[i].x)))
        << i;
  }
  EXPECT_EQ(m.parts.front().group, "bark");
  EXPECT_EQ(m.parts.back().group, "leaf");
}

}  // namespace
}  // namespace arbor::formats
