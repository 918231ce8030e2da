// Weber & Penn 1995 §4 equations. Each function cites its section; choices where the paper is
// ambiguous are stated next to the code and in docs/species-format.md.
#include "generator/models/weber_penn/weber_penn_formulas.h"

#include <algorithm>
#include <cmath>
#include "common/math.h"

namespace arbor::generator::wp {

double envelope_ratio(double ratio, const Envelope& e) {
  // §4.6: ShapeRatio(8, ratio) is 0 outside [0, 1].
  if (!(ratio >= 0.0 && ratio <= 1.0)) return 0.0;
  const double upper = 1.0 - e.width_peak;  // ratio runs from 0 at the top to 1 at the bottom
  if (ratio < upper) {
    return std::pow(ratio / upper, e.power_high);
  }
  // The paper prints (1 - ratio) / (1 - PruneWidthPeak) here, which is not 1 at the peak unless
  // PruneWidthPeak = 0.5; the envelope of Figure 2 is continuous, so we divide by PruneWidthPeak.
  if (e.width_peak <= 0.0) return 1.0;
  return std::pow((1.0 - ratio) / e.width_peak, e.power_low);
}

double shape_ratio(int shape, double r, const Envelope& envelope) {
  // §4.3, table of ShapeRatio(shape, ratio).
  switch (shape) {
    case 0: return 0.2 + 0.8 * r;                         // conical
    case 1: return 0.2 + 0.8 * std::sin(kPi * r);         // spherical
    case 2: return 0.2 + 0.8 * std::sin(0.5 * kPi * r);   // hemispherical
    case 3: return 1.0;                                   // cylindrical
    case 4: return 0.5 + 0.5 * r;                         // tapered cylindrical
    case 5: return r <= 0.7 ? r / 0.7 : (1.0 - r) / 0.3;  // flame
    case 6: return 1.0 - 0.8 * r;                         // inverse conical
    case 7: return r <= 0.7 ? 0.5 + 0.5 * r / 0.7 : 0.5 + 0.5 * (1.0 - r) / 0.3;  // tend flame
    case 8: return envelope_ratio(r, envelope);                                   // envelope
    default: return 1.0;
  }
}

bool inside_envelope(double x, double y, double z, double scale_tree, double base_size,
                     double prune_width, const Envelope& envelope) {
  // §4.6. The paper prints r = sqrt(x² + y² + z²), which would put every high point outside any
  // envelope narrower than the tree is tall; Figure 2 measures the width horizontally, so r is
  // the horizontal distance from the tree's axis.
  const double r = std::sqrt(x * x + y * y);
  const double ratio = (scale_tree - z) / (scale_tree * (1.0 - base_size));
  return r / scale_tree < prune_width * envelope_ratio(ratio, envelope);
}

double taper_radius(double taper, double radius, double length, double z) {
  // §4.4 stem radius.
  double unit_taper = 0.0;
  if (taper < 1.0)
    unit_taper = taper;
  else if (taper < 2.0)
    unit_taper = 2.0 - taper;
  const double taper_z = radius * (1.0 - unit_taper * z);
  if (taper < 1.0) return taper_z;
  if (taper_z <= 0.0) return 0.0;

  const double z2 = (1.0 - z) * length;  // distance from the tip
  const double depth = (taper < 2.0 || z2 < taper_z) ? 1.0 : taper - 2.0;
  double z3 = z2;
  if (taper >= 2.0) {
    z3 = std::fabs(z2 - 2.0 * taper_z * std::floor(z2 / (2.0 * taper_z) + 0.5));
  }
  if (taper < 2.0 && z3 >= taper_z) return taper_z;
  const double d = z3 - taper_z;
  return (1.0 - depth) * taper_z + depth * std::sqrt(std::max(0.0, taper_z * taper_z - d * d));
}

double flare_scale(double flare, double z) {
  // §4.4: y = 1 - 8z limited to ≥ 0; flareZ = Flare * (100^y - 1) / 100 + 1.
  const double y = std::max(0.0, 1.0 - 8.0 * z);
  return flare * (std::pow(100.0, y) - 1.0) / 100.0 + 1.0;
}

double lobe_scale(int lobes, double lobe_depth, double angle) {
  // §4.4: lobeZ = 1 + LobeDepth * sin(Lobes * angle).
  return 1.0 + lobe_depth * std::sin(lobes * angle);
}

double children_of_first_level(double stems_max, double length, double parent_length,
                               double length_max) {
  // §4.3: stems = stems_max * (0.2 + 0.8 * (length_child / length_parent) / length_child,max).
  if (parent_length <= 0.0 || length_max <= 0.0) return 0.0;
  return stems_max * (0.2 + 0.8 * (length / parent_length) / length_max);
}

double children_of_deeper_level(double stems_max, double offset, double parent_length) {
  // §4.3: stems = stems_max * (1.0 - 0.5 * offset_child / length_parent).
  if (parent_length <= 0.0) return stems_max;
  return stems_max * (1.0 - 0.5 * offset / parent_length);
}

double leaves_per_branch(double leaves, double offset, double parent_length, double quality) {
  // §4.5: Leaves * ShapeRatio(4, offset_child / length_parent) * quality. A stem without a parent
  // (leaves straight on the trunk, Levels = 1) uses ratio 1.
  const double ratio = parent_length > 0.0 ? offset / parent_length : 1.0;
  return leaves * shape_ratio(4, ratio) * quality;
}

double first_level_length(int shape, double trunk_length, double length_max, double offset,
                          double base_length, const Envelope& envelope) {
  // §4.3: length_trunk * length_child,max *
  //       ShapeRatio(Shape, (length_trunk - offset_child) / (length_trunk - length_base)).
  const double span = trunk_length - base_length;
  if (span <= 0.0) return 0.0;
  return trunk_length * length_max * shape_ratio(shape, (trunk_length - offset) / span, envelope);
}

double deeper_level_length(double length_max, double parent_length, double offset) {
  // §4.3: length_child,max * (length_parent - 0.6 * offset_child).
  return length_max * (parent_length - 0.6 * offset);
}

double down_angle_along_parent(double down_angle, double down_angle_v, double parent_length,
                               double offset, double base_length) {
  // §4.3, nDownAngleV < 0. The paper writes "nDownAngle ± [...]"; with the variation carried by
  // the negative nDownAngleV and spread along the parent, we read "±" as "+" (no random part).
  const double span = parent_length - base_length;
  const double ratio = span > 0.0 ? (parent_length - offset) / span : 0.0;
  return down_angle + down_angle_v * (1.0 - 2.0 * shape_ratio(0, ratio));
}

double split_angle(double split_angle_sampled, double declination_degrees) {
  // §4.2: angle_split = (nSplitAngle ± nSplitAngleV) - declination, limited to ≥ 0.
  return std::max(0.0, split_angle_sampled - declination_degrees);
}

double split_spread(double declination_degrees, double u) {
  // §4.2: 20 + 0.75 * (30 + |declination - 90|) * RANDOM(0..1)².
  return 20.0 + 0.75 * (30.0 + std::fabs(declination_degrees - 90.0)) * u * u;
}

int SplitDiffusion::next(double seg_splits) {
  // §4.2: effective = round(nSegSplits + error); error -= effective - nSegSplits.
  const int effective = static_cast<int>(std::floor(seg_splits + error + 0.5));
  error -= effective - seg_splits;
  return std::max(0, effective);
}

Sway sway_angles(double wind_speed, double wind_gust, double stem_length, double stem_radius,
                 double radius_z, double z, int curve_res, double time, double offset_x,
                 double offset_y) {
  // §4.7 wind sway.
  Sway s;
  if ((wind_speed == 0.0 && wind_gust == 0.0) || radius_z <= 0.0 || stem_length <= 0.0) return s;
  const double a0 = 4.0 * stem_length * (1.0 - z) / radius_z;  // degrees
  const double a1 = wind_speed / 50.0 * a0;
  const double a2 = wind_gust / 50.0 * a0 + a1 / 2.0;
  // The paper prints radius_stem / length_stem × time / 15, which sways a 12 m trunk of radius
  // 0.25 m with a period of 2 hours and a twig in 3 hours: nothing moves in an animation. arbor
  // reads it as length / radius (an erratum, our choice, docs/species-format.md): periods of about
  // 2 s for that trunk and 1 s for a twig, thinner and longer stems swaying faster, as real
  // branches do (their natural frequencies are a few tenths of a hertz to a few hertz).
  const double rate = stem_length / std::max(stem_radius, 1e-6) * time / 15.0;  // radians
  const double bx = offset_x + rate;
  const double by = offset_y + rate;
  s.x = (a1 * std::sin(bx) + a2 * std::sin(0.7 * bx)) / curve_res;
  s.y = (a1 * std::sin(by) + a2 * std::sin(0.7 * by)) / curve_res;
  return s;
}

double attraction_up(double attraction, double z_of_z, double z_of_y, int curve_res) {
  // §4.8: declination = acos(transform_zz), orientation = acos(transform_yz),
  //       curve_up = AttractionUp * declination * cos(orientation) / nCurveRes.
  const double declination = std::acos(std::clamp(z_of_z, -1.0, 1.0));
  const double cos_orientation = std::clamp(z_of_y, -1.0, 1.0);
  return attraction * declination * cos_orientation / curve_res;
}

}  // namespace arbor::generator::wp
