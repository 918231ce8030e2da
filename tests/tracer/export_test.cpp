// Tests of the pbrt-v4 scene writer (`arbor export`): pbrt-v4's equal-area map, the colour space,
// and a whole exported scene read back: its syntax, camera, lights, objects and the sky image's
// irradiance and orientation (the landscape's parts: export_landscape_test.cpp).
#include "tracer/pbrt_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "formats/scene_file.h"
#include "imaging/color.h"
#include "pbrt_reading.h"
#include "scene/scene.h"
#include "tracer/lights/sky.h"
#include "tracer/test_world.h"

namespace arbor::tracer {
namespace {

using namespace pbrt_reading;  // NOLINT: the tests' reader of pbrt files

constexpr double kPi = 3.14159265358979323846;

}  // namespace

TEST(PbrtExport, EqualAreaMapIsPbrtsAndKeepsAreas) {
  // Its fixed points: the centre is the zenith, the corners the nadir, the edges' middles the
  // horizon along ±x and ±y.
  const glm::vec3 up = equal_area_square_to_sphere({0.5f, 0.5f});
  EXPECT_NEAR(up.z, 1.0f, 1e-6f);
  EXPECT_NEAR(equal_area_square_to_sphere({0.0f, 0.0f}).z, -1.0f, 1e-6f);
  EXPECT_NEAR(equal_area_square_to_sphere({1.0f, 0.5f}).x, 1.0f, 1e-6f);
  EXPECT_NEAR(equal_area_square_to_sphere({0.5f, 1.0f}).y, 1.0f, 1e-6f);
  EXPECT_NEAR(equal_area_square_to_sphere({0.5f, 0.0f}).y, -1.0f, 1e-6f);
  // Equal areas: texel centres sample the sphere uniformly, so z and z² average 0 and 1/3, and
  // the upper hemisphere holds half of them.
  const int n = 256;
  double z = 0.0, z2 = 0.0, upper = 0.0, worst = 0.0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const glm::vec3 d = equal_area_square_to_sphere({(x + 0.5f) / n, (y + 0.5f) / n});
      worst = std::max(worst, std::fabs(static_cast<double>(glm::length(d)) - 1.0));
      z += d.z;
      z2 += d.z * d.z;
      upper += d.z > 0.0f ? 1.0 : d.z == 0.0f ? 0.5 : 0.0;  // the horizon: half above
    }
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_NEAR(z / (n * n), 0.0, 1e-4);
  EXPECT_NEAR(z2 / (n * n), 1.0 / 3.0, 1e-4);
  EXPECT_NEAR(upper / (n * n), 0.5, 1e-3);
}

TEST(PbrtExport, ColourSpacesPbrtKnowsAreKeptAndAcesCgBecomesAp0) {
  const std::vector<float> rec709 = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  const std::vector<float> ap1 = {0.713f, 0.293f, 0.165f,   0.830f,
                                  0.128f, 0.044f, 0.32168f, 0.33767f};
  EXPECT_STREQ(pbrt_color_space_for(rec709).name, "srgb");
  const PbrtColorSpace aces = pbrt_color_space_for(ap1);
  EXPECT_STREQ(aces.name, "aces2065-1");
  // AP1 → AP0 (same white): the ACES AP1-to-AP0 matrix's first column for AP1 red, white kept.
  const imaging::ColorTransform t = imaging::rgb_to_rgb(ap1, aces.chromaticities);
  float red[3] = {1.0f, 0.0f, 0.0f}, white[3] = {1.0f, 1.0f, 1.0f};
  t(red);
  t(white);
  EXPECT_NEAR(red[0], 0.6954522f, 1e-3f);
  EXPECT_NEAR(red[1], 0.0447946f, 1e-3f);
  EXPECT_NEAR(red[2], -0.0055259f, 1e-3f);
  for (float w : white) EXPECT_NEAR(w, 1.0f, 1e-4f);
}

