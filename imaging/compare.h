// Image comparison: error metrics, false-colour heatmaps, side-by-side pictures
// through the OCIO display view, and the per-pixel z-test of render tests (DESIGN.md, "How we
// know it is right").
#pragma once

#include <string>
#include <vector>

namespace arbor::imaging {

// The RGB of an EXR (or any image OIIO reads) and, when present, its variance.{R,G,B}
// channels: the variance of each pixel's mean, as arbor writes it.
struct CompareImage {
  std::string path;
  std::string colorspace;  // arbor:colorspace (the OCIO space it was written in), or empty
  int width = 0, height = 0;
  std::vector<float> rgb;       // width*height*3
  std::vector<float> variance;  // width*height*3, or empty
  bool half_beauty = false;     // R,G,B stored as half floats (adds quantisation noise)
  int passes = 0;  // arbor:passes, the passes the variance was estimated over; 0: unknown
  bool sequence_passes =
      false;    // the passes took points of one sequence: the variance is an upper bound
  int spp = 0;  // arbor:spp, samples a pixel; 0: unknown
  bool display_encoded = false;  // integer pixels (a PNG, JPEG, 8/16-bit TIFF): display-referred
};

// InputError when the file cannot be read, lacks R/G/B, or holds a NaN or infinity.
CompareImage read_compare_image(const std::string& path);

struct CompareMetrics {
  double rmse = 0, mean_abs = 0, rel_mse = 0, max_abs = 0, psnr = 0;
  int max_x = 0, max_y = 0;  // where max_abs is
};

// RMSE, mean absolute error, max error (and where) and PSNR (peak 1; infinite when equal),
// over R, G and B. rel_mse = mean over channels of (a-b)^2 / (b^2 + 0.01), B the reference.
CompareMetrics compare_images(const CompareImage& a, const CompareImage& b);

struct ZTest {
  double alpha = 0.01;       // family-wise level over all pixels
  double alpha_channel = 0;  // per channel, after the Sidak correction over 3*pixels tests
  double z_critical = 0;     // two-sided critical |z| at alpha_channel (Student's t with dof)
  double dof = 0;            // of the reference's per-pixel variance; 0: taken as normal
  double pass_fraction = 0;  // pixels whose three channels all pass
  double required = 0.995;
  long long pixels = 0, failed = 0;
  bool a_has_variance = false;
  // Pooled tests, each at alpha_pooled: the image mean of each channel (Sidak over the three)
  // and the chi-square of the block means' z over 16x16 blocks.
  double alpha_pooled = 0.005;
  double mean_z[3] = {0, 0, 0};  // (mean of A - mean of B) / its standard error, per channel
  double mean_z_critical = 0;
  double block_chi2 = 0, block_dof = 0, block_p = 1;
  // Channels of blocks that differ beyond their rounding where neither image has noise (a
  // deterministic difference, e.g. in a sky seen directly): any fails the block test.
  long long noiseless_blocks_differing = 0;
  double variance_ratio = 0;  // Σ var_a / Σ var_b: how much noisier A is than B
  double spp_ratio = 0;       // spp_b / spp_a when both say, else 0: A's variance over a block is
                         // at least B's times this (quasi-Monte Carlo converges at least as 1/n)
  bool pixels_passed = false, mean_passed = false, blocks_passed = false;
  bool passed = false;  // all three
};

// The reference test of A against B (docs/rendering.md, "Reference tests"). Per pixel: z =
// (a - b) / sqrt((1 + c) var_b + q), c = Σ var_a / Σ var_b over the pixel's 16x16 block, at
// least spp_ratio (A's own variance is too noisy a pixel at a few passes; B's shape scaled to
// A's level is not), and q the
// float or half rounding of both; |z| <= the Sidak-corrected critical value of Student's t with
// B's passes - 1 degrees of freedom, for at least `required` of the pixels. Pooled, with A's and
// B's variance summed: each channel's image mean, and Σ z² of the block means against
// chi-square, A's variance over a block taken as at least spp_ratio times B's (where A never
// sampled a thin twig B sees, it has no variance of its own). B must carry variance (InputError
// otherwise); without A's, c = 0 and the pooled tests use B's variance alone. Rounding is variance
// in the pooled tests where a pixel has noise, and a bound forgiven where it has none.
ZTest reference_z_test(const CompareImage& a, const CompareImage& b, double alpha = 0.01,
                       double required = 0.995);

struct ComparePictures {
  // A false-colour image of the per-pixel error (mean over RGB of |a-b|), 0 .. the largest
  // error, with a labelled scale bar below it.
  std::string heatmap;
  // A, B (through the OCIO display/view from each file's colour space) and the heatmap in a row.
  std::string side_by_side;
  std::string display = "sRGB", view = "ACES 1.0 SDR-video";
  std::string ocio_config;  // the config of the display and view (default_ocio_config())
};

// Writes the pictures whose paths are set, atomically (8-bit; format by extension). Both are
// made before either is written, so an unknown display or view leaves neither behind.
void write_compare_pictures(const CompareImage& a, const CompareImage& b,
                            const ComparePictures& pictures);

}  // namespace arbor::imaging
