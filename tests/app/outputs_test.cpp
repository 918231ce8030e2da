// What a compositor reads from arbor's EXR (issue 15): the colour space as OIIO reads it back,
// premultiplied RGBA with a transparent sky, object and material ids, and Cryptomatte mattes that
// decode to the same objects — through the command line, as a pipeline meets them.
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app/cli.h"

namespace {

// Two aspens and the ground, the sky above them.
std::string outputs_scene(const char* name, const std::string& output) {
  return write_temp(
      name,
      "[render]\nwidth = 48\nheight = 36\nspp = 16\npass_spp = 4\n"
      "[camera]\nposition = [0.0, -14.0, 3.0]\nlook_at = [0.0, 0.0, 4.0]\nfov = 50.0\n"
      "[[tree]]\nspecies = \"" +
          species("quaking_aspen.toml") +
          "\"\n"
          "[[tree]]\nspecies = \"" +
          species("quaking_aspen.toml") +
          "\"\nposition = [3.0, 3.0, 0.0]\n"
          "[ground]\nenabled = true\n[output]\n" +
          output);
}

struct Exr {
  OIIO::ImageSpec spec;
  std::vector<float> px;
  float at(int x, int y, const std::string& channel) const {
    const int c = spec.channelindex(channel);
    EXPECT_GE(c, 0) << channel;
    return c < 0 ? NAN : px[(static_cast<std::size_t>(y) * spec.width + x) * spec.nchannels + c];
  }
};

Exr read_exr(const std::string& path) {
  Exr e;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  if (!in) return e;
  e.spec = in->spec();
  e.px.resize(static_cast<std::size_t>(e.spec.width) * e.spec.height * e.spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, e.spec.nchannels, OIIO::TypeDesc::FLOAT, e.px.data()));
  return e;
}

// {"name": "hex", …} or {"name": id, …} → name → value text.
std::map<std::string, std::string> parse_flat_json(const std::string& text) {
  std::map<std::string, std::string> out;
  std::size_t p = 0;
  while ((p = text.find('"', p)) != std::string::npos) {
    const std::size_t e = text.find('"', p + 1);
    const std::string key = text.substr(p + 1, e - p - 1);
    std::size_t v = text.find(':', e) + 1;
    while (text[v] == ' ') ++v;
    std::size_t ve = text.find_first_of(",}", v);
    std::string value = text.substr(v, ve - v);
    if (!value.empty() && value.front() == '"') value = value.substr(1, value.size() - 2);
    out[key] = value;
    p = ve;
  }
  return out;
}

// The Cryptomatte matte of `id` at a pixel: the coverage of every rank that holds it.
float matte(const Exr& e, const std::string& layer, float id, int x, int y) {
  float m = 0.0f;
  for (int set = 0; set < 3; ++set) {
    char name[64];
    std::snprintf(name, sizeof name, "%s%02d", layer.c_str(), set);
    const std::string s = name;
    if (e.at(x, y, s + ".R") == id) m += e.at(x, y, s + ".G");
    if (e.at(x, y, s + ".B") == id) m += e.at(x, y, s + ".A");
  }
  return m;
}

float id_of_hex(const std::string& hex) {
  const std::uint32_t bits = static_cast<std::uint32_t>(std::stoul(hex, nullptr, 16));
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

}  // namespace

TEST(Outputs, OiioReadsBackTheColourSpaceAndChromaticities) {
  const std::string dir = ::testing::TempDir();
  struct Case {
    const char* space;
    const char* interop;
    float red_x;
  };
  for (const Case c :
       {Case{"ACEScg", "lin_ap1_scene", 0.713f}, Case{"ACES2065-1", "lin_ap0_scene", 0.7347f},
        Case{"Linear Rec.709 (sRGB)", "lin_rec709_scene", 0.64f}}) {
    const std::string scene =
        outputs_scene("tags.toml", std::string("colorspace = \"") + c.space + "\"\n");
    const std::string out = dir + "tags.exr";
    ASSERT_EQ(run_arbor("render " + scene + " --spp 1 -o " + out).code, 0);
    const Exr e = read_exr(out);
    EXPECT_EQ(e.spec.get_string_attribute("oiio:ColorSpace"), c.space);
    EXPECT_EQ(e.spec.get_string_attribute("colorInteropID"), c.interop);
    const OIIO::ParamValue* chroma = e.spec.find_attribute("chromaticities");
    ASSERT_TRUE(chroma) << c.space;
    EXPECT_NEAR(chroma->get_float(0), c.red_x, 1e-6) << c.space;
    // An ACES container only for ACES2065-1 RGBA without AOVs.
    EXPECT_EQ(e.spec.get_int_attribute("acesImageContainerFlag", 0),
              std::string(c.space) == "ACES2065-1" ? 1 : 0);
  }
  // A space arbor does not know by name still gets its chromaticities, measured through the config.
  const std::string scene =
      outputs_scene("tags2.toml", "colorspace = \"lin_rec709\"\naovs = [\"depth\"]\n");
  ASSERT_EQ(run_arbor("render " + scene + " --spp 1 -o " + dir + "tags2.exr").code, 0);
  const Exr e = read_exr(dir + "tags2.exr");
  EXPECT_EQ(e.spec.get_string_attribute("oiio:ColorSpace"), "lin_rec709");
  ASSERT_TRUE(e.spec.find_attribute("chromaticities"));
  EXPECT_NEAR(e.spec.find_attribute("chromaticities")->get_float(0), 0.64f, 1e-6);
}

