// Tests of the scene file's key tables: the reference page is theirs, a key of another sky model
// is refused at its position, and the settings' text holds every [render] key at full precision.
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "expect_scene_error.h"

#include "formats/scene_file.h"

namespace arbor::formats {

// docs/scene-format.md is what the tables say. ARBOR_WRITE_REFERENCE=1 rewrites it.
TEST(SceneKeys, TheReferencePageIsTheTables) {
  const std::string path = std::string(ARBOR_SOURCE_DIR) + "/docs/scene-format.md";
  const std::string generated = scene_key_reference();
  if (std::getenv("ARBOR_WRITE_REFERENCE")) std::ofstream(path) << generated;
  std::ifstream in(path);
  std::stringstream page;
  page << in.rdbuf();
  EXPECT_EQ(page.str(), generated)
      << "docs/scene-format.md is stale: ARBOR_WRITE_REFERENCE=1 build/tests/formats_tests "
         "--gtest_filter=SceneKeys.TheReferencePageIsTheTables rewrites it";
  // Every table and a sample of keys, with their ranges and defaults.
  for (const char* line :
       {"## [render]", "## [sky]", "## [[tree]]", "## [mesh.material.NAME]", "## [animation]",
        "| `width` | integer | [1, 16384] pixels | 960 |", "| `aperture_radius` | number |",
        "| `turbidity` | number | [1.7, 10] | 3 |", "| `rotation` | number | [-360, 360] degrees",
        "| `seed` | integer | ≥ 0 | 1 |"}) {
    EXPECT_NE(generated.find(line), std::string::npos) << line;
  }
}

// The same for the integrators: the treemaker's samples with the path integrator (the default),
// adaptive sampling and regularisation with the treemaker's; each integrator's own keys are read.
TEST(SceneKeys, AKeyOfAnotherIntegratorIsAnErrorAtIt) {
  expect_scene_error("[render]\ntreemaker_spp = 8\n", 2, 17,
                     "render.treemaker_spp belongs to render.integrator = \"treemaker\", not "
                     "\"path\"");
  expect_scene_error("[render]\nintegrator = \"treemaker\"\nnoise_threshold = 0.05\n", 3, 19,
                     "render.noise_threshold belongs to render.integrator = \"path\"");
  expect_scene_error("[render]\nmin_spp = 4\nintegrator = \"treemaker\"\n", 2, 11,
                     "not \"treemaker\"");
  expect_scene_error("[render]\nintegrator = \"treemaker\"\nregularize = true\n", 3, 14,
                     "render.regularize belongs to render.integrator = \"path\"");
  const spec::SceneDesc t = parse_scene(
      "[render]\nintegrator = \"treemaker\"\ntreemaker_spp = 8\nmax_depth = 3\n", "s.toml");
  EXPECT_EQ(t.render.treemaker_spp, 8);
  EXPECT_EQ(t.render.max_depth, 3);
  EXPECT_DOUBLE_EQ(
      parse_scene("[render]\nnoise_threshold = 0.05\n", "s.toml").render.noise_threshold, 0.05);
}

TEST(SceneKeys, AKeyOfAnotherSkyModelIsAnErrorAtIt) {
  expect_scene_error("[sky]\nmodel = \"constant\"\nturbidity = 9.5\n", 3, 13,
                     "sky.turbidity belongs to sky.model = \"preetham\" or \"atmosphere\", not "
                     "\"constant\"");
  expect_scene_error("[sky]\nmodel = \"constant\"\nrotation = 30\n", 3, 12,
                     "sky.rotation belongs to sky.model = \"envmap\"");
  expect_scene_error("[sky]\nmodel = \"preetham\"\ncolor = [1, 1, 1]\n", 3, 9,
                     "belongs to sky.model = \"constant\", not \"preetham\"");
  expect_scene_error("[sky]\nmodel = \"preetham\"\nair_density = 2\n", 3, 15,
                     "\"nishita\" or \"atmosphere\"");
  // The default model is preetham's.
  expect_scene_error("[sky]\ndust_density = 2\n", 2, 16, "not \"preetham\"");
  // A model's own keys are read.
  const spec::SceneDesc s = parse_scene(
      "[sky]\nmodel = \"nishita\"\nair_density = 2\ndust_density = 0.5\naltitude = 1000\n",
      "s.toml");
  EXPECT_DOUBLE_EQ(s.sky.air_density, 2.0);
  EXPECT_DOUBLE_EQ(s.sky.dust_density, 0.5);
  EXPECT_DOUBLE_EQ(s.sky.altitude, 1000.0);
  EXPECT_DOUBLE_EQ(
      parse_scene("[sky]\nmodel = \"envmap\"\npath = \"a.exr\"\nrotation = 30\n", "s.toml")
          .sky.rotation,
      30.0);
}

// The fingerprint's settings: every [render] key, each value exactly (two times or qualities
// that differ past the sixth decimal differ in it).
TEST(SceneKeys, TheRenderSettingsTextHoldsEveryKeyExactly) {
  spec::RenderSettings a;
  const std::string text = render_settings_text(a);
  for (const char* key : {"width 960", "height 640", "spp 64", "seed 1", "integrator path",
                          "regularize false", "lod false", "lod_quality 1", "max_depth 12",
                          "treemaker_spp 4", "pass_spp 16", "independent_passes false",
                          "noise_threshold 0", "min_spp 16", "aerial_perspective false"}) {
    EXPECT_NE(text.find(key), std::string::npos) << key << " in " << text;
  }
  spec::RenderSettings b = a;
  b.lod_quality = 1.0000001;
  EXPECT_NE(render_settings_text(b), text);
  EXPECT_NE(render_settings_text(b).find("lod_quality 1.0000001"), std::string::npos);
  b = a;
  b.noise_threshold = 0.1;
  EXPECT_NE(render_settings_text(b).find("noise_threshold 0.1;"), std::string::npos);
  b = a;
  b.integrator = spec::Integrator::Treemaker;
  EXPECT_NE(render_settings_text(b).find("integrator treemaker"), std::string::npos);
}

}  // namespace arbor::formats