TEST(PbrtExport, WritesTheWholeSceneAndASkyWithItsIrradiance) {
  const std::string dir = ::testing::TempDir() + "pbrt_export/";
  const std::string scene_path = dir + "scene.toml";
  std::remove((dir + "scene.pbrt").c_str());
  std::string text =
      "[render]\nwidth = 90\nheight = 120\nspp = 32\nmax_depth = 6\n"
      "[camera]\nposition = [12.0, -18.0, 2.5]\nlook_at = [0.0, 0.0, 5.0]\nfov = 40.0\nexposure = "
      "1.0\n"
      "[sun]\nelevation = 35.0\nazimuth = 120.0\nirradiance = 3.0\n"
      "[sky]\nmodel = \"preetham\"\nturbidity = 3.0\n"
      "[[tree]]\nspecies = \"" +
      std::string(ARBOR_SOURCE_DIR) +
      "/species/young_tree.skel\"\nposition = [0.0, 0.0, 0.0]\n"
      "[[tree]]\nspecies = \"" +
      std::string(ARBOR_SOURCE_DIR) +
      "/species/young_tree.skel\"\nposition = [4.0, 1.0, 0.0]\nrotation = 30.0\n"
      "[[tree]]\nspecies = \"" +
      std::string(ARBOR_SOURCE_DIR) +
      "/species/young_tree.skel\"\nposition = [-4.0, 1.0, 0.0]\n"
      "[tree.bark]\nalbedo = [0.2, 0.1, 0.05]\n";
  {
    std::system(("mkdir -p " + dir).c_str());
    std::ofstream(scene_path) << text;
  }
  const std::string pbrt_out = dir + "scene.pbrt";
  export_scene(scene_path, pbrt_out, 128);
  const std::vector<Statement> pbrt = parse_pbrt(slurp(pbrt_out));
  ASSERT_FALSE(pbrt.empty());

  EXPECT_EQ(find(pbrt, "ColorSpace")->args.at(0), "srgb");
  const Statement* look = find(pbrt, "LookAt");
  ASSERT_NE(look, nullptr);
  EXPECT_EQ(look->args,
            (std::vector<std::string>{"12", "-18", "2.5", "0", "0", "5", "0", "0", "1"}));
  // A portrait image: pbrt's fov spans the width, arbor's the height.
  const Statement* camera = find(pbrt, "Camera");
  ASSERT_NE(camera, nullptr);
  EXPECT_NEAR(numbers(*camera, "float fov").at(0),
              2.0 * std::atan(std::tan(20.0 * kPi / 180.0) * 90.0 / 120.0) * 180.0 / kPi, 1e-4);
  EXPECT_EQ(numbers(*find(pbrt, "Film"), "integer xresolution").at(0), 90);
  EXPECT_EQ(numbers(*find(pbrt, "Sampler"), "integer pixelsamples").at(0), 32);
  EXPECT_EQ(numbers(*find(pbrt, "Integrator"), "integer maxdepth").at(0), 6);
  EXPECT_EQ(count(pbrt, "AttributeBegin"), count(pbrt, "AttributeEnd"));
  EXPECT_EQ(count(pbrt, "ObjectBegin"), count(pbrt, "ObjectEnd"));
  // One tree grown once; the third's own bark makes a second object; three instances.
  EXPECT_EQ(count(pbrt, "ObjectBegin"), 2u);
  EXPECT_EQ(count(pbrt, "ObjectInstance"), 3u);
  bool dark_bark = false;
  for (const Statement& s : pbrt) {
    if (s.directive == "MakeNamedMaterial" &&
        numbers(s, "rgb reflectance") == std::vector<double>{0.2, 0.1, 0.05})
      dark_bark = true;
  }
  EXPECT_TRUE(dark_bark);

  // The sun: towards it, its irradiance, the exposure's 2× as the scale.
  const imaging::ColorPipeline color(kOcioConfig);
  spec::SceneDesc desc = formats::load_scene(scene_path);
  const Sky sky(desc.sky, desc.sun, color.xyz_to_scene_linear());
  const Statement* sun = find(pbrt, "LightSource", "distant");
  ASSERT_NE(sun, nullptr);
  const std::vector<double> from = numbers(*sun, "point3 from"), l = numbers(*sun, "rgb L");
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(from.at(k), sky.sun_direction()[k], 1e-6);
    EXPECT_NEAR(l.at(k), sky.sun_irradiance_color()[k], 1e-5);
  }
  EXPECT_EQ(numbers(*sun, "float scale").at(0), 2.0);

  // The sky image: square, its own colour space stated, and the map's irradiance on an upward
  // plane (each texel 4π/N² sr) that of arbor's sky; its brightest texel near the sun.
  const Statement* infinite = find(pbrt, "LightSource", "infinite");
  ASSERT_NE(infinite, nullptr);
  auto in = OIIO::ImageInput::open(dir + "scene.sky.exr");
  ASSERT_TRUE(in);
  const OIIO::ImageSpec spec = in->spec();
  ASSERT_EQ(spec.width, 128);
  ASSERT_EQ(spec.height, 128);
  EXPECT_NE(spec.find_attribute("chromaticities"), nullptr);
  // Linear, tagged as OIIO reads it (not "srgb", OIIO's sRGB curve), and no render attributes.
  EXPECT_EQ(spec.get_string_attribute("oiio:ColorSpace"), "Linear");
  EXPECT_EQ(spec.find_attribute("arbor:spp"), nullptr);
  EXPECT_EQ(spec.find_attribute("arbor:seed"), nullptr);
  std::vector<float> px(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
  glm::dvec3 e(0.0);
  double brightest = -1.0;
  glm::vec3 brightest_direction(0.0f);
  for (int y = 0; y < spec.height; ++y) {
    for (int x = 0; x < spec.width; ++x) {
      const glm::vec3 d =
          equal_area_square_to_sphere({(x + 0.5f) / spec.width, (y + 0.5f) / spec.height});
      const float* p = &px[(static_cast<std::size_t>(y) * spec.width + x) * spec.nchannels];
      if (d.z > 0.0f) e += glm::dvec3(p[0], p[1], p[2]) * static_cast<double>(d.z);
      // Below the horizon (the ground hides it) and on it (z = 0: texels the square's diamond runs
      // through) the horizon's radiance, never black: pbrt's bilinear lookup of the lowest sky
      // rows blends these in.
      if (d.z <= 0.0f) {
        const float across = std::hypot(d.x, d.y);
        const glm::vec3 h = glm::normalize(glm::vec3(d.x / across, d.y / across, 1e-4f));
        const glm::vec3 horizon =
            glm::max(sky.radiance(h), glm::vec3(0.0f));  // pbrt's srgb is scene_linear here
        EXPECT_GT(p[1], 0.0f) << x << "," << y;
        EXPECT_NEAR(p[1], horizon.y, 1e-3f * horizon.y + 1e-6f) << x << "," << y;
      }
      if (p[1] > brightest) {
        brightest = p[1];
        brightest_direction = d;
      }
    }
  }
  e *= 4.0 * kPi / (spec.width * spec.height);
  const glm::vec3 expected = sky.irradiance_up();
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(e[k], expected[k], 0.02 * expected[k]) << k;
  EXPECT_GT(glm::dot(glm::normalize(brightest_direction), sky.sun_direction()),
            std::cos(15.0 * kPi / 180.0));
}

