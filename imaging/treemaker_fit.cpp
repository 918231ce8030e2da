// Non-negative least squares of TREE-MAKER's five weights against an exact render.
#include "imaging/treemaker_fit.h"

#include <cmath>
#include <limits>

#include "common/error.h"
#include "imaging/image_file.h"
#include "imaging/treemaker_channels.h"

namespace arbor::imaging {

namespace {

constexpr int kFactors = 5;
const char* const kRgb[3] = {".R", ".G", ".B"};

std::string contribution_channel(int factor, int c) {
  return std::string("tm_") + kTreemakerTermNames[factor] + kRgb[c];
}

// Solves the symmetric positive-definite system G w = b restricted to the factors in `subset`
// (a bit mask) by Cholesky; false when that restriction is singular.
bool solve_subset(const double g[kFactors][kFactors], const double b[kFactors], unsigned subset,
                  std::array<double, kFactors>& w) {
  int idx[kFactors], n = 0;
  for (int i = 0; i < kFactors; ++i) {
    if (subset & (1u << i)) idx[n++] = i;
  }
  double l[kFactors][kFactors] = {};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j <= i; ++j) {
      double s = g[idx[i]][idx[j]];
      for (int k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
      if (i == j) {
        // Relative to the diagonal: a factor that another one (nearly) repeats is singular here.
        if (s <= 1e-12 * g[idx[i]][idx[i]] || s <= 0.0) return false;
        l[i][i] = std::sqrt(s);
      } else {
        l[i][j] = s / l[j][j];
      }
    }
  }
  double y[kFactors];
  for (int i = 0; i < n; ++i) {
    double s = b[idx[i]];
    for (int k = 0; k < i; ++k) s -= l[i][k] * y[k];
    y[i] = s / l[i][i];
  }
  w.fill(0.0);
  for (int i = n - 1; i >= 0; --i) {
    double s = y[i];
    for (int k = i + 1; k < n; ++k) s -= l[k][i] * w[static_cast<std::size_t>(idx[k])];
    w[static_cast<std::size_t>(idx[i])] = s / l[i][i];
  }
  return true;
}

// XᵀX, Xᵀy and yᵀy over the rows (pixel, channel) of the pixels that show a tree, with
// y = exact − rest and X the contributions; `pixels` counts those pixels.
struct NormalEquations {
  double g[kFactors][kFactors] = {};
  double b[kFactors] = {};
  double yy = 0.0;
};

NormalEquations normal_equations(const CompareImage& exact, const TreemakerAovs& tm,
                                 long long& pixels) {
  NormalEquations ne;
  const std::size_t n = static_cast<std::size_t>(tm.width) * tm.height;
  for (std::size_t p = 0; p < n; ++p) {
    if (tm.coverage[p] <= 0.0f) continue;
    ++pixels;
    for (int c = 0; c < 3; ++c) {
      const double y = double(exact.rgb[3 * p + c]) - tm.rest[3 * p + c];
      const float* x = &tm.contribution[p * kFactors * 3 + static_cast<std::size_t>(c)];
      for (int i = 0; i < kFactors; ++i) {
        ne.b[i] += double(x[3 * i]) * y;
        for (int j = 0; j <= i; ++j) ne.g[i][j] += double(x[3 * i]) * x[3 * j];
      }
      ne.yy += y * y;
    }
  }
  for (int i = 0; i < kFactors; ++i) {
    for (int j = i + 1; j < kFactors; ++j) ne.g[i][j] = ne.g[j][i];
  }
  return ne;
}

// The non-negative optimum is the unconstrained least-squares solution on its own support: try
// all 31 supports, keep the feasible one with the smallest residual (all zero if none beats it).
std::array<double, kFactors> non_negative_solution(const NormalEquations& ne) {
  std::array<double, kFactors> best_w{};
  double best = ne.yy;  // the empty support
  for (unsigned subset = 1; subset < (1u << kFactors); ++subset) {
    std::array<double, kFactors> w;
    if (!solve_subset(ne.g, ne.b, subset, w)) continue;
    bool feasible = true;
    for (double v : w) feasible = feasible && v >= 0.0;
    if (!feasible) continue;
    // At a least-squares solution the residual is yᵀy − wᵀb.
    double wb = 0.0;
    for (int i = 0; i < kFactors; ++i) wb += w[static_cast<std::size_t>(i)] * ne.b[i];
    if (ne.yy - wb < best) {
      best = ne.yy - wb;
      best_w = w;
    }
  }
  return best_w;
}

// The fitted image and the errors of it and of the render as rendered, from the pixels
// themselves (no cancellation as in yᵀy − wᵀb), over the pixels that show a tree.
void measure_errors(const CompareImage& exact, const TreemakerAovs& tm, TreemakerFit& fit) {
  const std::size_t n = static_cast<std::size_t>(tm.width) * tm.height;
  fit.fitted.resize(3 * n);
  double se = 0.0, rel = 0.0, se_render = 0.0, rel_render = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    for (int c = 0; c < 3; ++c) {
      double v = tm.rest[3 * p + c];
      for (int i = 0; i < kFactors; ++i) {
        v += fit.weights[static_cast<std::size_t>(i)] * tm.contribution[(p * kFactors + i) * 3 + c];
      }
      fit.fitted[3 * p + c] = static_cast<float>(v);
      if (tm.coverage[p] <= 0.0f) continue;
      const double ref = exact.rgb[3 * p + c];
      const double d = v - ref, d_render = double(tm.beauty[3 * p + c]) - ref;
      se += d * d;
      rel += d * d / (ref * ref + 0.01);
      se_render += d_render * d_render;
      rel_render += d_render * d_render / (ref * ref + 0.01);
    }
  }
  const double rows = 3.0 * static_cast<double>(fit.pixels);
  fit.rmse = std::sqrt(se / rows);
  fit.rel_mse = rel / rows;
  fit.render_rmse = std::sqrt(se_render / rows);
  fit.render_rel_mse = rel_render / rows;
}

}  // namespace

