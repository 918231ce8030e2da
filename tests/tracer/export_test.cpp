// Tests of the pbrt-v4 scene writer (`arbor export`): pbrt-v4's equal-area map, the colour space,
// and a whole exported scene read back: its syntax, camera, lights, objects and the sky image's
// irradiance and orientation.
#include "tracer/pbrt_scene.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "imaging/color.h"
#include "scene/scene.h"
#include "tracer/lights/sky.h"
#include "tracer/test_world.h"

namespace arbor::tracer {
namespace {

constexpr double kPi = 3.14159265358979323846;

// `arbor export`'s library part: the scene built, then written as pbrt-v4 sees it.
void export_scene(const std::string& scene_path, const std::string& out, int sky_resolution) {
  const formats::SceneDesc desc = formats::load_scene(scene_path);
  write_pbrt_scene(*scene::build_scene(desc, kOcioConfig), scene::render_input(desc),
                   imaging::ColorPipeline(kOcioConfig), out, sky_resolution);
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A pbrt-v4 file as statements: a directive and its arguments (quoted strings, numbers, or
// bracketed lists); comments dropped. Fails the test on anything pbrt's tokenizer would refuse.
struct Statement {
  std::string directive;
  std::vector<std::string> args;  // strings without their quotes; a list as "[", items, "]"
};
std::vector<Statement> parse_pbrt(const std::string& text) {
  std::vector<std::string> tokens;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '#') {
      i = text.find('\n', i);
      if (i == std::string::npos) break;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '"') {
      const std::size_t end = text.find('"', i + 1);
      EXPECT_NE(end, std::string::npos) << "unterminated string at " << i;
      if (end == std::string::npos) break;
      tokens.push_back("\"" + text.substr(i + 1, end - i - 1));
      i = end + 1;
    } else if (c == '[' || c == ']') {
      tokens.emplace_back(1, c);
      ++i;
    } else {
      std::size_t end = i;
      while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])) &&
             text[end] != '[' && text[end] != ']' && text[end] != '"')
        ++end;
      tokens.push_back(text.substr(i, end - i));
      i = end;
    }
  }
  std::vector<Statement> out;
  int depth = 0;
  for (const std::string& t : tokens) {
    const bool word = std::isalpha(static_cast<unsigned char>(t[0])) && t != "true" && t != "false";
    if (word && depth == 0) {
      out.push_back({t, {}});
      continue;
    }
    EXPECT_FALSE(out.empty()) << "argument before any directive: " << t;
    if (out.empty()) continue;
    if (t == "[") ++depth;
    if (t == "]") --depth;
    EXPECT_GE(depth, 0);
    EXPECT_LE(depth, 1) << "nested list";
    if (t[0] != '"' && t != "[" && t != "]") {
      char* end = nullptr;
      std::strtod(t.c_str(), &end);
      EXPECT_EQ(*end, '\0') << "not a number: " << t << " in " << out.back().directive;
    }
    out.back().args.push_back(t[0] == '"' ? t.substr(1) : t);
  }
  EXPECT_EQ(depth, 0);
  const std::set<std::string> known = {"ColorSpace",
                                       "Scale",
                                       "LookAt",
                                       "Camera",
                                       "Film",
                                       "PixelFilter",
                                       "Sampler",
                                       "Integrator",
                                       "WorldBegin",
                                       "LightSource",
                                       "MakeNamedMaterial",
                                       "NamedMaterial",
                                       "Material",
                                       "ObjectBegin",
                                       "ObjectEnd",
                                       "ObjectInstance",
                                       "AttributeBegin",
                                       "AttributeEnd",
                                       "Shape",
                                       "Transform",
                                       "Texture"};
  const std::set<std::string> types = {"float", "integer", "point3", "point2", "normal",
                                       "rgb",   "string",  "bool",   "texture"};
  for (const Statement& s : out) {
    EXPECT_TRUE(known.count(s.directive)) << s.directive;
    // Parameter lists: "type name" then one value or a bracketed list.
    std::size_t i = 0;
    if (s.directive == "Camera" || s.directive == "Film" || s.directive == "PixelFilter" ||
        s.directive == "Sampler" || s.directive == "Integrator" || s.directive == "LightSource" ||
        s.directive == "Shape" || s.directive == "MakeNamedMaterial" || s.directive == "Material" ||
        s.directive == "Texture") {
      i = s.directive == "Texture" ? 3 : 1;  // Texture "name" "type" "class" params
      while (i < s.args.size()) {
        const std::string& decl = s.args[i];
        const std::size_t space = decl.find(' ');
        EXPECT_NE(space, std::string::npos)
            << s.directive << ": parameter without a type: " << decl;
        if (space == std::string::npos) break;
        EXPECT_TRUE(types.count(decl.substr(0, space))) << s.directive << ": type of " << decl;
        ++i;
        if (i < s.args.size() && s.args[i] == "[") {
          while (i < s.args.size() && s.args[i] != "]") ++i;
        }
        ++i;
      }
    }
  }
  return out;
}

std::vector<double> numbers(const Statement& s, const std::string& param) {
  std::vector<double> v;
  for (std::size_t i = 0; i < s.args.size(); ++i) {
    if (s.args[i] != param) continue;
    ++i;
    const bool list = s.args[i] == "[";
    for (i += list ? 1 : 0; i < s.args.size() && s.args[i] != "]"; ++i) {
      v.push_back(std::stod(s.args[i]));
      if (!list) break;
    }
    break;
  }
  return v;
}

const Statement* find(const std::vector<Statement>& all, const std::string& directive,
                      const std::string& first = "") {
  for (const Statement& s : all) {
    if (s.directive == directive && (first.empty() || (!s.args.empty() && s.args[0] == first)))
      return &s;
  }
  return nullptr;
}

std::size_t count(const std::vector<Statement>& all, const std::string& directive) {
  std::size_t n = 0;
  for (const Statement& s : all) n += s.directive == directive;
  return n;
}

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
  formats::SceneDesc desc = formats::load_scene(scene_path);
  const Sky sky(scene::sky_spec(desc.sky), scene::sun_spec(desc.sun), color.xyz_to_scene_linear());
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

}  // namespace arbor::tracer

namespace arbor::tracer {

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

  const formats::SceneDesc desc = formats::load_scene(scene_path);
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
  const formats::SceneDesc desc = formats::load_scene(scene_path);
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
