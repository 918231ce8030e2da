// `arbor compare`: error metrics of image A against reference B, the z-test of render tests, the
// TREE-MAKER weight fit, heatmap and side-by-side pictures.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace arbor::app {

struct CompareRequest {
  std::string a, b;
  std::string heatmap, side_by_side;  // pictures to write; empty: none
  std::string display = "sRGB", view = "ACES 1.0 SDR-video";
  bool json = false, reference_test = false, fit_treemaker = false;
  std::string ocio_config;  // the run's OCIO config (default_ocio_config())
};

// Adds `arbor compare` to `app`, its options bound to `request`.
CLI::App* add_compare_command(CLI::App& app, CompareRequest& request);

// Prints the report (text or JSON) on stdout; returns the exit status: 1 when the reference
// test fails, else 0. InputError for bad input.
int compare_command(const CompareRequest& request);

}  // namespace arbor::app
