// The colour pipeline's pixel values, not only its names: arbor's OCIO config converts
// scene-linear Rec.709 to ACEScg by the published Bradford-adapted matrix, CIE XYZ to Rec.709 by
// the sRGB standard's, and writes a PNG through the sRGB display curve.
#include <array>
#include <cmath>
#include <fstream>
#include <string>

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "imaging/color.h"
#include "formats/scene_file.h"
#include "imaging/image_output.h"

namespace arbor::imaging {

namespace {

const std::string kConfig = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";

void expect_rgb(const float got[3], double r, double g, double b, double tolerance,
                const char* what) {
  EXPECT_NEAR(got[0], r, tolerance) << what;
  EXPECT_NEAR(got[1], g, tolerance) << what;
  EXPECT_NEAR(got[2], b, tolerance) << what;
}

// Errors the OCIO config finds in a scene that parsed: still at the scene key.
void expect_colour_error(const std::string& text, int line, int column,
                         const std::string& fragment) {
  const spec::SceneDesc s = formats::parse_scene(text, "dir/s.toml");
  const ColorPipeline color(kConfig);
  testing::expect_input_error([&] { color.check(s.output, s.output.where); }, "dir/s.toml", line,
                              column, fragment);
}

}  // namespace

TEST(Color, ASceneOutputsUnknownNamesAreErrorsAtTheSceneKey) {
  // The scene file parsed; the config finds the colour space, display or view missing and says
  // so at the key, listing what it has.
  expect_colour_error("[output]\nexr = \"a.exr\"\ncolorspace = \"Rec.2020 please\"\n", 3, 14,
                      "output.colorspace \"Rec.2020 please\" is not in the OCIO config");
  expect_colour_error("[output]\ndisplay = \"CRT\"\n", 2, 11,
                      "output.display \"CRT\" is not a display of the OCIO config");
  expect_colour_error("[output]\nview = \"Filmic\"\n", 2, 8,
                      "output.view \"Filmic\" is not a view of display \"sRGB\"");
}

TEST(Color, Rec709ToAcescgIsTheBradfordAdaptedMatrix) {
  // Linear Rec.709 → ACEScg (AP1, D60), Bradford adaptation: the columns of the published matrix
  // (e.g. the ACES and OCIO references) are the images of the three primaries.
  const ColorPipeline color(kConfig);
  const ColorTransform to_acescg = color.to_output("ACEScg");
  float red[3] = {1.0f, 0.0f, 0.0f}, green[3] = {0.0f, 1.0f, 0.0f}, blue[3] = {0.0f, 0.0f, 1.0f};
  float white[3] = {1.0f, 1.0f, 1.0f};
  to_acescg(red);
  to_acescg(green);
  to_acescg(blue);
  to_acescg(white);
  expect_rgb(red, 0.6130974, 0.0701937, 0.0206156, 2e-4, "red");
  expect_rgb(green, 0.3395231, 0.9163539, 0.1095698, 2e-4, "green");
  expect_rgb(blue, 0.0473795, 0.0134524, 0.8698146, 2e-4, "blue");
  expect_rgb(white, 1.0, 1.0, 1.0, 2e-4, "white stays white");
  // The rendering space to itself is the identity.
  float grey[3] = {0.18f, 0.5f, 2.0f};
  color.to_output("Linear Rec.709 (sRGB)")(grey);
  expect_rgb(grey, 0.18, 0.5, 2.0, 1e-6, "identity");
}

TEST(Color, CieXyzToTheRenderingSpaceIsTheSrgbMatrix) {
  // The sky's XYZ: D65 white is white, the sRGB red primary's XYZ (IEC 61966-2-1) is pure red.
  const ColorTransform xyz = ColorPipeline(kConfig).xyz_to_scene_linear();
  float d65[3] = {0.95047f, 1.0f, 1.08883f}, red[3] = {0.4124564f, 0.2126729f, 0.0193339f};
  float y_only[3] = {0.0f, 1.0f, 0.0f};
  xyz(d65);
  xyz(red);
  xyz(y_only);
  expect_rgb(d65, 1.0, 1.0, 1.0, 2e-3, "D65 white");
  expect_rgb(red, 1.0, 0.0, 0.0, 2e-3, "red primary");
  // The second column of the sRGB matrix XYZ → RGB.
  expect_rgb(y_only, -1.5372, 1.8758, -0.2040, 2e-3, "Y alone");
}

TEST(Color, PngsGoThroughTheSrgbDisplayCurve) {
  // The un-tone-mapped view: scene-linear grey through the sRGB curve, 8-bit:
  // 0 → 0, 0.0031308 → 0.04045 (10), 0.18 → 0.4614 (118), 1 and above → 255.
  Image image;
  image.width = 5;
  image.height = 1;
  for (float v : {0.0f, 0.0031308f, 0.18f, 1.0f, 4.0f}) image.beauty.push_back(glm::vec3(v));
  OutputSpec out;
  out.colorspace = "Linear Rec.709 (sRGB)";
  out.view = "Un-tone-mapped";
  const ColorPipeline color(kConfig);
  color.check(out);
  const std::string path = ::testing::TempDir() + "arbor_color_test.png";
  write_png(image, out, color, path);
  OIIO::ImageBuf png(path);
  ASSERT_TRUE(png.read(0, 0, true, OIIO::TypeDesc::UINT8)) << png.geterror();
  const int expected[5] = {0, 10, 118, 255, 255};
  for (int x = 0; x < 5; ++x) {
    float px[3];
    png.getpixel(x, 0, px, 3);  // 8-bit values as fractions of 255
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(px[c] * 255.0f, expected[x], 1.0f) << "pixel " << x << " channel " << c;
    }
  }
}

