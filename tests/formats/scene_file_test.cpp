// Tests of the scene file loader: every key of the contract is read, paths resolve against the
// scene's folder, and every class of bad input is an InputError with file, line and column.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "expect_input_error.h"

#include "formats/scene_file.h"

namespace arbor::formats {

namespace {

void expect_error(const std::string& text, int line, int column, const std::string& fragment) {
  testing::expect_input_error([&] { parse_scene(text, "dir/s.toml"); }, "dir/s.toml", line, column,
                              fragment);
}

}  // namespace

TEST(SceneFile, ReadsTheContractsKeys) {
  const spec::SceneDesc s = parse_scene(R"(
[render]
width = 320
height = 200
spp = 16
seed = 9
integrator = "path"
max_depth = 5
[camera]
position = [1.0, 2.0, 3.0]
look_at = [0.0, 0.0, 1.0]
up = [0.0, 0.0, 1.0]
fov = 30.0
aperture_radius = 0.01
focus_distance = 4.0
exposure = -1.0
[sun]
elevation = 20.0
azimuth = 10.0
irradiance = 2.5
angular_diameter = 0.6
[sky]
model = "envmap"
path = "sky.exr"
rotation = 90.0
scale = 2.0
[ground]
enabled = false
albedo = [0.1, 0.2, 0.3]
[[tree]]
species = "trees/aspen.toml"
seed = 4
position = [1.0, 0.0, 0.0]
rotation = 45.0
scale = 1.5
time = 2.0
[tree.bark]
albedo = [0.3, 0.2, 0.1]
bump_height = 0.01
roughness = 20.0
[tree.leaf]
reflectance = [0.1, 0.2, 0.1]
cuticle_ior = 1.5
[[forest]]
species = "/abs/tupelo.toml"
count = 20
variants = 3
area = [[-5.0, -5.0], [5.0, 5.0]]
seed = 2
[[mesh]]
path = "m.obj"
up = "y"
[mesh.material.leafy]
kind = "leaf"
reflectance = [0.1, 0.1, 0.1]
transmittance = [0.2, 0.2, 0.2]
cuticle_roughness = 0.2
[output]
exr = "out/a.exr"
png = "out/a.png"
colorspace = "ACEScg"
display = "sRGB"
view = "Un-tone-mapped"
aovs = ["albedo", "variance"]
pixel_type = "float"
)",
                                        "dir/s.toml");
  EXPECT_EQ(s.render.width, 320);
  EXPECT_EQ(s.render.seed, 9u);
  EXPECT_DOUBLE_EQ(s.camera.focus_distance, 4.0);
  EXPECT_DOUBLE_EQ(s.sun.irradiance, 2.5);
  EXPECT_EQ(s.sky.path, "dir/sky.exr");  // relative to the scene file
  EXPECT_FALSE(s.ground.enabled);
  ASSERT_EQ(s.trees.size(), 1u);
  EXPECT_EQ(s.trees[0].species, "dir/trees/aspen.toml");
  EXPECT_DOUBLE_EQ(*s.trees[0].bark.roughness, 20.0);
  EXPECT_DOUBLE_EQ((*s.trees[0].leaf.reflectance)[1], 0.2);
  EXPECT_FALSE(s.trees[0].leaf.transmittance.has_value());
  EXPECT_DOUBLE_EQ(*s.trees[0].leaf.cuticle_ior, 1.5);
  EXPECT_FALSE(s.trees[0].leaf.cuticle_roughness.has_value());  // the species' own
  EXPECT_DOUBLE_EQ(s.meshes[0].materials.at("leafy").cuticle_roughness, 0.2);
  EXPECT_DOUBLE_EQ(s.meshes[0].materials.at("leafy").cuticle_ior, 1.45);
  EXPECT_EQ(s.forests[0].species, "/abs/tupelo.toml");
  EXPECT_DOUBLE_EQ(s.forests[0].area[2], 5.0);
  EXPECT_EQ(s.meshes[0].materials.at("leafy").kind, "leaf");
  EXPECT_EQ(s.output.exr, "dir/out/a.exr");
  EXPECT_EQ(s.output.aovs.text(), "albedo variance");
}

