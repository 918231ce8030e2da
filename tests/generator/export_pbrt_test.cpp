// Tests of the pbrt-v4 export: one Bézier cylinder curve per curve segment with the exact control
// points, meshes for the trunk grid and leaves, well-formed parameter lists.
#include "generator/export/export_pbrt.h"

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "generator/models/weber_penn/weber_penn.h"
#include "formats/species_file.h"

namespace arbor::generator {

namespace {
std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}
}  // namespace

TEST(ExportPbrt, WritesEveryCurveAsABezierCylinderAndTheMeshes) {
  const Species s =
      formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml");
  GrowOptions o;
  o.quality = 0.1;
  const TreeGeometry g = build_tree_geometry(grow_weber_penn(s.weber_penn(), o));
  const std::string path = ::testing::TempDir() + "tree.pbrt";
  write_pbrt(g, s.bark, s.leaf, path);
  const std::string text = slurp(path);
  EXPECT_EQ(count(text, "Shape \"curve\""), g.curves.size());
  EXPECT_EQ(count(text, "\"string type\" \"cylinder\""), g.curves.size());
  EXPECT_EQ(count(text, "Shape \"trianglemesh\""), g.grids.grids.size() + 1);
  EXPECT_EQ(count(text, "AttributeBegin"), count(text, "AttributeEnd"));
  EXPECT_EQ(count(text, "["), count(text, "]"));
  EXPECT_EQ(count(text, "Material \"diffusetransmission\""), 1u);

  // The first curve's control points are the Hermite segment in Bézier form.
  const std::size_t at = text.find("\"point3 P\" [ ") + 13;
  std::istringstream numbers(text.substr(at, 400));
  std::vector<float> p(12);
  for (float& v : p) numbers >> v;
  const glm::vec4 p0 = g.curves.points[0], p1 = g.curves.points[1];
  const glm::vec4 b1 = p0 + g.curves.tangents[0] / 3.0f;
  EXPECT_FLOAT_EQ(p[0], p0.x);
  EXPECT_FLOAT_EQ(p[3], b1.x);
  EXPECT_FLOAT_EQ(p[5], b1.z);
  EXPECT_FLOAT_EQ(p[11], p1.z);
  std::remove(path.c_str());
}

// The ramiform's collars are exported (issue 45): after the trunk grids, one more triangle mesh
// in the bark's attribute block holding every collar vertex (the z-up positions and normals as
// built, to the digits pbrt reads) and triangle. Power: leaving the collars out, or writing
// their normals as positions, fails it.
TEST(ExportPbrt, TheRamiformsCollarsAreATriangleMesh) {
  const Species s =
      formats::load_species(std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen_ramiform.toml");
  GrowOptions o;
  o.seed = 5;
  const TreeGeometry g =
      build_tree_geometry(grow_weber_penn(s.weber_penn(), o), geometry_options_for(s));
  const RamiformSet& r = g.ramiforms;
  ASSERT_GT(r.triangle_count(), 1000u);
  const std::string path = ::testing::TempDir() + "ramiform.pbrt";
  write_pbrt(g, s.bark, s.leaf, path);
  const std::string text = slurp(path);
  std::remove(path.c_str());
  EXPECT_EQ(count(text, "Shape \"trianglemesh\""), g.grids.grids.size() + 1);
  // The collars' mesh: the last in the bark's block (the leafless aspen has no leaf mesh).
  const std::size_t at = text.rfind("Shape \"trianglemesh\"");
  ASSERT_LT(at, text.find("AttributeEnd", at));
  auto list = [&](const std::string& name) {
    const std::size_t from = text.find("\"" + name + "\" [ ", at) + name.size() + 5;
    std::istringstream in(text.substr(from, text.find(']', from) - from));
    std::vector<double> v;
    for (double x; in >> x;) v.push_back(x);
    return v;
  };
  const std::vector<double> p = list("point3 P"), n = list("normal N"),
                            idx = list("integer indices");
  ASSERT_EQ(p.size(), 3 * r.positions.size());
  ASSERT_EQ(n.size(), 3 * r.normals.size());
  ASSERT_EQ(idx.size(), r.indices.size());
  for (std::size_t i = 0; i < r.positions.size(); i += 101) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_FLOAT_EQ(static_cast<float>(p[3 * i + c]), r.positions[i][c]) << i;
      EXPECT_FLOAT_EQ(static_cast<float>(n[3 * i + c]), r.normals[i][c]) << i;
    }
  }
  for (std::size_t i = 0; i < r.indices.size(); i += 37) EXPECT_EQ(idx[i], r.indices[i]) << i;
}

}  // namespace arbor::generator
