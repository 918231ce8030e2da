// Tests of the pbrt-v4 export of a landscape: the terrain is its grid (a binary PLY read back
// against the built terrain) with its albedo baked, the surround and skirt beside it, and the
// rocks are object instances under their transforms.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "pbrt_reading.h"

namespace arbor::tracer {
namespace {

using namespace pbrt_reading;  // NOLINT: the tests' reader of pbrt files

// A binary little-endian PLY as pbrt-v4 reads ours: the counts, the vertices' eight floats and
// the faces' corners.
struct Ply {
  std::size_t vertices = 0, faces = 0;
  std::vector<float> vertex;           // x y z nx ny nz u v, each vertex
  std::vector<std::uint32_t> corners;  // three a face
};
Ply read_ply(const std::string& path) {
  Ply ply;
  const std::string bytes = slurp(path);
  const std::size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  if (end == std::string::npos) return ply;
  std::istringstream header(bytes.substr(0, end));
  std::string line, properties;
  while (std::getline(header, line)) {
    if (line.rfind("element vertex ", 0) == 0) ply.vertices = std::stoul(line.substr(15));
    if (line.rfind("element face ", 0) == 0) ply.faces = std::stoul(line.substr(13));
    if (line.rfind("property", 0) == 0) properties += line.substr(9) + ";";
  }
  EXPECT_EQ(properties,
            "float x;float y;float z;float nx;float ny;float nz;float u;float v;"
            "list uchar int vertex_indices;");
  const char* at = bytes.data() + end + 11;
  EXPECT_EQ(bytes.size() - (end + 11), ply.vertices * 32 + ply.faces * 13);
  if (bytes.size() - (end + 11) != ply.vertices * 32 + ply.faces * 13) return ply;
  ply.vertex.resize(ply.vertices * 8);
  std::memcpy(ply.vertex.data(), at, ply.vertices * 32);  // this machine is little-endian
  at += ply.vertices * 32;
  for (std::size_t f = 0; f < ply.faces; ++f, at += 13) {
    EXPECT_EQ(at[0], 3);
    for (int c = 0; c < 3; ++c) {
      std::uint32_t v;
      std::memcpy(&v, at + 1 + 4 * c, 4);
      ply.corners.push_back(v);
    }
  }
  return ply;
}

}  // namespace

TEST(PbrtExport, TheTerrainIsItsGridWithItsAlbedoAndTheRocksAreInstances) {
  const std::string dir = ::testing::TempDir() + "pbrt_terrain/";
  std::system(("mkdir -p " + dir).c_str());
  const std::string scene_path = dir + "scene.toml";
  std::ofstream(scene_path)
      << "[render]\nwidth = 40\nheight = 30\nspp = 4\n"
         "[camera]\nposition = [-40.0, -45.0, 2.0]\nabove_ground = 1.7\nlook_at = [0.0, 0.0, "
         "10.0]\n"
         "[sky]\nmodel = \"constant\"\ncolor = [0.5, 0.5, 0.5]\n"
         "[ground]\nalbedo = [0.2, 0.3, 0.1]\n"
         "[terrain]\nkind = \"mountains\"\nsize = 100\nrelief = 30\nresolution = 1\nseed = 5\n"
         "[rocks]\ndensity = 0.05\nsize_min = 0.5\nsize_max = 2\n";
  const std::string pbrt_out = dir + "scene.pbrt";
  export_scene(scene_path, pbrt_out, 16);
  const std::vector<Statement> pbrt = parse_pbrt(slurp(pbrt_out));
  const spec::SceneDesc desc = formats::load_scene(scene_path);
  const std::unique_ptr<const scene::Scene> built = scene::build_scene(desc, kOcioConfig);
  const scene::Terrain& t = built->terrain;
  const int nx = t.columns(), ny = t.rows();

  // The mesh: every vertex of the grid, the cells split as Embree splits them.
  const Statement* shape = find(pbrt, "Shape", "plymesh");
  ASSERT_NE(shape, nullptr);
  EXPECT_NE(std::find(shape->args.begin(), shape->args.end(), "scene.terrain.ply"),
            shape->args.end());
  const Ply ply = read_ply(dir + "scene.terrain.ply");
  ASSERT_EQ(ply.vertices, static_cast<std::size_t>(nx) * ny);
  ASSERT_EQ(ply.faces, 2u * (nx - 1) * (ny - 1));
  ASSERT_EQ(ply.corners.size(), 3 * ply.faces);
  for (std::size_t v = 0; v < ply.vertices; v += 97) {
    const glm::vec3 p = t.vertices()[v], n = t.normal(p.x, p.y);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(ply.vertex[8 * v + k], p[k]) << v;
      EXPECT_NEAR(ply.vertex[8 * v + 3 + k], n[k], 1e-6f) << v;
    }
    EXPECT_NEAR(ply.vertex[8 * v + 6], (p.x - t.origin().x) / t.extent().x, 1e-6) << v;
    EXPECT_NEAR(ply.vertex[8 * v + 7], (p.y - t.origin().y) / t.extent().y, 1e-6) << v;
  }
  // Any point of any face is on the surface Terrain::height states (what stands on it stands
  // on what pbrt renders), and faces turn up.
  for (std::size_t f = 0; f < ply.faces; f += 13) {
    glm::vec3 c[3];
    for (int k = 0; k < 3; ++k) {
      const float* q = &ply.vertex[8 * ply.corners[3 * f + k]];
      c[k] = glm::vec3(q[0], q[1], q[2]);
    }
    EXPECT_GT(glm::cross(c[1] - c[0], c[2] - c[0]).z, 0.0f) << f;
    const glm::vec3 inside = 0.5f * c[0] + 0.3f * c[1] + 0.2f * c[2];
    EXPECT_NEAR(inside.z, t.height(inside.x, inside.y), 2e-3) << f;
  }

