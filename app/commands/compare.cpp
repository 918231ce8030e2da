// `arbor compare`: read both images, measure, test, fit, draw, report.
#include "app/commands/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/image_library.h"
#include "common/json.h"
#include "imaging/compare.h"
#include "imaging/treemaker_channels.h"
#include "imaging/treemaker_fit.h"

namespace arbor::app {

namespace {

void check_image_output(const std::string& path, const CompareRequest& a, const char* option) {
  if (path.empty()) return;
  refuse_overwriting(option, path, {a.a, a.b});
  if (!image_library("write " + path).writable(path)) {
    throw InputError({}, std::string(option) + " " + path +
                             ": no image format for this extension (use .png, .exr, .tif or .jpg)");
  }
  prepare_output_folder(path);
}

// --fit-treemaker: whichever image carries the treemaker AOVs is the approximate render, the
// other the exact one.
struct FitReport {
  imaging::TreemakerFit fit;
  std::string exact_path, approx_path;
};

FitReport fit_if_asked(const CompareRequest& args, const imaging::CompareImage& a,
                       const imaging::CompareImage& b) {
  FitReport r;
  if (!args.fit_treemaker) return r;
  const bool a_tm = imaging::has_treemaker_aovs(args.a), b_tm = imaging::has_treemaker_aovs(args.b);
  if (a_tm == b_tm) {
    throw InputError({},
                     std::string("--fit-treemaker needs one exact render and one treemaker render "
                                 "with the \"treemaker\" AOVs; ") +
                         (a_tm ? "both images have them" : "neither image has them"));
  }
  r.exact_path = a_tm ? args.b : args.a;
  r.approx_path = a_tm ? args.a : args.b;
  const imaging::CompareImage& exact = a_tm ? b : a;
  if (exact.colorspace.empty()) {
    std::fprintf(stderr,
                 "arbor compare: note: %s does not say its colour space (no arbor:colorspace); "
                 "the fit takes it to be scene-linear in the treemaker render's space\n",
                 r.exact_path.c_str());
  }
  r.fit = imaging::fit_treemaker(exact, imaging::read_treemaker_aovs(r.approx_path));
  return r;
}

void print_json(const CompareRequest& args, const imaging::CompareMetrics& m,
                const imaging::ZTest& z, const FitReport& report) {
  const auto& names = imaging::kTreemakerTermNames;
  const imaging::TreemakerFit& fit = report.fit;
  JsonObject j;
  j.number("rmse", m.rmse).number("mean_abs", m.mean_abs).number("rel_mse", m.rel_mse);
  j.number("max_abs", m.max_abs).integers("max_at", {m.max_x, m.max_y}).number("psnr", m.psnr);
  if (args.reference_test) {
    j.number("z_test_pass_fraction", z.pass_fraction).number("z_critical", z.z_critical);
    j.number("z_dof", z.dof).integer("pixels", z.pixels).integer("failed_pixels", z.failed);
    j.boolean("pixels_passed", z.pixels_passed);
    j.integer("noiseless_blocks_differing", z.noiseless_blocks_differing);
    j.numbers("mean_z", {z.mean_z[0], z.mean_z[1], z.mean_z[2]})
        .number("mean_z_critical", z.mean_z_critical);
    j.boolean("mean_passed", z.mean_passed);
    j.number("block_chi2", z.block_chi2)
        .number("block_dof", z.block_dof)
        .number("block_p", z.block_p);
    j.boolean("blocks_passed", z.blocks_passed).number("variance_ratio", z.variance_ratio);
    j.number("spp_ratio", z.spp_ratio);
    j.boolean("passed", z.passed);
  }
  if (args.fit_treemaker) {
    JsonObject weights, f;
    for (int i = 0; i < 5; ++i) weights.number(names[i], fit.weights[static_cast<size_t>(i)]);
    f.text("exact", report.exact_path)
        .text("approximate", report.approx_path)
        .object("weights", weights);
    f.integer("pixels", fit.pixels).number("rmse", fit.rmse).number("rel_mse", fit.rel_mse);
    f.number("render_rmse", fit.render_rmse).number("render_rel_mse", fit.render_rel_mse);
    f.text("render_weights", fit.render_weights);
    j.object("treemaker_fit", f);
  }
  std::printf("%s\n", j.str().c_str());
}

void print_text(const CompareRequest& args, const imaging::CompareMetrics& m,
                const imaging::ZTest& z, const FitReport& f) {
  const auto& names = imaging::kTreemakerTermNames;
  const imaging::TreemakerFit& fit = f.fit;
  std::printf("rmse      %.6g\nmean_abs  %.6g\nrel_mse   %.6g\nmax_abs   %.6g at (%d, %d)\n",
              m.rmse, m.mean_abs, m.rel_mse, m.max_abs, m.max_x, m.max_y);
  if (std::isfinite(m.psnr)) {
    std::printf("psnr      %.2f dB\n", m.psnr);
  } else {
    std::printf("psnr      inf (identical)\n");
  }
  if (args.reference_test) {
    std::printf(
        "z-test    pixels: %.3f %% of %lld pass (|z| <= %.2f: alpha 0.01, Sidak-corrected, t with "
        "%g dof); needs %.1f %%: %s\n",
        100.0 * z.pass_fraction, z.pixels, z.z_critical, z.dof, 100.0 * z.required,
        z.pixels_passed ? "pass" : "FAIL");
    std::printf("          image mean: z = %.2f %.2f %.2f (|z| <= %.2f: alpha %g): %s\n",
                z.mean_z[0], z.mean_z[1], z.mean_z[2], z.mean_z_critical, z.alpha_pooled,
                z.mean_passed ? "pass" : "FAIL");
    std::printf("          16x16 blocks: chi-square %.1f on %g dof, p = %.3g (alpha %g)%s: %s\n",
                z.block_chi2, z.block_dof, z.block_p, z.alpha_pooled,
                z.noiseless_blocks_differing > 0
                    ? (", and " + std::to_string(z.noiseless_blocks_differing) +
                       " block channels differ where neither image has noise")
                          .c_str()
                    : "",
                z.blocks_passed ? "pass" : "FAIL");
    std::printf(
        "          A is %.3g times as noisy as B (variance; in each block at least %.3g times B's, "
        "their spp ratio); %s\n",
        z.variance_ratio, z.spp_ratio, z.passed ? "PASS" : "FAIL");
  }
  if (args.fit_treemaker) {
    std::printf("treemaker fit of %s to the exact %s, over the %lld pixels that show a tree:\n",
                f.approx_path.c_str(), f.exact_path.c_str(), fit.pixels);
    std::printf("  fitted weights  ");
    for (int i = 0; i < 5; ++i)
      std::printf(" %s=%.4g", names[i], fit.weights[static_cast<size_t>(i)]);
    std::printf("\n  fitted          rmse %.6g  rel_mse %.6g\n", fit.rmse, fit.rel_mse);
    std::printf("  as rendered     rmse %.6g  rel_mse %.6g  (%s)\n", fit.render_rmse,
                fit.render_rel_mse,
                fit.render_weights.empty() ? "weights unknown" : fit.render_weights.c_str());
    for (int i = 0; i < 5; ++i) {
      if (!fit.determined[static_cast<size_t>(i)]) {
        std::printf(
            "  note: the %s factor is 0 wherever a tree is seen, so its weight is not determined\n",
            names[i]);
      }
    }
    std::printf("  as a scene table:\n  [tree.treemaker]\n");
    for (int i = 0; i < 5; ++i)
      std::printf("  %s = %.4f\n", names[i], fit.weights[static_cast<size_t>(i)]);
  }
}

// Notes and warnings on stderr about what limits the test's power or its false-alarm rate.
void print_notes(const CompareRequest& args, const imaging::CompareImage& a,
                 const imaging::CompareImage& b, const imaging::ZTest& z) {
  if (args.reference_test && z.a_has_variance && a.passes >= 2 && a.passes < 8) {
    std::fprintf(
        stderr,
        "arbor compare: note: %s has %d passes: its variance is estimated from %d degree%s of "
        "freedom a pixel, and a block whose noise sits in a few pixels can fail by chance; "
        "render it in at least 8 passes (pass_spp = spp / 8)\n",
        args.a.c_str(), a.passes, a.passes - 1, a.passes == 2 ? "" : "s");
  }
  if (args.reference_test && b.passes >= 1 && b.passes < 8) {
    std::fprintf(
        stderr,
        "arbor compare: warning: the reference %s has %d pass%s: its variance is estimated from "
        "%d degree%s of freedom a pixel, below the 8 passes the test's false-alarm rate was "
        "measured for (docs/rendering.md); render references in at least 8 independent passes\n",
        args.b.c_str(), b.passes, b.passes == 1 ? "" : "es", std::max(0, b.passes - 1),
        b.passes == 2 ? "" : "s");
  }
  for (const imaging::CompareImage* im : {&a, &b}) {
    if (args.reference_test && im->sequence_passes && !im->variance.empty()) {
      std::fprintf(
          stderr,
          "arbor compare: note: %s took its passes from one sequence, so its variance is an "
          "upper bound and the test is conservative (less power); render with [render] "
          "independent_passes = true for the honest variance\n",
          im->path.c_str());
    }
  }
  if (args.reference_test && !z.a_has_variance) {
    std::fprintf(stderr,
                 "arbor compare: note: %s has no variance channels; the test used the "
                 "reference's variance alone\n",
                 args.a.c_str());
  }
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app, CompareRequest& cmp) {
  CLI::App* cmd = app.add_subcommand(
      "compare", "Compare image A against reference B: error metrics, heatmap, z-test");
  cmd->add_option("A", cmp.a, "image to test (EXR, or any format OIIO reads)")->required();
  cmd->add_option("B", cmp.b, "reference image (with variance.R/G/B for --reference-test)")
      ->required();
  cmd->add_option("--heatmap", cmp.heatmap,
                  "write a false-colour image of the per-pixel error with a scale bar");
  cmd->add_option("--side-by-side", cmp.side_by_side,
                  "write A, B and the heatmap in one picture through the display view");
  cmd->add_option("--display", cmp.display, "OCIO display for --side-by-side")
      ->capture_default_str();
  cmd->add_option("--view", cmp.view, "OCIO view for --side-by-side")->capture_default_str();
  cmd->add_flag("--json", cmp.json, "print the metrics as one JSON object");
  cmd->add_flag("--reference-test", cmp.reference_test,
                "test A against B's variance in three parts: a per-pixel z-test (alpha 0.01, "
                "Sidak-corrected; at least 99.5 % of pixels must pass), each channel's image "
                "mean, and a chi-square of the 16x16 block means (alpha 0.005 each); exit 0 "
                "when all three pass, 1 otherwise");
  cmd->add_flag("--fit-treemaker", cmp.fit_treemaker,
                "fit the five TREE-MAKER weights by least squares: one image is an exact "
                "render, the other a treemaker render of the same view with the \"treemaker\" "
                "AOVs; prints the weights and the error left");
  return cmd;
}

int compare_command(const CompareRequest& args) {
  check_image_output(args.heatmap, args, "--heatmap");
  check_image_output(args.side_by_side, args, "--side-by-side");
  if (!args.heatmap.empty()) refuse_overwriting("--heatmap", args.heatmap, {}, {args.side_by_side});
  const imaging::CompareImage a = imaging::read_compare_image(args.a);
  const imaging::CompareImage b = imaging::read_compare_image(args.b);
  if (a.display_encoded != b.display_encoded) {
    // Issue 15: a PNG against its own EXR measured 17.6 dB of "error" that was only the encoding.
    const imaging::CompareImage& shown = a.display_encoded ? a : b;
    const imaging::CompareImage& linear = a.display_encoded ? b : a;
    throw InputError({}, shown.path +
                             " holds display-encoded integer pixels (a PNG's sRGB values) and " +
                             linear.path +
                             " scene-linear floats (an EXR): they are different quantities. "
                             "Compare the EXRs, or two PNGs (render both with --png)");
  }
  const imaging::CompareMetrics m = imaging::compare_images(a, b);
  imaging::ZTest z;
  if (args.reference_test) z = imaging::reference_z_test(a, b);
  const FitReport fit = fit_if_asked(args, a, b);
  imaging::write_compare_pictures(
      a, b, {args.heatmap, args.side_by_side, args.display, args.view, args.ocio_config});
  if (args.json) {
    print_json(args, m, z, fit);
  } else {
    print_text(args, m, z, fit);
  }
  print_notes(args, a, b, z);
  return args.reference_test && !z.passed ? 1 : 0;
}

}  // namespace arbor::app
