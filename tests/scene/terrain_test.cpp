// Tests of the terrain's height field (scene/terrain.h): the procedural models' range and
// determinism, an elevation image read north up with its own relief, the camera placed on it, and
// every bad elevation image refused at terrain.path with nothing built.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "formats/scene_file.h"
#include "scene/render_budget.h"
#include "scene/terrain.h"

namespace arbor::scene {
namespace {

std::string temp(const std::string& name) { return ::testing::TempDir() + name; }

// An EXR of `w` × `h` pixels whose pixel (x, y) is f(x, y).
template <class F>
std::string exr(const std::string& name, int w, int h, F f) {
  std::vector<float> px(static_cast<std::size_t>(w * h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) px[static_cast<std::size_t>(y * w + x)] = f(x, y);
  const std::string path = temp(name);
  auto out = OIIO::ImageOutput::create(path);
  EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(w, h, 1, OIIO::TypeDesc::FLOAT)) &&
              out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
  out->close();
  return path;
}

spec::SceneDesc scene_with(const std::string& terrain_table) {
  const std::string path = temp("terrain_scene.toml");
  std::ofstream(path) << terrain_table;
  return formats::load_scene(path);
}

TEST(Terrain, TheProceduralModelsSpanTheReliefAndRepeatBitForBit) {
  for (const char* kind : {"hills", "mountains"}) {
    spec::TerrainDesc d;
    d.enabled = true;
    d.kind = std::string(kind) == "hills" ? spec::TerrainKind::Hills : spec::TerrainKind::Mountains;
    d.size = 500;
    d.resolution = 5;
    d.relief = 80;
    d.surround = 0;  // (the surround: Terrain.TheSurroundContinuesTheModelToTheHorizon)
    const Terrain a(d), b(d);
    ASSERT_EQ(a.columns(), 101);
    float lo = 1e9f, hi = -1e9f;
    for (int j = 0; j < a.rows(); ++j)
      for (int i = 0; i < a.columns(); ++i) {
        lo = std::min(lo, a.at(i, j));
        hi = std::max(hi, a.at(i, j));
        ASSERT_EQ(a.at(i, j), b.at(i, j));
      }
    EXPECT_EQ(lo, 0.0f) << kind;
    EXPECT_NEAR(hi, 80.0f, 1e-4f) << kind;
    EXPECT_EQ(a.at(0, 50), 0.0f) << kind;  // the edges fall to the lowest level
    EXPECT_EQ(a.height(0.0, 0.0), a.at(50, 50)) << kind;
    EXPECT_EQ(a.height(400.0, 0.0), 0.0) << kind;  // outside: the plane's level
    d.seed = 2;
    EXPECT_NE(Terrain(d).at(50, 50), a.at(50, 50)) << kind;
  }
}

TEST(Terrain, AnElevationImageIsReadNorthUpWithItsOwnRelief) {
  // Heights rise to the east (x) and to the image's top row (north).
  const std::string dem =
      exr("dem.exr", 5, 3, [](int x, int y) { return 100.0f + 2.0f * x + 10.0f * (2 - y); });
  const spec::SceneDesc s = scene_with("[terrain]\nkind = \"image\"\npath = \"" + dem +
                                       "\"\nmetres_per_pixel = 10\nheight_scale = 0.5\n"
                                       "[camera]\nposition = [20, 10, 0]\nabove_ground = 1.5\n"
                                       "look_at = [0, 0, 0]\n");
  const Terrain t(s.terrain);
  ASSERT_EQ(t.columns(), 5);
  ASSERT_EQ(t.rows(), 3);
  EXPECT_EQ(t.extent(), glm::dvec2(40.0, 20.0));
  EXPECT_EQ(t.origin(), glm::dvec2(-20.0, -10.0));
  EXPECT_DOUBLE_EQ(t.relief(), 0.5 * (8.0 + 20.0));
  EXPECT_FLOAT_EQ(t.at(0, 0), 0.0f);           // south-west: the lowest
  EXPECT_FLOAT_EQ(t.at(4, 2), 14.0f);          // north-east: the highest
  EXPECT_NEAR(t.height(5.0, 0.0), 7.5, 1e-5);  // a plane (2.5 + 5): exact between the samples
  const spec::CameraDesc c = placed_camera(s.camera, t);
  EXPECT_NEAR(c.position[2], 14.0 + 1.5, 1e-6);
  EXPECT_NEAR(c.focus_distance, std::sqrt(20.0 * 20 + 10 * 10 + 15.5 * 15.5), 1e-9);
  EXPECT_EQ(terrain_vertices(s.terrain), 15u);
}

TEST(Terrain, BadElevationImagesAreRefusedAtThePath) {
  const std::string table = "[terrain]\nkind = \"image\"\npath = \"";
  testing::expect_input_error([&] { scene_with(table + temp("none.png") + "\"\n"); },
                              temp("terrain_scene.toml"), 3, 8, "does not exist");
  const std::string text = temp("text.png");
  std::ofstream(text) << "not an image\n";
  const spec::SceneDesc not_image = scene_with(table + text + "\"\n");
  testing::expect_input_error([&] { Terrain t(not_image.terrain); }, temp("terrain_scene.toml"), 3,
                              8, "cannot read the elevation image");
  // A PNG whose header says 100,000 × 100,000 pixels.
  const std::string huge = temp("huge.png");
  std::ofstream(huge, std::ios::binary) << std::string(
      "\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR\x00\x01\x86\xa0\x00\x01\x86\xa0\x10"
      "\x00\x00\x00\x00\xdd\xa9\x88\x57\x00\x00\x00\x0bIDATx\x9c\x63\x60\x80\x01"
      "\x00\x00\x0a\x00\x01\x7f\x80\x74\x5e\x00\x00\x00\x00IEND\xae\x42\x60\x82",
      69);
  const spec::SceneDesc big = scene_with(table + huge + "\"\n");
  testing::expect_input_error([&] { estimate_render_memory(big, {}); }, temp("terrain_scene.toml"),
                              3, 8, "100000x100000");
  const std::string nan =
      exr("nan.exr", 4, 4, [](int x, int y) { return x == 2 && y == 1 ? NAN : 1.0f; });
  const spec::SceneDesc holes = scene_with(table + nan + "\"\n");
  testing::expect_input_error([&] { Terrain t(holes.terrain); }, temp("terrain_scene.toml"), 3, 8,
                              "not finite, at (2, 1)");
}

// The surround continues the model beyond the square, coarser, to `surround` sides each way:
// across the square's edge the ground goes on (no fall to the plane; steps of its sinking margin
// and the detail the coarser grid misses), its normals turn little, its own outer tenth falls to
// its lowest level, where the plane lies; it is counted in the memory estimate and repeats bit for
// bit.
TEST(Terrain, TheSurroundContinuesTheModelToTheHorizon) {
  for (const char* kind : {"hills", "mountains"}) {
    SCOPED_TRACE(kind);
    spec::TerrainDesc d;
    d.enabled = true;
    d.kind = std::string(kind) == "hills" ? spec::TerrainKind::Hills : spec::TerrainKind::Mountains;
    d.size = 500;
    d.resolution = 2;
    d.relief = 80;
    const Terrain a(d), b(d);
    ASSERT_NE(a.surround(), nullptr);
    const Terrain& s = *a.surround();
    EXPECT_LE(s.origin().x, -250.0 - 4 * 500.0);
    EXPECT_GE(s.origin().x + s.extent().x, 250.0 + 4 * 500.0);
    EXPECT_GE(s.spacing(), 8 * a.spacing() - 1e-9);
    EXPECT_EQ(terrain_vertices(d), static_cast<std::size_t>(a.columns()) * a.rows() +
                                       static_cast<std::size_t>(s.columns()) * s.rows());
    // Across the edges, 1 cm either side: the same ground within the margin the surround is sunk
    // by (a fiftieth of the relief and half a metre) and the detail its coarser grid misses.
    double worst = 0.0, mean = 0.0, turn = 0.0;
    int n = 0;
    for (double u = -249.0; u <= 249.0; u += 7.3) {
      const double in = 250.0 - 0.01, out = 250.0 + 0.01;
      const double pairs[4][4] = {
          {u, in, u, out}, {u, -in, u, -out}, {in, u, out, u}, {-in, u, -out, u}};
      for (const auto& p : pairs) {
        const double step = std::abs(a.height(p[0], p[1]) - a.height(p[2], p[3]));
        worst = std::max(worst, step);
        mean += step;
        ++n;
        const double cosine = glm::dot(a.normal(p[0], p[1]), a.normal(p[2], p[3]));
        turn += std::acos(std::min(1.0, cosine)) * 180.0 / 3.14159265358979;
      }
    }
    mean /= n;
    turn /= n;
    // Measured: hills 0.67 m mean, 2.2 m worst, normals 8° apart; mountains (ridges finer than
    // the coarser grid) 1.2 m, 7.0 m, 22°. The margin alone is 0.65 m; without the surround
    // the edge falls to the plane, tens of metres.
    const double margin = 0.005 * 80 + 0.25;
    EXPECT_LT(mean, margin + (std::string(kind) == "hills" ? 0.5 : 1.0));
    EXPECT_LT(worst, 0.1 * 80);
    EXPECT_LT(turn, std::string(kind) == "hills" ? 10.0 : 25.0);
    std::printf("%s: step across the edge mean %.2f m, worst %.2f m; normals turn %.1f deg\n", kind,
                mean, worst, turn);
    // Inside the square its own surface; far out, the surround's outer tenth at the floor.
    EXPECT_EQ(a.height(10.0, 20.0), b.height(10.0, 20.0));
    EXPECT_LE(a.floor(), 0.0);
    const double far = s.origin().x + 1e-3;
    EXPECT_NEAR(a.height(far, 0.0), a.floor(), 1e-3);
    EXPECT_EQ(a.height(far - 100.0, 0.0), a.floor());  // beyond it all: the plane's level
    // And somewhere out there it rises and falls as hills do.
    double lo = 1e9, hi = -1e9;
    for (double x = 300.0; x < 1500.0; x += 10.0) {
      lo = std::min(lo, a.height(x, 100.0));
      hi = std::max(hi, a.height(x, 100.0));
    }
    EXPECT_GT(hi - lo, 10.0);
    for (int j = 0; j < s.rows(); j += 13)
      for (int i = 0; i < s.columns(); i += 11) ASSERT_EQ(s.at(i, j), b.surround()->at(i, j));
    ASSERT_EQ(a.skirt_indices().size(), 4u * (a.columns() - 1) * 6);
  }
}

}  // namespace
}  // namespace arbor::scene