TEST(Outputs, TransparentSkyIsPremultipliedRgbaAndIdsDecodeToTheSameObjects) {
  const std::string dir = ::testing::TempDir();
  const std::string scene =
      outputs_scene("ids.toml",
                    "aovs = [\"object_id\", \"material_id\", \"crypto_object\", "
                    "\"crypto_material\"]\npixel_type = \"float\"\n");
  ASSERT_EQ(run_arbor("render " + scene + " -o " + dir + "opaque.exr").code, 0);
  const CliRun r = run_arbor("render " + scene + " --transparent -o " + dir + "clear.exr");
  ASSERT_EQ(r.code, 0) << r.err;
  const Exr opaque = read_exr(dir + "opaque.exr"), clear = read_exr(dir + "clear.exr");
  ASSERT_EQ(clear.spec.get_int_attribute("arbor:transparent_sky"), 1);
  const int w = clear.spec.width, h = clear.spec.height;
  const std::map<std::string, std::string> objects =
      parse_flat_json(clear.spec.get_string_attribute("arbor:object_ids"));
  ASSERT_EQ(objects.size(), 3u);
  ASSERT_EQ(objects.at("quaking_aspen.0"), "1");
  ASSERT_EQ(objects.at("quaking_aspen.1"), "2");
  ASSERT_EQ(objects.at("ground"), "3");
  // The Cryptomatte layers' headers, by the specification's key.
  std::map<std::string, std::string> object_manifest, material_manifest;
  for (const OIIO::ParamValue& p : clear.spec.extra_attribs) {
    const std::string name = p.name().string();
    if (name.rfind("cryptomatte/", 0) != 0 || name.size() < 20 || name.substr(19) != "/name")
      continue;
    const std::string key = name.substr(0, 19);
    const std::string layer = clear.spec.get_string_attribute(name);
    EXPECT_EQ(clear.spec.get_string_attribute(key + "/hash"), "MurmurHash3_32");
    EXPECT_EQ(clear.spec.get_string_attribute(key + "/conversion"), "uint32_to_float32");
    (layer == "crypto_object" ? object_manifest : material_manifest) =
        parse_flat_json(clear.spec.get_string_attribute(key + "/manifest"));
  }
  ASSERT_EQ(object_manifest.size(), 3u);
  ASSERT_EQ(material_manifest.size(), 4u);  // bark, leaf front, leaf back, ground
  int sky = 0, edges = 0, dominant = 0, sky_wins = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float a = clear.at(x, y, "A");
      EXPECT_EQ(opaque.at(x, y, "A"), 1.0f);
      EXPECT_GE(a, 0.0f);
      EXPECT_LE(a, 1.0f);
      if (a == 0.0f) {
        // Pure sky: nothing added, no id; the opaque render sees the sky there.
        ++sky;
        EXPECT_EQ(clear.at(x, y, "R"), 0.0f);
        EXPECT_EQ(clear.at(x, y, "object_id.X"), 0.0f);
        EXPECT_GT(opaque.at(x, y, "B"), 0.01f);
      }
      if (a > 0.0f && a < 1.0f) ++edges;
      // The mattes of all objects (and of all materials) add up to the alpha.
      float objects_sum = 0.0f, best = 0.0f;
      std::string best_name;
      for (const auto& [name, hex] : object_manifest) {
        const float m = matte(clear, "crypto_object", id_of_hex(hex), x, y);
        objects_sum += m;
        if (m > best) best = m, best_name = name;
      }
      float materials_sum = 0.0f;
      for (const auto& [name, hex] : material_manifest)
        materials_sum += matte(clear, "crypto_material", id_of_hex(hex), x, y);
      EXPECT_NEAR(objects_sum, a, 1e-5) << x << "," << y;
      EXPECT_NEAR(materials_sum, a, 1e-5) << x << "," << y;
      // object_id is the object whose matte is largest.
      if (best > 0.5f) {
        ++dominant;
        EXPECT_EQ(clear.at(x, y, "object_id.X"), std::stof(objects.at(best_name))) << x << "," << y;
      }
      // Where the sky covers more of the pixel than any object, object_id is 0 (docs/outputs.md:
      // "the id covering most of the pixel").
      if (1.0f - objects_sum > best + 1e-6f) {
        ++sky_wins;
        EXPECT_EQ(clear.at(x, y, "object_id.X"), 0.0f) << x << "," << y;
      }
      // The ids do not depend on the sky being transparent.
      EXPECT_EQ(opaque.at(x, y, "object_id.X"), clear.at(x, y, "object_id.X"));
    }
  }
  EXPECT_GT(sky, 20);
  EXPECT_GT(edges, 20);
  EXPECT_GT(sky_wins, sky);  // some edge pixels are mostly sky
  EXPECT_GT(dominant, w * h / 2);
  // Each tree is seen: its matte is somewhere above 0.9.
  for (const char* tree : {"quaking_aspen.0", "quaking_aspen.1", "ground"}) {
    float most = 0.0f;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        most = std::max(most,
                        matte(clear, "crypto_object", id_of_hex(object_manifest.at(tree)), x, y));
    EXPECT_GT(most, 0.9f) << tree;
  }
}

