// Image comparison for `arbor compare` and the render tests.
#include "imaging/compare.h"

#include "imaging/color.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "common/image_library.h"
#include "imaging/image_file.h"
#include "imaging/image_output.h"
#include "imaging/statistics.h"

namespace arbor::imaging {

namespace {

// An RGB float picture (display-referred) being composed.
struct Picture {
  int width = 0, height = 0;
  std::vector<float> rgb;
  Picture(int w, int h) : width(w), height(h), rgb(3 * static_cast<std::size_t>(w) * h, 0.0f) {}
  void set(int x, int y, const float v[3]) {
    for (int c = 0; c < 3; ++c) rgb[3 * (static_cast<std::size_t>(y) * width + x) + c] = v[c];
  }
  // `from` with its top-left corner at (x0, y0), clipped to this picture.
  void paste(int x0, int y0, const Picture& from) {
    for (int y = 0; y < from.height && y0 + y < height; ++y)
      for (int x = 0; x < from.width && x0 + x < width; ++x)
        set(x0 + x, y0 + y, &from.rgb[3 * (static_cast<std::size_t>(y) * from.width + x)]);
  }
  void text(int x, int y, const std::string& s, bool right_aligned = false) {
    image_library("label a comparison picture")
        .draw_text(rgb, width, height, x, y, s, 12, right_aligned);
  }
};

void require_same_size(const CompareImage& a, const CompareImage& b) {
  if (a.width != b.width || a.height != b.height) {
    throw InputError({b.path, 0, 0}, "is " + std::to_string(b.width) + "x" +
                                         std::to_string(b.height) + " but " + a.path + " is " +
                                         std::to_string(a.width) + "x" + std::to_string(a.height) +
                                         "; compare needs images of the same size");
  }
}

// The per-pixel error of the heatmap: mean over R, G, B of |a - b|.
std::vector<float> pixel_errors(const CompareImage& a, const CompareImage& b) {
  std::vector<float> e(static_cast<std::size_t>(a.width) * a.height);
  for (std::size_t p = 0; p < e.size(); ++p) {
    float s = 0;
    for (int c = 0; c < 3; ++c) s += std::fabs(a.rgb[3 * p + c] - b.rgb[3 * p + c]);
    e[p] = s / 3.0f;
  }
  return e;
}

// arbor's false-colour ramp: black, violet, red, orange, pale yellow. Monotonic in luminance
// so the picture still reads in grey. t in [0, 1]; output is display-referred sRGB.
void ramp(float t, float rgb[3]) {
  static const float stops[5][3] = {{0.00f, 0.00f, 0.02f},
                                    {0.33f, 0.05f, 0.45f},
                                    {0.80f, 0.20f, 0.25f},
                                    {0.98f, 0.60f, 0.10f},
                                    {0.99f, 0.99f, 0.75f}};
  t = std::clamp(t, 0.0f, 1.0f) * 4.0f;
  const int i = std::min(3, static_cast<int>(t));
  const float f = t - static_cast<float>(i);
  for (int c = 0; c < 3; ++c) rgb[c] = stops[i][c] + f * (stops[i + 1][c] - stops[i][c]);
}

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// The heatmap with its scale bar: height + 36 rows, display-referred floats in [0, 1].
Picture heatmap(const CompareImage& a, const CompareImage& b) {
  const std::vector<float> err = pixel_errors(a, b);
  const float top = err.empty() ? 0.0f : *std::max_element(err.begin(), err.end());
  const int bar = 36;
  Picture pic(a.width, a.height + bar);
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      float rgb[3];
      ramp(top > 0 ? err[static_cast<std::size_t>(y) * a.width + x] / top : 0.0f, rgb);
      pic.set(x, y, rgb);
    }
  }
  // The bar: the ramp from 0 (left) to the largest error (right), labelled at both ends.
  const int margin = std::min(8, a.width / 8);
  const int x0 = margin, x1 = std::max(x0 + 1, a.width - margin);
  for (int y = a.height + 4; y < a.height + 16; ++y) {
    for (int x = x0; x < x1; ++x) {
      float rgb[3];
      ramp(static_cast<float>(x - x0) / static_cast<float>(std::max(1, x1 - x0 - 1)), rgb);
      pic.set(x, y, rgb);
    }
  }
  // Labels are a convenience: without FreeType or the font the bar is still drawn.
  pic.text(x0, a.height + 31, "0");
  pic.text(x1, a.height + 31, short_number(top) + " |a-b|", true);
  return pic;
}

// One ulp of v stored as a half float (11 significant bits; below the smallest normal half, the
// ulp of 2^-14) or as a float (24 bits; below FLT_MIN, the ulp of FLT_MIN).
double ulp(double v, bool half) {
  return half ? std::ldexp(1.0, std::ilogb(std::max(std::fabs(v), 6.1e-5)) - 10)
              : std::ldexp(1.0, std::ilogb(std::max(std::fabs(v), 1.1754944e-38)) - 23);
}

