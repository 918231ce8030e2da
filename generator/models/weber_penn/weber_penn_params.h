// Parameters of the Weber & Penn model (paper appendix), with one table naming and bounding them.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace arbor::generator {

// Per-level parameters; the paper's "nX" names without the level digit.
struct WeberPennLevel {
  double down_angle = 0.0, down_angle_v = 0.0;  // degrees from the parent's axis
  double rotate = 0.0, rotate_v = 0.0;          // degrees about the parent's axis
  double branches = 0.0;                        // children (max); negative: fan at the tip
  double length = 0.0, length_v = 0.0;          // fraction of the parent (trunk: of Scale)
  double taper = 1.0;                           // 0 cylinder, 1 cone, 2 sphere end, 3 periodic
  int base_splits = 0;                          // level 0 only: clones at the base
  double seg_splits = 0.0;                      // clones per segment
  double split_angle = 0.0, split_angle_v = 0.0;
  int curve_res = 1;                                    // segments per stem
  double curve = 0.0, curve_back = 0.0, curve_v = 0.0;  // degrees; curve_v < 0: helix
  double scale = 1.0, scale_v = 0.0;                    // level 0 only: 0Scale, 0ScaleV
};

struct WeberPennParams {
  int shape = 0;
  double base_size = 0.0;
  double scale = 10.0, scale_v = 0.0;
  double z_scale = 1.0, z_scale_v = 0.0;
  int levels = 1;
  double ratio = 0.02, ratio_power = 1.0;
  int lobes = 0;
  double lobe_depth = 0.0;
  double flare = 0.0;
  double leaves = 0.0;
  int leaf_shape = 0;
  double leaf_scale = 0.1, leaf_scale_x = 1.0;
  double leaf_bend = 0.3;  // §4.9 "bend" fraction (not in the appendix; arbor's default)
  double attraction_up = 0.0;
  double prune_ratio = 0.0;
  double prune_width = 0.5, prune_width_peak = 0.5;
  double prune_power_low = 0.5, prune_power_high = 0.5;
  double wind_speed = 0.0, wind_gust = 0.0;  // §4.7 (not in the appendix; no wind by default)
  std::array<WeberPennLevel, 4> level{};

  WeberPennParams() { level[0].length = 1.0; }  // the trunk is Scale long unless told otherwise

  // Levels beyond 3 reuse level 3 (§4.5).
  const WeberPennLevel& at(int n) const { return level[static_cast<size_t>(n < 3 ? n : 3)]; }
};

// One parameter of the file formats: its paper name, type, bounds and where it is stored.
struct ParamInfo {
  std::string_view name;
  bool integer = false;
  double min = 0.0, max = 0.0;
  double WeberPennParams::*real = nullptr;
  int WeberPennParams::*whole = nullptr;
  double WeberPennLevel::*level_real = nullptr;
  int WeberPennLevel::*level_whole = nullptr;
  bool level0_only = false;    // only meaningful for the trunk (0BaseSplits, 0Scale, 0ScaleV)
  bool children_only = false;  // not meaningful for the trunk (DownAngle, Rotate, Branches)
  std::string_view description;
};

// Tree-wide parameters (Shape, BaseSize, …) and per-level parameters (Length, Taper, …).
const std::vector<ParamInfo>& tree_param_table();
const std::vector<ParamInfo>& level_param_table();
const ParamInfo* find_tree_param(std::string_view name);
const ParamInfo* find_level_param(std::string_view name);

// Stores `value` for `info` (at `level` for per-level parameters). Returns "" when accepted,
// else why not (not finite, not a whole number, out of range).
std::string set_param(WeberPennParams& params, const ParamInfo& info, int level, double value);

// Checks rules that involve several parameters. Returns "" or the problem, and in `key` the
// paper name of the parameter to point at (e.g. "ScaleV", "2CurveV").
std::string check_consistency(const WeberPennParams& params, std::string& key);

}  // namespace arbor::generator