TEST(SceneFile, FocusDistanceDefaultsToTheLookAtPoint) {
  const spec::SceneDesc s =
      parse_scene("[camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [3.0, 4.0, 0.0]\n", "s.toml");
  EXPECT_DOUBLE_EQ(s.camera.focus_distance, 5.0);
}

TEST(SceneFile, ReadsTheTreemakerKeys) {
  const spec::SceneDesc s = parse_scene(R"([render]
integrator = "treemaker"
treemaker_spp = 2
[[tree]]
species = "a.tmpl"
[tree.treemaker]
ambient = 0.2
angle = 0.0
[[forest]]
species = "b.toml"
[forest.treemaker]
lambert = 1.5
[output]
aovs = ["treemaker", "albedo"]
)",
                                        "dir/s.toml");
  EXPECT_EQ(s.render.integrator, spec::Integrator::Treemaker);
  EXPECT_EQ(s.render.treemaker_spp, 2);
  EXPECT_EQ(s.render.spp, 64);  // the path integrator's count is separate
  EXPECT_DOUBLE_EQ(*s.trees[0].treemaker.ambient, 0.2);
  EXPECT_DOUBLE_EQ(*s.trees[0].treemaker.angle, 0.0);
  EXPECT_FALSE(s.trees[0].treemaker.lambert.has_value());  // unset weights keep the template's
  EXPECT_DOUBLE_EQ(*s.forests[0].treemaker.lambert, 1.5);
  EXPECT_TRUE(s.output.aovs.has(imaging::Aov::Treemaker));
  expect_error("[[tree]]\nspecies = \"a.toml\"\n[tree.treemaker]\nshadow = 1\n", 4, 1,
               "unknown key 'shadow' in [tree.treemaker]");
  expect_error("[[tree]]\nspecies = \"a.toml\"\n[tree.treemaker]\nheight = -0.1\n", 4, 10,
               "tree.treemaker.height = -0.1 is out of range [0, 10]");
  expect_error("[[forest]]\nspecies = \"a.toml\"\n[forest.treemaker]\nradius = nan\n", 4, 10,
               "finite");
  expect_error("[render]\ntreemaker_spp = 0\n", 2, 17, "render.treemaker_spp");
}

TEST(SceneFile, UnknownKeysAndTablesAreErrors) {
  expect_error("[camera]\nzoom = 2\n", 2, 1, "unknown key 'zoom' in [camera]");
  expect_error("[lights]\n", 1, 2, "unknown table or key 'lights'");
  expect_error("[[tree]]\nspecies = \"a.toml\"\ncolour = 1\n", 3, 1, "unknown key 'colour'");
  expect_error("[[tree]]\nspecies = \"a.toml\"\n[tree.bark]\nshine = 1\n", 4, 1,
               "unknown key 'shine' in [tree.bark]");
}

TEST(SceneFile, ValuesAreRangeAndTypeChecked) {
  expect_error("[render]\nwidth = 0\n", 2, 9, "render.width = 0 is out of range");
  expect_error("[render]\nspp = 1.5\n", 2, 7, "whole number");
  expect_error("[render]\nintegrator = \"bdpt\"\n", 2, 14, "one of \"path\", \"treemaker\"");
  expect_error("[render]\nregularize = 1\n", 2, 14, "true or false");
  expect_error("[[tree]]\nspecies = \"a.toml\"\n[tree.leaf]\nseason = \"winter\"\n", 4, 10,
               "tree.leaf.season must be one of \"summer\", \"spring\", \"autumn\"");
  EXPECT_TRUE(parse_scene("[render]\nregularize = true\n", "s.toml").render.regularize);
  EXPECT_FALSE(parse_scene("", "s.toml").render.regularize);
  expect_error("[render]\nlod = \"on\"\n", 2, 7, "true or false");
  expect_error("[render]\nlod_quality = 0.0\n", 2, 15, "render.lod_quality = 0 is out of range");
  expect_error("[render]\nlod_quality = inf\n", 2, 15, "finite");
  EXPECT_FALSE(parse_scene("", "s.toml").render.lod);
  EXPECT_DOUBLE_EQ(
      parse_scene("[render]\nlod = true\nlod_quality = 2.5\n", "s.toml").render.lod_quality, 2.5);
  expect_error("[camera]\nfov = 200.0\n", 2, 7, "camera.fov");
  expect_error("[camera]\nposition = [1.0, 2.0]\n", 2, 12, "array of 3 numbers");
  expect_error("[camera]\nfov = nan\n", 2, 7, "finite");
  expect_error("[sun]\nirradiance = -1.0\n", 2, 14, "out of range");
  expect_error("[ground]\nalbedo = [0.5, 1.5, 0.5]\n", 2, 16, "ground.albedo");
  expect_error("[ground]\nenabled = 1\n", 2, 11, "true or false");
  expect_error("[ground]\npatch_cover = 1.5\n", 2, 15, "ground.patch_cover");
  expect_error("[ground]\npatch_scale = 0\n", 2, 15, "ground.patch_scale");
  expect_error("[ground]\npatch_albedo = [0.1, 0.1]\n", 2, 16, "ground.patch_albedo");
  expect_error("[[tree]]\nspecies = \"a.toml\"\n[tree.leaf]\ncuticle_ior = 0.5\n", 4, 15,
               "tree.leaf.cuticle_ior");
  expect_error("[[forest]]\nspecies = \"a.toml\"\n[forest.leaf]\ncuticle_roughness = -0.1\n", 4, 21,
               "forest.leaf.cuticle_roughness");
  expect_error("[output]\naovs = [\"albedo\", \"motion\"]\n", 2, 19, "output.aovs");
}

