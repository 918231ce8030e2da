// The colour pipeline's pixel values, not only its names: arbor's OCIO config converts
// scene-linear Rec.709 to ACEScg by the published Bradford-adapted matrix, CIE XYZ to Rec.709 by
// the sRGB standard's, and writes a PNG through the sRGB display curve.
#include <cmath>
#include <string>

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "imaging/color.h"
#include "formats/scene_desc.h"
#include "imaging/image_output.h"

namespace arbor::trace {

namespace {

const std::string kConfig = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";

void expect_rgb(const float got[3], double r, double g, double b, double tolerance, const char* what) {
  EXPECT_NEAR(got[0], r, tolerance) << what;
  EXPECT_NEAR(got[1], g, tolerance) << what;
  EXPECT_NEAR(got[2], b, tolerance) << what;
}

// Errors the OCIO config finds in a scene that parsed: still at the scene key.
void expect_colour_error(const std::string& text, int line, int column, const std::string& fragment) {
  const SceneDesc s = parse_scene(text, "dir/s.toml");
  const ColorPipeline color(kConfig);
  testing::expect_input_error([&] { color.check(s.output); }, "dir/s.toml", line, column, fragment);
}

}  // namespace

TEST(Color, ASceneOutputsUnknownNamesAreErrorsAtTheSceneKey) {
  // The scene file parsed; the config finds the colour space, display or view missing and says
  // so at the key, listing what it has.
  expect_colour_error("[output]\nexr = \"a.exr\"\ncolorspace = \"Rec.2020 please\"\n", 3, 14,
                      "output.colorspace \"Rec.2020 please\" is not in the OCIO config");
  expect_colour_error("[output]\ndisplay = \"CRT\"\n", 2, 11,
                      "output.display \"CRT\" is not in the OCIO config; it has \"sRGB\"");
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
  OutputDesc out;
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
  testing::expect_input_error([] { ColorPipeline("/nonexistent/config.ocio"); }, "/nonexistent/config.ocio",
                              0, 0, "cannot use this OCIO config");
}

}  // namespace arbor::trace
