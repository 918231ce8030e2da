// `arbor merge`: work units of one render (--passes ranges, --crop windows) combined into the
// image the single render gives, bit for bit.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace arbor::app {

struct MergeRequest {
  std::vector<std::string> parts;  // EXRs with their film states beside them
  std::string exr, png;            // png: empty for none
  std::string ocio_config;         // the run's OCIO config (default_ocio_config())
  bool partial = false;            // --partial: write parts that do not make the whole render
};

// Adds `arbor merge` to `app`, its options bound to `request`.
CLI::App* add_merge_command(CLI::App& app, MergeRequest& request);

// Merges and writes; returns the exit status (0). InputError (exit 2) for parts that are not of
// one render, overlap, or leave a gap, or (unless `partial`) do not cover the whole image and
// every pass; RuntimeFailure when writing fails.
int merge_command(const MergeRequest& request);

}  // namespace arbor::app