// [meadow]: its keys read, each range-checked at its position, a blade that would create light
// and a meadow too large for memory refused at the table.
TEST(SceneFile, MeadowKeysAreReadAndChecked) {
  const spec::SceneDesc s = parse_scene(
      "[meadow]\ndensity = 800\narea = [[-5.0, -4.0], [6.0, 7.0]]\nheight = 0.4\n"
      "clumping = 0.2\ndry = 0.1\nwind = 3.0\ntile = 2.0\ntiles = 8\nseed = 9\n",
      "s.toml");
  EXPECT_EQ(s.meadow.density, 800.0);
  EXPECT_EQ(s.meadow.area, (std::array<double, 4>{-5.0, -4.0, 6.0, 7.0}));
  EXPECT_EQ(s.meadow.height, 0.4);
  EXPECT_EQ(s.meadow.tiles, 8);
  EXPECT_EQ(s.meadow.seed, 9u);
  EXPECT_EQ(parse_scene("", "s.toml").meadow.density, 0.0);  // no [meadow]: no grass
  expect_error("[meadow]\ndensity = -1\n", 2, 11, "meadow.density");
  expect_error("[meadow]\nheight = 0\n", 2, 10, "meadow.height");
  expect_error("[meadow]\nblades = 3\n", 2, 1, "unknown key 'blades' in [meadow]");
  expect_error("[meadow]\narea = [[1.0, 0.0], [0.0, 1.0]]\n", 2, 8, "smaller corner");
  expect_error("[meadow]\nreflectance = [0.5, 0.5, 0.5]\ntransmittance = [0.6, 0.1, 0.1]\n", 1, 1,
               "would create light");
  expect_error("[meadow]\ndensity = 50000\narea = [[-1e4, -1e4], [1e4, 1e4]]\n", 1, 1, "10⁹");
}

TEST(SceneFile, StructuralRulesAreChecked) {
  expect_error("[sky]\nmodel = \"envmap\"\n", 1, 1, "needs sky.path");
  expect_error("[[tree]]\nseed = 3\n", 1, 1, "needs a species");
  expect_error("[[forest]]\nspecies = \"a.toml\"\narea = [[5.0, 5.0], [-5.0, -5.0]]\n", 3, 8,
               "smaller corner");
  expect_error("[[forest]]\nspecies = \"a.toml\"\ncount = 2\nvariants = 3\n", 1, 1,
               "must not exceed");
  expect_error(
      "[[mesh]]\npath = \"m.obj\"\n[mesh.material.x]\nkind = \"leaf\"\nreflectance = [0.6, 0.6, "
      "0.6]\n"
      "transmittance = [0.6, 0.6, 0.6]\n",
      3, 1, "at most 1");
  expect_error("tree = 3\n", 1, 8, "array of tables");
  expect_error("[render\n", 1, 8, "");
}