// The ground's patches near the camera are an image pbrt reads as a texture: each texel is
// arbor's ground albedo at its place (row 0 at the square's +y edge, as pbrt's flipped v reads
// it), and the square sits on the camera; farther out, the patches' mean.
TEST(PbrtExport, GroundPatchesNearTheCameraAreAnImage) {
  const std::string dir = ::testing::TempDir() + "pbrt_ground/";
  std::system(("mkdir -p " + dir).c_str());
  const std::string scene_path = dir + "scene.toml";
  std::ofstream(scene_path)
      << "[render]\nwidth = 40\nheight = 30\nspp = 4\n"
         "[camera]\nposition = [12.4, -18.6, 2.5]\nlook_at = [0.0, 0.0, 1.0]\n"
         "[sky]\nmodel = \"constant\"\ncolor = [0.5, 0.5, 0.5]\n"
         "[ground]\nalbedo = [0.2, 0.15, 0.1]\npatch_albedo = [0.05, 0.1, 0.03]\n"
         "patch_cover = 0.5\npatch_scale = 4.0\n";
  const std::string pbrt_out = dir + "scene.pbrt";
  export_scene(scene_path, pbrt_out, 16);
  const std::vector<Statement> pbrt = parse_pbrt(slurp(pbrt_out));
  const Statement* texture = find(pbrt, "Texture", "ground patches");
  ASSERT_NE(texture, nullptr);
  EXPECT_NE(std::find(texture->args.begin(), texture->args.end(), "scene.ground.exr"),
            texture->args.end());

  auto in = OIIO::ImageInput::open(dir + "scene.ground.exr");
  ASSERT_TRUE(in);
  const OIIO::ImageSpec spec = in->spec();
  ASSERT_EQ(spec.width, 1024);
  EXPECT_EQ(spec.get_string_attribute("oiio:ColorSpace"), "Linear");
  std::vector<float> px(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));

  const spec::SceneDesc desc = formats::load_scene(scene_path);
  const std::unique_ptr<const scene::Scene> built = scene::build_scene(desc, kOcioConfig);
  ASSERT_NE(built->ground.as<materials::GroundMaterial>(), nullptr);
  const materials::GroundMaterial& ground = *built->ground.as<materials::GroundMaterial>();
  // The camera at (12.4, -18.6) puts the square's centre on (12, -19); 0.25 m texels.
  double mean = 0.0;
  int patched = 0, bare = 0;
  for (int row = 0; row < 1024; row += 37) {
    for (int column = 0; column < 1024; column += 41) {
      const glm::vec2 xy(12.0f - 128.0f + (column + 0.5f) * 0.25f,
                         -19.0f + 128.0f - (row + 0.5f) * 0.25f);
      const float w = ground.patch(xy);
      const glm::vec3 expected = ground.albedo + (ground.patch_albedo - ground.albedo) * w;
      const float* p = &px[(static_cast<std::size_t>(row) * 1024 + column) * spec.nchannels];
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(p[k], expected[k], 2e-3f * expected[k] + 1e-5f) << row << "," << column;
      patched += w > 0.99f;
      bare += w < 0.01f;
      mean += p[1];
    }
  }
  EXPECT_GT(patched, 50);  // both kinds of ground are in the sample, so orientation shows
  EXPECT_GT(bare, 50);
  // The mean ground beyond the square: between the two albedos.
  const Statement* outer = nullptr;
  for (const Statement& s : pbrt) {
    const std::string name = s.args.empty() ? "" : s.args[0];
    if (s.directive == "MakeNamedMaterial" && name.size() >= 6 &&
        name.compare(name.size() - 6, 6, "ground") == 0)
      outer = &s;
  }
  ASSERT_NE(outer, nullptr);
  const double g = numbers(*outer, "rgb reflectance").at(1);
  EXPECT_GT(g, 0.1);
  EXPECT_LT(g, 0.15);
}

}  // namespace arbor::tracer