TEST(Outputs, IdsAndAlphaMergeBitIdentically) {
  const std::string dir = ::testing::TempDir();
  const std::string scene = outputs_scene(
      "merge_ids.toml",
      "aovs = [\"object_id\", \"crypto_object\", \"crypto_material\"]\npixel_type = \"float\"\n");
  ASSERT_EQ(run_arbor("render " + scene + " --transparent -o " + dir + "whole.exr").code, 0);
  // Two windows, the second in two pass groups.
  ASSERT_EQ(
      run_arbor("render " + scene + " --transparent --crop 0,0,48,20 -o " + dir + "p0.exr").code,
      0);
  ASSERT_EQ(run_arbor("render " + scene + " --transparent --crop 0,20,48,36 --passes 0:2 -o " +
                      dir + "p1.exr")
                .code,
            0);
  ASSERT_EQ(run_arbor("render " + scene + " --transparent --crop 0,20,48,36 --passes 2:4 -o " +
                      dir + "p2.exr")
                .code,
            0);
  const CliRun m = run_arbor("merge -o " + dir + "merged.exr " + dir + "p2.exr " + dir + "p0.exr " +
                             dir + "p1.exr");
  ASSERT_EQ(m.code, 0) << m.err;
  const Exr a = read_exr(dir + "whole.exr"), b = read_exr(dir + "merged.exr");
  ASSERT_EQ(a.spec.nchannels, b.spec.nchannels);
  ASSERT_EQ(a.px.size(), b.px.size());
  EXPECT_EQ(std::memcmp(a.px.data(), b.px.data(), a.px.size() * sizeof(float)), 0);
  EXPECT_EQ(a.spec.get_string_attribute("arbor:object_ids"),
            b.spec.get_string_attribute("arbor:object_ids"));
  // A part rendered without --transparent is another render.
  ASSERT_EQ(run_arbor("render " + scene + " --crop 0,0,48,20 -o " + dir + "q0.exr").code, 0);
  const CliRun refused = run_arbor("merge -o " + dir + "mixed.exr " + dir + "q0.exr " + dir +
                                   "p1.exr " + dir + "p2.exr");
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_NE(refused.err.find("not a part of the same render"), std::string::npos) << refused.err;
}