// Camera, output-extension and colour errors once named no file or position and surfaced only
// when rendering started; the loader finds them, at the key.
TEST(SceneFile, CameraAndOutputErrorsAreFoundWithTheirKey) {
  expect_error("[camera]\nposition = [1.0, 2.0, 3.0]\nlook_at = [1.0, 2.0, 3.0]\n", 3, 11,
               "camera.look_at must differ from camera.position");
  expect_error("[camera]\nposition = [0.0, 0.0, 6.0]\n", 2, 12,
               "must differ");  // the default look_at
  expect_error(
      "[camera]\nposition = [0.0, 0.0, 1.0]\nlook_at = [0.0, 0.0, 5.0]\nup = [0.0, 0.0, 2.0]\n", 4,
      6, "camera.up must not be parallel");
  expect_error("[camera]\nup = [0.0, 0.0, 0.0]\n", 2, 6, "camera.up must not be parallel");
  expect_error("[output]\nexr = \"out/a.png\"\n", 2, 7, "output.exr must name a .exr file");
  expect_error("[output]\npng = \"out/a.exr\"\n", 2, 7, "output.png must name a .png file");
}

// The atmosphere sky's keys: the aerosols by one of three keys, the ground's albedo by default
// from [ground], and the keys that belong to it refused elsewhere, at the key.
TEST(SceneFile, TheAtmosphereSkysKeys) {
  const spec::SceneDesc a = parse_scene(
      "[sky]\nmodel = \"atmosphere\"\nvisibility = 40.0\n[ground]\nalbedo = [0.2, 0.2, 0.2]\n",
      "s.toml");
  EXPECT_EQ(a.sky.model, spec::SkyModel::Atmosphere);
  EXPECT_DOUBLE_EQ(a.sky.visibility, 40.0);
  EXPECT_FALSE(a.sky.turbidity_given);
  EXPECT_FALSE(a.sky.dust_given);
  EXPECT_NEAR(a.sky.ground_albedo, 0.2, 1e-12);  // [ground]'s, no patches
  const spec::SceneDesc b = parse_scene(
      "[sky]\nmodel = \"atmosphere\"\nturbidity = 4.0\nground_albedo = 0.3\n[ground]\n"
      "patch_cover = 0.5\n",
      "s.toml");
  EXPECT_TRUE(b.sky.turbidity_given);
  EXPECT_DOUBLE_EQ(b.sky.ground_albedo, 0.3);  // given: [ground] does not matter
  // Half soil, half grass: the mean of the two luminances.
  const spec::SceneDesc c = parse_scene("[ground]\npatch_cover = 0.5\n", "s.toml");
  const spec::GroundDesc g;
  auto y = [](const Rgb& v) { return 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2]; };
  EXPECT_NEAR(c.sky.ground_albedo, 0.5 * (y(g.albedo) + y(g.patch_albedo)), 1e-12);

  expect_error("[sky]\nmodel = \"atmosphere\"\nturbidity = 3.0\nvisibility = 30.0\n", 4, 14,
               "give the aerosols once");
  expect_error("[sky]\nmodel = \"atmosphere\"\ndust_density = 2.0\nturbidity = 3.0\n", 4, 13,
               "give the aerosols once");
  expect_error("[sky]\nmodel = \"atmosphere\"\nturbidity = 2.0\n", 3, 13, "at least 2.21");
  expect_error("[sky]\nmodel = \"nishita\"\nvisibility = 30.0\n", 3, 14,
               "belongs to sky.model = \"atmosphere\"");
  expect_error("[sky]\nground_albedo = 0.2\n", 2, 17, "belongs to sky.model");
  expect_error("[sky]\nmodel = \"atmosphere\"\nvisibility = 500.0\n", 3, 14, "sky.visibility");
  expect_error("[sky]\nmodel = \"atmosphere\"\nground_albedo = 1.5\n", 3, 17, "sky.ground_albedo");
  // Preetham's turbidity keeps its own range.
  EXPECT_NO_THROW(parse_scene("[sky]\nturbidity = 2.0\n", "s.toml"));
}