TEST(Color, AConfigThatCannotBeReadIsAnInputErrorNamingIt) {
  testing::expect_input_error([] { ColorPipeline("/nonexistent/config.ocio"); },
                              "/nonexistent/config.ocio", 0, 0, "cannot use this OCIO config");
}

}  // namespace arbor::imaging

namespace arbor::imaging {

namespace {

std::string write_config(const char* name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// The head every test config shares: a display with one view, the roles OCIO requires.
std::string config_head(const std::string& scene_linear, const std::string& extra_roles) {
  return "ocio_profile_version: 2.1\nsearch_path: \"\"\nstrictparsing: true\nroles:\n  default: " +
         scene_linear + "\n  scene_linear: " + scene_linear + "\n" + extra_roles +
         "displays:\n  sRGB:\n    - !<View> {name: Raw, colorspace: " + scene_linear +
         "}\n"
         "active_displays: [sRGB]\nactive_views: [Raw]\ncolorspaces:\n";
}

// XYZ → scene_linear by `config`, against arbor's own config, at a few colours.
void expect_xyz_like_arbors(const std::string& config, const std::string& route_fragment,
                            double tolerance) {
  const ColorPipeline mine(kConfig), other(config);
  EXPECT_NE(other.xyz_route().find(route_fragment), std::string::npos) << other.xyz_route();
  const ColorTransform a = mine.xyz_to_scene_linear(), b = other.xyz_to_scene_linear();
  for (const auto& xyz :
       {std::array<float, 3>{0.95047f, 1.0f, 1.08883f}, std::array<float, 3>{0.3f, 0.4f, 0.2f},
        std::array<float, 3>{0.1f, 0.05f, 0.6f}}) {
    float p[3] = {xyz[0], xyz[1], xyz[2]}, q[3] = {xyz[0], xyz[1], xyz[2]};
    a(p);
    b(q);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(q[c], p[c], tolerance) << other.xyz_route() << " channel " << c;
  }
}

const char* kRec709ToXyz =
    "[0.4124564, 0.3575761, 0.1804375, 0, 0.2126729, 0.7151522, 0.0721750, 0, "
    "0.0193339, 0.1191920, 0.9503041, 0, 0, 0, 0, 1]";

}  // namespace

TEST(Color, XyzIsFoundInConfigsWithoutArborsName) {
  // Blender's way: a role "XYZ" naming a space defined from the Rec.709 reference by the sRGB
  // standard's matrix.
  expect_xyz_like_arbors(
      write_config("blender_like.ocio",
                   config_head("Linear", "  XYZ: Linear XYZ (Blender)\n") +
                       "  - !<ColorSpace>\n    name: Linear\n    isdata: false\n"
                       "  - !<ColorSpace>\n    name: Linear XYZ (Blender)\n    isdata: false\n"
                       "    from_scene_reference: !<MatrixTransform> {matrix: " +
                       kRec709ToXyz + "}\n"),
      "\"XYZ\" (\"Linear XYZ (Blender)\")", 2e-3);
  // Only the aces_interchange role: XYZ reaches ACES2065-1 by the AP0 primaries.
  expect_xyz_like_arbors(
      write_config("aces_only.ocio",
                   config_head("lin_rec709", "  aces_interchange: ACES2065-1\n") +
                       "  - !<ColorSpace>\n    name: ACES2065-1\n    isdata: false\n"
                       "  - !<ColorSpace>\n    name: lin_rec709\n    isdata: false\n"
                       "    to_scene_reference: !<GroupTransform>\n      children:\n"
                       "        - !<BuiltinTransform> {style: \"UTILITY - "
                       "ACES-AP1_to_LINEAR-REC709_BFD\", direction: inverse}\n"
                       "        - !<BuiltinTransform> {style: ACEScg_to_ACES2065-1}\n"),
      "role aces_interchange", 1e-4);
  // Nothing but a scene_linear space arbor knows by name.
  expect_xyz_like_arbors(
      write_config("linear_only.ocio",
                   config_head("lin_rec709", "") +
                       "  - !<ColorSpace>\n    name: lin_rec709\n    isdata: false\n"),
      "the scene_linear space \"lin_rec709\" by its primaries", 2e-3);
}

TEST(Color, AConfigWithoutXyzSaysEveryWayItTried) {
  // A display-referred XYZ (reached only through a view transform) and an unknown scene_linear.
  const std::string config = write_config(
      "no_xyz.ocio",
      config_head("Mystery", "  cie_xyz_d65_interchange: CIE-XYZ-D65\n") +
          "  - !<ColorSpace>\n    name: Mystery\n    isdata: false\n"
          "display_colorspaces:\n  - !<ColorSpace>\n    name: CIE-XYZ-D65\n    isdata: false\n"
          "view_transforms:\n  - !<ViewTransform>\n    name: none\n"
          "    from_scene_reference: !<MatrixTransform> {}\n");
  const ColorPipeline color(config);
  try {
    (void)color.xyz_to_scene_linear();
    ADD_FAILURE() << "a config without XYZ was accepted";
  } catch (const InputError& e) {
    const std::string m = e.message();
    for (const char* part :
         {"colour space \"Linear CIE-XYZ-D65\": not in the config",
          "\"CIE-XYZ-D65\" is display-referred", "role aces_interchange: not in the config",
          "the scene_linear space \"Mystery\": not a space arbor knows the primaries of",
          "Add a scene-referred colour space named \"Linear CIE-XYZ-D65\""}) {
      EXPECT_NE(m.find(part), std::string::npos) << part << "\n" << m;
    }
  }
}

TEST(Color, ChromaticitiesAreMeasuredThroughTheConfig) {
  const ColorPipeline color(kConfig);
  const std::vector<float> c = color.chromaticities("Linear Rec.709 (sRGB)");
  ASSERT_EQ(c.size(), 8u);
  const float rec709[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(c[static_cast<std::size_t>(i)], rec709[i], 1e-3) << i;
  // A space arbor does not know by name is measured: linear XYZ's primaries are the axes, its
  // white (1, 1, 1) is the equal-energy white.
  const std::vector<float> xyz = color.chromaticities("Linear CIE-XYZ-D65");
  ASSERT_EQ(xyz.size(), 8u);
  const float axes[8] = {1.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f / 3.0f, 1.0f / 3.0f};
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(xyz[static_cast<std::size_t>(i)], axes[i], 2e-3) << i;
  // A known space is stated: ACEScg's D60 white.
  EXPECT_EQ(color.chromaticities("ACEScg")[6], 0.32168f);
  EXPECT_EQ(color.interop_id("ACEScg"), "lin_ap1_scene");
  // An encoded space has none.
  EXPECT_TRUE(color.chromaticities("sRGB - Texture").empty());
  EXPECT_EQ(color.names_of("lin_rec709").front(), "Linear Rec.709 (sRGB)");
}

}  // namespace arbor::imaging