// The variance rounding adds to a stored value. Half: a uniform error one ulp wide (ulp²/12).
// Float: a floor of one ulp of standard deviation, so that a pixel whose variance is 0 (a
// constant sky seen directly) still passes when another renderer's arithmetic lands a few ulps
// away (0.59999996 for 0.6) and fails at any error a user could see.
double rounding_variance(double v, bool half) {
  const double u = ulp(v, half);
  return half ? u * u / 12.0 : u * u;
}

// The largest rounding error the pooled tests forgive a value: half a half-float ulp (its
// rounding), one float ulp (the floor above). Where a pixel has noise, its rounding errors are
// as good as independent and count as variance; where it has none beyond its rounding (a
// constant sky), its rounding may be the same in every pixel and would not average out over a
// block, so the pixel's difference is first shrunk towards 0 by the bound: such a pixel may be
// off by its rounding, and no more.
double rounding_bound(double v, bool half) { return half ? 0.5 * ulp(v, true) : ulp(v, false); }

double forgive(double d, double bound) {
  return std::copysign(std::max(0.0, std::fabs(d) - bound), d);
}

// z of a pooled difference d with variance v (a difference where nothing is noise: infinite).
double pooled_z(double d, double v) {
  if (d == 0.0) return 0.0;
  return v > 0 ? d / std::sqrt(v) : std::copysign(HUGE_VAL, d);
}

}  // namespace

CompareImage read_compare_image(const std::string& path) {
  const ImageChannels image = read_image_channels(path);
  const DecodedImage& spec = image.image;
  CompareImage im;
  im.path = path;
  im.width = spec.width;
  im.height = spec.height;
  // arbor's own attribute names the OCIO space exactly; OIIO reports EXRs as plain "Linear".
  im.colorspace = spec.attribute("arbor:colorspace");
  const int r = image.index("R"), g = image.index("G"), bl = image.index("B");
  if (r < 0 || g < 0 || bl < 0) throw InputError({path, 0, 0}, "has no R, G and B channels");
  im.half_beauty = spec.channel_kinds[static_cast<std::size_t>(r)] == 'h';
  im.passes = spec.int_attribute("arbor:passes", 0);
  im.sequence_passes = im.passes >= 2 && spec.int_attribute("arbor:independent_passes", 1) == 0;
  im.spp = spec.int_attribute("arbor:spp", 0);
  // Integer pixels are display-encoded (sRGB PNGs, JPEGs): not the same quantity as an EXR's
  // scene-linear values.
  im.display_encoded = spec.channel_kinds[static_cast<std::size_t>(r)] == 'i';
  const int vr = image.index("variance.R"), vg = image.index("variance.G"),
            vb = image.index("variance.B");
  const bool has_var = vr >= 0 && vg >= 0 && vb >= 0;
  const std::size_t n = static_cast<std::size_t>(spec.width) * spec.height;
  im.rgb.resize(3 * n);
  if (has_var) im.variance.resize(3 * n);
  const int rgb_idx[3] = {r, g, bl}, var_idx[3] = {vr, vg, vb};
  for (std::size_t p = 0; p < n; ++p) {
    for (int c = 0; c < 3; ++c) {
      im.rgb[3 * p + c] = image.finite(p, rgb_idx[c], "");
      if (has_var) {
        const float s = image.finite(p, var_idx[c], "the variance of ");
        if (s < 0) {
          throw InputError({path, 0, 0}, "the variance of pixel (" +
                                             std::to_string(p % spec.width) + ", " +
                                             std::to_string(p / spec.width) + ") is negative");
        }
        im.variance[3 * p + c] = s;
      }
    }
  }
  return im;
}

CompareMetrics compare_images(const CompareImage& a, const CompareImage& b) {
  require_same_size(a, b);
  // Over every R, G and B value (in double): mean |a − b|, RMS, the largest |a − b| (the first
  // pixel where it is reached), and PSNR for a peak of 1 (infinite for identical images).
  CompareMetrics m;
  double sum = 0, sum2 = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    const double d = std::fabs(static_cast<double>(a.rgb[i]) - b.rgb[i]);
    sum += d;
    sum2 += d * d;
    if (d > m.max_abs) {
      m.max_abs = d;
      m.max_x = static_cast<int>((i / 3) % static_cast<std::size_t>(a.width));
      m.max_y = static_cast<int>((i / 3) / static_cast<std::size_t>(a.width));
    }
  }
  const double values = std::max<double>(1.0, static_cast<double>(a.rgb.size()));
  m.mean_abs = sum / values;
  m.rmse = std::sqrt(sum2 / values);
  m.psnr = m.rmse > 0 ? 20.0 * std::log10(1.0 / m.rmse) : HUGE_VAL;
  double rel = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    const double d = static_cast<double>(a.rgb[i]) - b.rgb[i];
    rel += d * d / (static_cast<double>(b.rgb[i]) * b.rgb[i] + 0.01);
  }
  m.rel_mse = a.rgb.empty() ? 0.0 : rel / static_cast<double>(a.rgb.size());
  return m;
}