  // The albedo: the ground's with soil and rock, each texel the mean of its 2 × 2 points, row 0
  // at +y; half floats.
  const Statement* texture = find(pbrt, "Texture", "terrain albedo");
  ASSERT_NE(texture, nullptr);
  EXPECT_NE(std::find(texture->args.begin(), texture->args.end(), "scene.terrain.exr"),
            texture->args.end());
  auto in = OIIO::ImageInput::open(dir + "scene.terrain.exr");
  ASSERT_TRUE(in);
  const OIIO::ImageSpec spec = in->spec();
  ASSERT_EQ(spec.width, 200);  // half the 1 m grid spacing over 100 m
  ASSERT_EQ(spec.height, 200);
  std::vector<float> px(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
  const materials::GroundMaterial& ground = *built->ground.as<materials::GroundMaterial>();
  int rock = 0, meadow = 0;
  for (int row = 0; row < 200; row += 7) {
    for (int column = 0; column < 200; column += 5) {
      glm::vec3 expected(0.0f);
      float rockiness = 0.0f;
      for (int s = 0; s < 4; ++s) {
        materials::SurfacePoint p;
        const double x = t.origin().x + (column + 0.25 + 0.5 * (s & 1)) * 0.5;
        const double y = t.origin().y + 100.0 - (row + 0.25 + 0.5 * (s >> 1)) * 0.5;
        p.ground = glm::vec2(static_cast<float>(x), static_cast<float>(y));
        p.terrain = t.cover(x, y);
        rockiness += p.terrain.y / 4.0f;
        expected += ground.albedo_at(p) / 4.0f;
      }
      const float* q = &px[(static_cast<std::size_t>(row) * 200 + column) * spec.nchannels];
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(q[k], expected[k], 2e-3f * expected[k] + 1e-5f) << row << "," << column;
      rock += rockiness > 0.99f;
      meadow += rockiness < 0.01f;
    }
  }
  EXPECT_GT(rock, 30);  // both in the sample, so a flipped image shows
  EXPECT_GT(meadow, 30);

  // The plane around it a millimetre below the lowest level (the surround's lowest point).
  bool plane = false;
  for (const Statement& s : pbrt) {
    if (s.directive != "Shape" || s.args.at(0) != "trianglemesh") continue;
    const std::vector<double> p = numbers(s, "point3 P");
    if (p.size() == 12 && p[0] == -1e4) {
      plane = true;
      EXPECT_NEAR(p[2], t.floor() - 0.001, 1e-5);
    }
  }
  EXPECT_TRUE(plane);
  // The surround as a mesh of its own, and the skirt that closes the seam.
  ASSERT_NE(t.surround(), nullptr);
  const Ply around = read_ply(dir + "scene.surround.ply");
  EXPECT_EQ(around.vertices,
            static_cast<std::size_t>(t.surround()->columns()) * t.surround()->rows());
  ASSERT_NE(find(pbrt, "Texture", "surround albedo"), nullptr);
  std::size_t skirt_points = 0;
  for (const Statement& s : pbrt) {
    if (s.directive != "Shape" || s.args.at(0) != "trianglemesh") continue;
    const std::vector<double> p = numbers(s, "point3 P");
    if (p.size() == 3 * t.skirt_positions().size()) skirt_points = p.size() / 3;
  }
  EXPECT_EQ(skirt_points, 4u * (nx - 1) * 4);

  // The rocks: each shape an object, each placement an instance of it under its transform.
  const scene::Rocks& rocks = built->rocks;
  ASSERT_GT(rocks.placements.size(), 50u);
  std::map<std::string, std::size_t> shapes;  // object → its points
  std::vector<std::pair<std::string, std::vector<double>>> instances;
  std::string object, transform_of_next;
  std::vector<double> transform;
  for (const Statement& s : pbrt) {
    if (s.directive == "ObjectBegin") object = s.args.at(0);
    if (s.directive == "ObjectEnd") object.clear();
    if (s.directive == "Shape" && object.rfind("rock", 0) == 0)
      shapes[object] = numbers(s, "point3 P").size() / 3;
    if (s.directive == "Transform") {
      transform.clear();
      for (const std::string& a : s.args)
        if (a != "[" && a != "]") transform.push_back(std::stod(a));
    }
    if (s.directive == "ObjectInstance" && s.args.at(0).rfind("rock", 0) == 0)
      instances.emplace_back(s.args.at(0), transform);
  }
  ASSERT_EQ(shapes.size(), rocks.shapes.size());
  for (std::size_t k = 0; k < rocks.shapes.size(); ++k)
    EXPECT_EQ(shapes["rock" + std::to_string(k + 1)], rocks.shapes[k].positions.size());
  ASSERT_EQ(instances.size(), rocks.placements.size());
  for (std::size_t i = 0; i < instances.size(); i += 7) {
    const scene::RockPlacement& r = rocks.placements[i];
    EXPECT_EQ(instances[i].first, "rock" + std::to_string(r.shape + 1));
    ASSERT_EQ(instances[i].second.size(), 16u);
    for (int c = 0; c < 16; ++c)
      EXPECT_NEAR(instances[i].second[c], r.to_world[c / 4][c % 4],
                  1e-5 * (1.0 + std::abs(r.to_world[c / 4][c % 4])))
          << i;
  }
  // Their material: the rock's mean, grey-green lichen on grey rock.
  const Statement* material = nullptr;
  for (const Statement& s : pbrt) {
    const std::string name = s.args.empty() ? "" : s.args[0];
    if (s.directive == "MakeNamedMaterial" && name.size() >= 5 &&
        name.compare(name.size() - 5, 5, "rocks") == 0)
      material = &s;
  }
  ASSERT_NE(material, nullptr);
  const std::vector<double> albedo = numbers(*material, "rgb reflectance");
  ASSERT_EQ(albedo.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(albedo[k], 0.25);
    EXPECT_LT(albedo[k], 0.40);
  }
}

}  // namespace arbor::tracer
