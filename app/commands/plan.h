// `arbor plan`: a render split into work units any scheduler can run (docs/farm.md).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands/options.h"

namespace arbor::app {

// The largest plan: units over all frames, and parts one merge reads (64x64 tiles, say).
constexpr long long kMaxPlanUnits = 100000;
constexpr long long kMaxMergeParts = 4096;

struct PlanRequest {
  std::string scene;
  std::string exr,
      png;  // the merged outputs (with a run of '#' for the frame number when --frames)
  RenderOverrides overrides;  // handed on to every unit as given
  std::string tiles = "1x1";  // CxR: columns × rows of crop windows
  int pass_groups = 1;        // K: contiguous runs of passes per tile
  std::string frames;         // "A:B": frames A to B-1 of the [animation]; empty: a still
  bool json = false;
  std::string arbor;  // the executable the commands run; empty: this one
};

// One work unit or merge: what it makes and the command that makes it.
struct PlanStep {
  std::string kind;                  // "render" or "merge"
  int frame = -1;                    // -1: a still
  int column = 0, row = 0;           // render: the tile
  int pass_begin = 0, pass_end = 0;  // render: passes [begin, end)
  int crop[4] = {0, 0, 0, 0};        // render: X0, Y0, X1, Y1
  std::string output;                // the part (render) or the merged EXR
  std::vector<std::string> inputs;   // merge: the parts
  std::vector<std::string> argv;     // the whole command, argv[0] the executable
};

// Adds `arbor plan` to `app`, its options bound to `request`.
CLI::App* add_plan_command(CLI::App& app, PlanRequest& request);

// The units, then the merges (one per frame). InputError for bad requests.
std::vector<PlanStep> make_plan(const PlanRequest& request);

// `argv` as one POSIX shell command line (words quoted where needed).
std::string shell_line(const std::vector<std::string>& argv);

// Prints the plan (shell lines, or JSON with --json); returns 0.
int plan_command(const PlanRequest& request);

}  // namespace arbor::app
