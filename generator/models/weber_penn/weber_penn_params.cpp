// The Weber & Penn parameter table: names as in the paper's appendix, bounds, and storage.
#include "generator/models/weber_penn/weber_penn_params.h"

#include "generator/models/weber_penn/weber_penn.h"

#include <cmath>
#include <cstdio>

#include "generator/geometry/leaf_shapes.h"

namespace arbor::generator {

namespace {

using P = WeberPennParams;
using L = WeberPennLevel;

ParamInfo real(std::string_view name, double lo, double hi, double P::*m, std::string_view d) {
  ParamInfo i;
  i.name = name;
  i.min = lo;
  i.max = hi;
  i.real = m;
  i.description = d;
  return i;
}
ParamInfo whole(std::string_view name, double lo, double hi, int P::*m, std::string_view d) {
  ParamInfo i;
  i.name = name;
  i.integer = true;
  i.min = lo;
  i.max = hi;
  i.whole = m;
  i.description = d;
  return i;
}
ParamInfo level_real(std::string_view name, double lo, double hi, double L::*m,
                     std::string_view d) {
  ParamInfo i;
  i.name = name;
  i.min = lo;
  i.max = hi;
  i.level_real = m;
  i.description = d;
  return i;
}
ParamInfo level_whole(std::string_view name, double lo, double hi, int L::*m, std::string_view d) {
  ParamInfo i;
  i.name = name;
  i.integer = true;
  i.min = lo;
  i.max = hi;
  i.level_whole = m;
  i.description = d;
  return i;
}
ParamInfo only_level0(ParamInfo i) {
  i.level0_only = true;
  return i;
}
ParamInfo only_children(ParamInfo i) {
  i.children_only = true;
  return i;
}

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

const std::vector<ParamInfo>& tree_param_table() {
  static const std::vector<ParamInfo> table = {
      whole("Shape", 0, 8, &P::shape, "general tree shape id (0-8, 8 = pruning envelope)"),
      real("BaseSize", 0, 1, &P::base_size, "fractional branchless area at the tree base"),
      real("Scale", 0.01, 500, &P::scale, "size of the tree (metres)"),
      real("ScaleV", 0, 500, &P::scale_v, "variation of Scale (metres)"),
      real("ZScale", 0.01, 100, &P::z_scale, "vertical scaling of the whole tree"),
      real("ZScaleV", 0, 100, &P::z_scale_v, "variation of ZScale"),
      whole("Levels", 1, 9, &P::levels, "levels of recursion (stems; leaves are one more)"),
      real("Ratio", 1e-6, 1, &P::ratio, "trunk radius / length"),
      real("RatioPower", 0, 10, &P::ratio_power, "reduction of radius for children"),
      whole("Lobes", 0, 100, &P::lobes, "peaks in the trunk's cross-section"),
      real("LobeDepth", 0, 1, &P::lobe_depth, "depth of the lobes, fraction of the radius"),
      real("Flare", 0, 10, &P::flare, "exponential expansion at the base of the trunk"),
      real("Leaves", -10000, 10000, &P::leaves, "leaves per stem of the last level; < 0: fan"),
      whole("LeafShape", 0, 5, &P::leaf_shape, "leaf shape id (see the species format docs)"),
      real("LeafScale", 1e-4, 100, &P::leaf_scale, "leaf length (metres)"),
      real("LeafScaleX", 1e-3, 100, &P::leaf_scale_x, "leaf width relative to length"),
      real("LeafBend", 0, 1, &P::leaf_bend, "fraction of §4.9 orientation toward the light"),
      real("AttractionUp", -100, 100, &P::attraction_up, "upward growth; < 0 droops"),
      real("PruneRatio", 0, 1, &P::prune_ratio, "fractional effect of pruning"),
      real("PruneWidth", 1e-3, 100, &P::prune_width, "width of the envelope / Scale"),
      real("PruneWidthPeak", 0, 1, &P::prune_width_peak, "height of the widest point"),
      real("PrunePowerLow", 0, 100, &P::prune_power_low, "envelope curvature below the peak"),
      real("PrunePowerHigh", 0, 100, &P::prune_power_high, "envelope curvature above the peak"),
      real("WindSpeed", 0, 200, &P::wind_speed, "§4.7 wind speed"),
      real("WindGust", 0, 200, &P::wind_gust, "§4.7 additional gust speed"),
  };
  return table;
}

const std::vector<ParamInfo>& level_param_table() {
  static const std::vector<ParamInfo> table = {
      only_children(level_real("DownAngle", -360, 360, &L::down_angle, "angle from parent")),
      only_children(level_real("DownAngleV", -360, 360, &L::down_angle_v,
                               "variation; < 0: varies along the parent")),
      only_children(level_real("Rotate", -360, 360, &L::rotate, "spiral angle; < 0: alternate")),
      only_children(level_real("RotateV", 0, 360, &L::rotate_v, "variation of Rotate")),
      only_children(level_real("Branches", -10000, 10000, &L::branches,
                               "max children per parent; < 0: fan at the tip")),
      level_real("Length", 0, 100, &L::length, "length relative to the parent (trunk: Scale)"),
      level_real("LengthV", 0, 100, &L::length_v, "variation of Length"),
      level_real("Taper", 0, 3, &L::taper, "0 cylinder, 1 cone, 2 spherical end, 3 periodic"),
      only_level0(level_whole("BaseSplits", 0, 64, &L::base_splits, "clones at the trunk base")),
      level_real("SegSplits", 0, 16, &L::seg_splits, "clones per segment"),
      level_real("SplitAngle", 0, 360, &L::split_angle, "angle of a split"),
      level_real("SplitAngleV", 0, 360, &L::split_angle_v, "variation of SplitAngle"),
      level_whole("CurveRes", 1, 1000, &L::curve_res, "segments per stem"),
      level_real("Curve", -3600, 3600, &L::curve, "curvature (degrees over the stem)"),
      level_real("CurveBack", -3600, 3600, &L::curve_back, "curvature of the second half"),
      level_real("CurveV", -89.9, 3600, &L::curve_v, "curve variation; < 0: helix angle"),
      only_level0(level_real("Scale", 1e-3, 100, &L::scale, "0Scale: extra trunk scaling")),
      only_level0(level_real("ScaleV", 0, 100, &L::scale_v, "0ScaleV: variation of 0Scale")),
  };
  return table;
}

namespace {
const ParamInfo* find_in(const std::vector<ParamInfo>& table, std::string_view name) {
  for (const ParamInfo& info : table) {
    if (info.name == name) return &info;
  }
  return nullptr;
}
}  // namespace

const ParamInfo* find_tree_param(std::string_view name) {
  return find_in(tree_param_table(), name);
}
const ParamInfo* find_level_param(std::string_view name) {
  return find_in(level_param_table(), name);
}

std::string set_param(WeberPennParams& params, const ParamInfo& info, int level, double value) {
  if (!std::isfinite(value)) return std::string(info.name) + " must be a finite number";
  if (info.integer && value != std::floor(value)) {
    return std::string(info.name) + " must be a whole number, not " + number(value);
  }
  if (value < info.min || value > info.max) {
    return std::string(info.name) + " = " + number(value) + " is out of range [" +
           number(info.min) + ", " + number(info.max) + "]";
  }
  if (info.real) params.*info.real = value;
  if (info.whole) params.*info.whole = static_cast<int>(value);
  if (info.level_real || info.level_whole) {
    WeberPennLevel& lv = params.level[static_cast<size_t>(level)];
    if (info.level_real) lv.*info.level_real = value;
    if (info.level_whole) lv.*info.level_whole = static_cast<int>(value);
  }
  return "";
}

std::string check_consistency(const WeberPennParams& p, std::string& key) {
  // A variation may reach the value itself (the paper's CA Black Oak has Scale = ScaleV = 10),
  // never beyond it: a tree of negative size is meaningless.
  if (p.scale_v > p.scale) {
    key = "ScaleV";
    return "ScaleV (" + number(p.scale_v) + ") must not exceed Scale (" + number(p.scale) +
           "): the tree's size would be negative";
  }
  if (p.z_scale_v > p.z_scale) {
    key = "ZScaleV";
    return "ZScaleV must not exceed ZScale";
  }
  if (p.level[0].scale_v > p.level[0].scale) {
    key = "0ScaleV";
    return "0ScaleV must not exceed 0Scale";
  }
  if (p.level[0].length <= 0.0 || p.level[0].length_v > p.level[0].length) {
    key = "0Length";
    return "the trunk needs a length: 0Length must be > 0 and 0LengthV must not exceed it";
  }
  if (p.leaf_shape >= static_cast<int>(leaf_shape_count())) {
    key = "LeafShape";
    return "LeafShape must be below " + std::to_string(leaf_shape_count());
  }
  return "";
}

SizeEstimate estimate_size(const WeberPennParams& p, double quality) {
  SizeEstimate e;
  double families = 1.0;  // stems at this level not counting clones (clones share children)
  for (int level = 0; level < p.levels; ++level) {
    const WeberPennLevel& lv = p.at(level);
    if (level > 0) families *= std::fabs(lv.branches);
    double clone_growth = std::pow(1.0 + lv.seg_splits, std::max(0, lv.curve_res - 1));
    if (level == 0) clone_growth *= 1.0 + lv.base_splits;
    e.stems += families * clone_growth;
  }
  e.leaves = families * std::fabs(p.leaves) * quality;
  return e;
}

}  // namespace arbor::generator