ZTest reference_z_test(const CompareImage& a, const CompareImage& b, double alpha,
                       double required) {
  require_same_size(a, b);
  if (b.variance.empty()) {
    throw InputError({b.path, 0, 0},
                     "has no variance.R/G/B channels; a reference for --reference-test "
                     "is rendered with aovs = [\"variance\"]");
  }
  ZTest t;
  t.alpha = alpha;
  t.required = required;
  t.a_has_variance = !a.variance.empty();
  const int w = a.width, h = a.height;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  t.pixels = static_cast<long long>(n);
  // Sidak over all 3N channel tests: the chance that any of them fails by noise alone is alpha.
  t.alpha_channel = -std::expm1(std::log1p(-alpha) / (3.0 * static_cast<double>(n)));
  t.dof = b.passes >= 2 ? b.passes - 1 : 0;
  t.z_critical = t.dof > 0 ? student_t_two_sided_critical(t.alpha_channel, t.dof)
                           : normal_two_sided_critical(t.alpha_channel);
  auto rounding = [&](std::size_t i) {
    return rounding_variance(b.rgb[i], b.half_beauty) + rounding_variance(a.rgb[i], a.half_beauty);
  };
  // Under the hypothesis that A renders what B does, A's variance is at least B's scaled by the
  // ratio of their samples (quasi-Monte Carlo converges at least as fast as 1/n).
  t.spp_ratio = t.a_has_variance && a.spp > 0 && b.spp > 0 ? double(b.spp) / double(a.spp) : 0.0;
  // Applied to sums over blocks, where A's estimate is good, not to single pixels, where
  // flooring a noisy estimate would inflate it.
  auto var_a = [&](std::size_t i) {
    return t.a_has_variance ? static_cast<double>(a.variance[i]) : 0.0;
  };

  // Blocks of kBlock x kBlock pixels: A's level of noise relative to B's, and the block means.
  constexpr int kBlock = 16;
  const int bx = (w + kBlock - 1) / kBlock, by = (h + kBlock - 1) / kBlock;
  double sum_a = 0, sum_b = 0, chi2 = 0;
  double image_d[3] = {0, 0, 0}, image_v[3] = {0, 0, 0};
  int blocks = 0;
  std::vector<double> ratio(static_cast<std::size_t>(bx) * by * 3, 0.0);
  for (int j = 0; j < by; ++j) {
    for (int k = 0; k < bx; ++k) {
      double d[3] = {0, 0, 0}, va[3] = {0, 0, 0}, vb[3] = {0, 0, 0}, q[3] = {0, 0, 0};
      int noisy[3] = {0, 0, 0};
      for (int y = j * kBlock; y < std::min(h, (j + 1) * kBlock); ++y) {
        for (int x = k * kBlock; x < std::min(w, (k + 1) * kBlock); ++x) {
          for (int c = 0; c < 3; ++c) {
            const std::size_t i = 3 * (static_cast<std::size_t>(y) * w + x) + c;
            const double diff = static_cast<double>(a.rgb[i]) - b.rgb[i];
            va[c] += var_a(i);
            vb[c] += b.variance[i];
            if (var_a(i) + b.variance[i] > rounding(i)) {
              d[c] += diff;
              q[c] += rounding(i);
              ++noisy[c];
            } else {
              d[c] += forgive(diff, rounding_bound(a.rgb[i], a.half_beauty) +
                                        rounding_bound(b.rgb[i], b.half_beauty));
            }
          }
        }
      }
      for (int c = 0; c < 3; ++c) {
        va[c] = std::max(va[c], t.spp_ratio * vb[c]);
        ratio[(static_cast<std::size_t>(j) * bx + k) * 3 + c] =
            vb[c] > 0 ? va[c] / vb[c] : t.spp_ratio;
        const double v = va[c] + vb[c] + q[c];
        const double z = pooled_z(d[c], v);
        // A block that differs by more than its rounding where neither image has noise is a
        // deterministic difference: counted and failed on its own, not an infinite chi-square.
        if (std::isfinite(z)) {
          chi2 += z * z;
        } else {
          ++t.noiseless_blocks_differing;
        }
        // A block without noise (sky seen directly) tests only that it does not differ by more
        // than its rounding: its z is 0 or infinite, and it adds no degree of freedom.
        if (noisy[c] > 0) ++blocks;
        image_d[c] += d[c];
        image_v[c] += v;
        sum_a += va[c];
        sum_b += vb[c];
      }
    }
  }
  t.variance_ratio = sum_b > 0 ? sum_a / sum_b : 0.0;

  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t block = static_cast<std::size_t>((static_cast<int>(p) / w) / kBlock) * bx +
                              static_cast<std::size_t>((static_cast<int>(p) % w) / kBlock);
    bool ok = true;
    for (int c = 0; c < 3 && ok; ++c) {
      const std::size_t i = 3 * p + c;
      const double d = static_cast<double>(a.rgb[i]) - b.rgb[i];
      // The larger of two estimates of var(a - b): B's pixel scaled to A's level by the block,
      // and each image's own pixel estimate summed. The first alone fails wherever B's few
      // passes missed a rare bright path that A caught (Monte Carlo pixels are heavy-tailed):
      // A's own passes then carry that path's variance.
      const double var =
          std::max((1.0 + ratio[block * 3 + c]) * b.variance[i], var_a(i) + b.variance[i]) +
          rounding(i);
      ok = std::fabs(d) <= t.z_critical * std::sqrt(var);
    }
    if (!ok) ++t.failed;
  }
  t.pass_fraction = n ? 1.0 - static_cast<double>(t.failed) / static_cast<double>(n) : 1.0;
  t.pixels_passed = t.pass_fraction >= required;

  // Pooled: each channel's image mean (Sidak over three) and the blocks' chi-square.
  t.mean_z_critical = normal_two_sided_critical(-std::expm1(std::log1p(-t.alpha_pooled) / 3.0));
  t.mean_passed = true;
  for (int c = 0; c < 3; ++c) {
    // An image mean that differs without any noise: its z is capped (stated as such) to stay a
    // number; the test fails either way.
    t.mean_z[c] = std::max(-1e30, std::min(1e30, pooled_z(image_d[c], image_v[c])));
    t.mean_passed = t.mean_passed && std::fabs(t.mean_z[c]) <= t.mean_z_critical;
  }
  t.block_chi2 = chi2;
  t.block_dof = blocks;
  t.block_p = blocks > 0 ? chi_square_upper_tail(chi2, blocks) : (chi2 > 0 ? 0.0 : 1.0);
  t.blocks_passed = t.block_p >= t.alpha_pooled && t.noiseless_blocks_differing == 0;
  t.passed = t.pixels_passed && t.mean_passed && t.blocks_passed;
  return t;
}