bool has_treemaker_aovs(const std::string& path) {
  DecodedImage header;
  if (!image_library("read " + path).read(path, false, header).empty()) return false;
  for (const std::string& name : treemaker_channel_names()) {
    bool found = false;
    for (const std::string& c : header.channel_names) found = found || c == name;
    if (!found) return false;
  }
  return true;
}

TreemakerAovs read_treemaker_aovs(const std::string& path) {
  const ImageChannels image = read_image_channels(path);
  TreemakerAovs t;
  t.path = path;
  t.width = image.image.width;
  t.height = image.image.height;
  t.colorspace = image.image.attribute("arbor:colorspace");
  t.weights = image.image.attribute("arbor:treemaker_weights");
  auto need = [&](const std::string& name) {
    const int c = image.index(name);
    if (c < 0) {
      throw InputError({path, 0, 0},
                       "has no channel " + name +
                           "; --fit-treemaker needs a render "
                           "made with --integrator treemaker and output.aovs = [\"treemaker\"]");
    }
    return c;
  };
  int beauty[3], rest[3], contribution[kFactors][3];
  for (int c = 0; c < 3; ++c) {
    beauty[c] = need(std::string(1, "RGB"[c]));
    rest[c] = need(std::string("tm_rest") + kRgb[c]);
    for (int i = 0; i < kFactors; ++i) contribution[i][c] = need(contribution_channel(i, c));
  }
  const int coverage = need("term_ambient.X");
  const std::size_t n = static_cast<std::size_t>(t.width) * t.height;
  t.beauty.resize(3 * n);
  t.rest.resize(3 * n);
  t.coverage.resize(n);
  t.contribution.resize(n * kFactors * 3);
  for (std::size_t p = 0; p < n; ++p) {
    t.coverage[p] = image.finite(p, coverage, "term_ambient.X of ");
    for (int c = 0; c < 3; ++c) {
      t.beauty[3 * p + c] = image.finite(p, beauty[c], "");
      t.rest[3 * p + c] = image.finite(p, rest[c], "tm_rest of ");
      for (int i = 0; i < kFactors; ++i) {
        t.contribution[(p * kFactors + i) * 3 + c] =
            image.finite(p, contribution[i][c], "a tm_ channel of ");
      }
    }
  }
  return t;
}

TreemakerFit fit_treemaker(const CompareImage& exact, const TreemakerAovs& tm) {
  if (exact.width != tm.width || exact.height != tm.height) {
    throw InputError({tm.path, 0, 0}, "is " + std::to_string(tm.width) + "x" +
                                          std::to_string(tm.height) + " but " + exact.path +
                                          " is " + std::to_string(exact.width) + "x" +
                                          std::to_string(exact.height) +
                                          "; the fit needs two renders of the same view");
  }
  if (!exact.colorspace.empty() && !tm.colorspace.empty() && exact.colorspace != tm.colorspace) {
    throw InputError({tm.path, 0, 0}, "is in " + tm.colorspace + " but " + exact.path + " is in " +
                                          exact.colorspace +
                                          "; render both to the same colour space");
  }
  TreemakerFit fit;
  const NormalEquations ne = normal_equations(exact, tm, fit.pixels);
  if (fit.pixels == 0) {
    throw InputError({tm.path, 0, 0},
                     "shows no tree (term_ambient.X is 0 everywhere): nothing to fit");
  }
  for (int i = 0; i < kFactors; ++i) fit.determined[static_cast<std::size_t>(i)] = ne.g[i][i] > 0.0;
  fit.weights = non_negative_solution(ne);
  measure_errors(exact, tm, fit);
  fit.render_weights = tm.weights;
  return fit;
}

}  // namespace arbor::imaging