// Aerial perspective: off unless asked; it needs the air of the atmosphere or nishita sky and the
// path integrator, refused at the key otherwise.
TEST(SceneFile, AerialPerspectiveNeedsAnAtmosphereAndThePathIntegrator) {
  EXPECT_FALSE(parse_scene("", "s.toml").render.aerial_perspective);
  EXPECT_TRUE(
      parse_scene("[render]\naerial_perspective = true\n[sky]\nmodel = \"atmosphere\"\n", "s.toml")
          .render.aerial_perspective);
  EXPECT_NO_THROW(
      parse_scene("[sky]\nmodel = \"nishita\"\n[render]\naerial_perspective = true\n", "s.toml"));
  expect_error("[render]\naerial_perspective = true\n", 2, 22, "needs sky.model = \"atmosphere\"");
  expect_error(
      "[render]\naerial_perspective = true\nintegrator = \"treemaker\"\n[sky]\n"
      "model = \"atmosphere\"\n",
      2, 22, "needs render.integrator = \"path\"");
  expect_error("[render]\naerial_perspective = 1\n", 2, 22, "true or false");
}

TEST(SceneFile, ExposureIsStopsOrAuto) {
  EXPECT_TRUE(parse_scene("[camera]\nexposure = \"auto\"\n", "s.toml").camera.auto_exposure);
  const spec::SceneDesc fixed = parse_scene("[camera]\nexposure = 1.5\n", "s.toml");
  EXPECT_FALSE(fixed.camera.auto_exposure);
  EXPECT_DOUBLE_EQ(fixed.camera.exposure, 1.5);
  expect_error("[camera]\nexposure = \"bright\"\n", 2, 12, "a number of stops or \"auto\"");
  expect_error("[camera]\nexposure = true\n", 2, 12, "camera.exposure");
}

}  // namespace arbor::formats

namespace arbor::formats {

// The ground's detail keys (issue 29): read with their values, refused out of range at the key.
TEST(SceneFile, GroundDetailKeysAreReadAndCheckedAtTheKey) {
  const spec::SceneDesc s = parse_scene(
      "[ground]\ndetail = 0.6\nstones = 8.0\nstone_albedo = [0.3, 0.3, 0.3]\nlitter = 0.2\n"
      "litter_albedo = [0.2, 0.1, 0.05]\n",
      "s.toml");
  EXPECT_EQ(s.ground.detail, 0.6);
  EXPECT_EQ(s.ground.stones, 8.0);
  EXPECT_EQ(s.ground.litter, 0.2);
  EXPECT_EQ(s.ground.litter_albedo[2], 0.05);
  for (const char* bad :
       {"detail = 1.01", "stones = -1", "litter = 2", "stone_albedo = [2, 0, 0]"}) {
    try {
      parse_scene(std::string("[ground]\n") + bad + "\n", "s.toml");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("s.toml:2:"), std::string::npos) << e.what();
    }
  }
}

}  // namespace arbor::formats

namespace arbor::formats {

// scenes/default_treemaker.toml is the default scene rendered by TREE-MAKER's shading (the
// README's worked example of --fit-treemaker): every table but [render] and [output] is
// default.toml's, line for line, and both read to the same camera, light and trees.
TEST(Scenes, TheTreemakerSceneIsTheDefaultScene) {
  const std::string folder = std::string(ARBOR_SOURCE_DIR) + "/scenes/";
  // The text from the [camera] header to the [output] header.
  const auto middle = [](const std::string& path) {
    std::ifstream in(path);
    std::string text, line;
    bool inside = false;
    while (std::getline(in, line)) {
      if (line.rfind("[camera]", 0) == 0) inside = true;
      if (line.rfind("[output]", 0) == 0) inside = false;
      if (inside) text += line + "\n";
    }
    return text;
  };
  const std::string exact = middle(folder + "default.toml");
  ASSERT_NE(exact.find("[meadow]"), std::string::npos);
  EXPECT_EQ(middle(folder + "default_treemaker.toml"), exact);
  const spec::SceneDesc a = load_scene(folder + "default.toml"),
                        b = load_scene(folder + "default_treemaker.toml");
  EXPECT_EQ(b.render.integrator, spec::Integrator::Treemaker);
  EXPECT_EQ(a.render.width, b.render.width);
  EXPECT_EQ(a.render.height, b.render.height);
  EXPECT_EQ(a.sun.elevation, b.sun.elevation);
  EXPECT_EQ(a.sun.azimuth, b.sun.azimuth);
  EXPECT_EQ(a.meadow.density, b.meadow.density);
  EXPECT_EQ(a.trees.size(), b.trees.size());
}

}  // namespace arbor::formats