// OpenImageIO (264 shared libraries on Debian, 0.3 CPU-s to bind) is loaded only by what needs
// it: a render writes its EXR and PNG without it, `compare` loads it. The dynamic loader says
// which objects it opens (LD_DEBUG=files, on stderr).
TEST(Outputs, ARenderLoadsOpenImageIoOnlyWhenItReadsAnImage) {
  const std::string dir = ::testing::TempDir();
  const std::string scene = outputs_scene("no_oiio.toml", "");
  const CliRun render =
      run_arbor_with("LD_DEBUG=files", "render " + scene + " --width 8 --height 6 --spp 1 -o " +
                                           dir + "no_oiio.exr --png " + dir + "no_oiio.png");
  ASSERT_EQ(render.code, 0) << render.err.substr(render.err.size() > 4000 ? render.err.size() - 4000
                                                                          : 0);
  EXPECT_EQ(render.err.find("libOpenImageIO"), std::string::npos);
  EXPECT_EQ(render.err.find("libarbor_oiio"), std::string::npos);
  // What it wrote reads back as before: an 8-bit RGB PNG of the same size.
  auto png = OIIO::ImageInput::open(dir + "no_oiio.png");
  ASSERT_TRUE(png);
  EXPECT_EQ(png->spec().width, 8);
  EXPECT_EQ(png->spec().nchannels, 3);
  EXPECT_EQ(png->spec().format, OIIO::TypeDesc::UINT8);
  // compare reads images through the module, which brings OpenImageIO in.
  const CliRun cmp =
      run_arbor_with("LD_DEBUG=files", "compare " + dir + "no_oiio.exr " + dir + "no_oiio.exr");
  ASSERT_EQ(cmp.code, 0);
  EXPECT_NE(cmp.err.find("libarbor_oiio.so"), std::string::npos);
  EXPECT_NE(cmp.err.find("libOpenImageIO"), std::string::npos);
}

// Through the module, a file that is not an image is still refused as what it should have been.
TEST(Outputs, AnEnvironmentMapThatIsNotAnImageIsNamedAsOne) {
  const std::string dir = ::testing::TempDir();
  const std::string bad = write_temp("not_an_image.exr", "stands for an image");
  const std::string scene = write_temp("bad_env.toml",
                                       "[render]\nwidth = 8\nheight = 6\nspp = 1\n[sky]\nmodel = "
                                       "\"envmap\"\npath = \"" +
                                           bad + "\"\n");
  const CliRun r = run_arbor("render " + scene + " -o " + dir + "bad_env.exr");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(bad + ": error: cannot read the environment map: "), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::ifstream(dir + "bad_env.exr").good());
}

// `exposure = "auto"` is metered once per scene (issue 48): the compositing plate
// (--transparent), TREE-MAKER's render and every frame of an animation take the beauty pass's
// exposure, as the EXR's arbor:exposure records it; another light meters another.
TEST(Outputs, AutoExposureIsTheSceneNotTheOutputOrTheFrame) {
  const std::string dir = ::testing::TempDir() + "exposure_once/";
  std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str());
  // An aspen in the wind: the frames sway it.
  const std::string scene =
      write_temp("exposure_once.toml",
                 "[render]\nwidth = 40\nheight = 30\nspp = 4\npass_spp = 4\n"
                 "[camera]\nposition = [0.0, -10.0, 2.0]\nlook_at = [0.0, 0.0, 4.0]\nfov = 50.0\n"
                 "exposure = \"auto\"\n"
                 "[[tree]]\nspecies = \"" +
                     species("quaking_aspen.toml") +
                     "\"\n[ground]\nenabled = true\n[animation]\nframes = 24\nfps = 4\n");
  const auto exposure_of = [&](const std::string& name, const std::string& options) {
    const CliRun r = run_arbor("render " + scene + " " + options + " -o " + dir + name);
    EXPECT_EQ(r.code, 0) << r.err;
    return read_exr(dir + name).spec.get_string_attribute("arbor:exposure");
  };
  const std::string beauty = exposure_of("beauty.exr", "");
  ASSERT_NE(beauty.find("(metered)"), std::string::npos) << beauty;
  EXPECT_EQ(exposure_of("plate.exr", "--transparent"), beauty);
  EXPECT_EQ(exposure_of("approximate.exr", "--integrator treemaker"), beauty);
  EXPECT_EQ(exposure_of("regularized.exr", "--regularize"), beauty);
  EXPECT_EQ(exposure_of("f0.exr", "--frame 0"), beauty);
  EXPECT_EQ(exposure_of("f7.exr", "--frame 7"), beauty);
  EXPECT_EQ(exposure_of("f23.exr", "--frame 23 --transparent"), beauty);
  // The frames differ (the aspen sways), their exposure does not.
  EXPECT_NE(read_exr(dir + "f7.exr").px, read_exr(dir + "f0.exr").px);
  // The meter still follows the scene: at another time the aspen is another tree.
  EXPECT_NE(exposure_of("young.exr", "--time 0.3"), beauty);
}