void write_compare_pictures(const CompareImage& a, const CompareImage& b,
                            const ComparePictures& pictures) {
  require_same_size(a, b);
  if (pictures.heatmap.empty() && pictures.side_by_side.empty()) return;
  const Picture heat = heatmap(a, b);
  Picture row(0, 0);
  if (!pictures.side_by_side.empty()) {
    // A display or view the config lacks is named with what it offers, before any work.
    const ColorPipeline pipeline(pictures.ocio_config);
    pipeline.check_display_view(pictures.display, pictures.view, {}, {});
    auto shown = [&](const CompareImage& im) {
      // Images not written by arbor are taken to be in the config's scene_linear role.
      const std::string from = im.colorspace.empty() ? "scene_linear" : im.colorspace;
      if (!im.colorspace.empty() && !pipeline.has_colorspace(from)) {
        throw InputError({im.path, 0, 0},
                         "its colour space \"" + from + "\" is not in " + pictures.ocio_config);
      }
      DecodedImage out;
      out.width = im.width;
      out.height = im.height;
      out.channels = 3;
      out.channel_names = {"R", "G", "B"};
      out.pixels = im.rgb;
      const std::string why =
          image_library("show " + im.path)
              .convert(out, pictures.ocio_config, from, "", pictures.display, pictures.view);
      if (!why.empty()) {
        throw InputError({im.path, 0, 0}, "cannot show it through display \"" + pictures.display +
                                              "\", view \"" + pictures.view + "\": " + why);
      }
      Picture pic(im.width, im.height);
      pic.rgb = std::move(out.pixels);
      return pic;
    };
    const Picture sa = shown(a), sb = shown(b);
    const int gap = 4;
    row = Picture(3 * a.width + 2 * gap, heat.height);
    row.paste(0, 0, sa);
    row.paste(a.width + gap, 0, sb);
    row.paste(2 * (a.width + gap), 0, heat);
    row.text(4, a.height + 22, "A");
    row.text(a.width + gap + 4, a.height + 22, "B");
  }
  // Both pictures are made before either is written: a bad view leaves neither behind.
  if (!pictures.heatmap.empty())
    write_encoded_atomic(pictures.heatmap, heat.width, heat.height, 3, heat.rgb, true);
  if (!pictures.side_by_side.empty())
    write_encoded_atomic(pictures.side_by_side, row.width, row.height, 3, row.rgb, true);
}

}  // namespace arbor::imaging
