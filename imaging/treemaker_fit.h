// Fitting TREE-MAKER's five shading weights (Neighbors & Hodges §III, Figure 3) to an exact
// render: how close the approximate model can come for a tree and a view.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "imaging/compare.h"

namespace arbor::imaging {

// A treemaker render's AOVs as `arbor render --integrator treemaker` writes them with
// output.aovs = ["treemaker"]: per pixel the beauty, the tree's coverage (term_ambient.X), each
// factor's contribution at weight 1 (tm_<factor>.R/G/B) and the rest (tm_rest.R/G/B), so that
// beauty = rest + Σ weight_i × contribution_i.
struct TreemakerAovs {
  std::string path;
  std::string colorspace;
  std::string weights;  // arbor:treemaker_weights of the render
  int width = 0, height = 0;
  std::vector<float> beauty;        // width*height*3
  std::vector<float> coverage;      // width*height
  std::vector<float> contribution;  // width*height*5*3: [pixel][factor][channel]
  std::vector<float> rest;          // width*height*3
};

// True when the file has the treemaker AOV channels (without reading its pixels).
bool has_treemaker_aovs(const std::string& path);

// InputError when the file cannot be read, lacks a channel, or holds a NaN or infinity.
TreemakerAovs read_treemaker_aovs(const std::string& path);

struct TreemakerFit {
  // ambient, lambert, height, radius, angle: the non-negative least-squares fit (TREE-MAKER's
  // weights are non-negative shares of the shade).
  std::array<double, 5> weights{};
  std::array<bool, 5> determined{};  // false: the factor is 0 wherever a tree is seen
  long long pixels = 0;              // pixels where a tree is seen (coverage > 0): the fit's rows
  double rmse = 0.0, rel_mse = 0.0;  // of the fitted image against the exact one, those pixels
  double render_rmse = 0.0, render_rel_mse = 0.0;  // of the treemaker render's own beauty
  std::string render_weights;                      // the render's weights (arbor:treemaker_weights)
  std::vector<float> fitted;  // the fitted image (width*height*3): rest + Σ w_i × tm_i
};

// Least squares over every pixel a tree covers and every channel of
//   exact − rest ≈ Σ_i w_i × contribution_i,  w_i ≥ 0,
// solved exactly by trying every subset of the five factors (the optimum is the unconstrained
// solution on its support). Errors: InputError when the sizes or colour spaces differ or no
// pixel shows a tree.
TreemakerFit fit_treemaker(const CompareImage& exact, const TreemakerAovs& approximate);

}  // namespace arbor::imaging
