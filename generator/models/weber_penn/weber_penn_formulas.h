// The equations of Weber & Penn 1995 §4 as free functions, one per formula family.
#pragma once

namespace arbor::generator::wp {

// The pruning envelope of §4.6 (Figure 2): width peak position and the two curvature powers.
struct Envelope {
  double width_peak = 0.5;
  double power_low = 0.5;
  double power_high = 0.5;
};

// §4.3 ShapeRatio(shape, ratio) for shapes 0–7, and 8 (envelope, §4.6).
double shape_ratio(int shape, double ratio, const Envelope& envelope = {});

// §4.6 ShapeRatio(8, ratio): 0 outside [0, 1]; 1 at ratio = 1 - width_peak.
double envelope_ratio(double ratio, const Envelope& envelope);

// §4.6 'inside' test for a point in tree coordinates (metres, before ZScale).
bool inside_envelope(double x, double y, double z, double scale_tree, double base_size,
                     double prune_width, const Envelope& envelope);

// §4.4 radius at normalised position z along a stem of base radius `radius` and length `length`,
// for nTaper in [0, 3]: 0 cylinder, 1 cone, 2 spherical end, 3 periodic (concatenated spheres).
double taper_radius(double taper, double radius, double length, double z);

// §4.4 flare: scale of the trunk radius at normalised height z, 1 + Flare at the base.
double flare_scale(double flare, double z);

// §4.4 lobes: scale of the trunk radius at azimuth `angle` (radians) about the stem axis.
double lobe_scale(int lobes, double lobe_depth, double angle);

// §4.3 number of children of a level-1 stem (the trunk's children): stems_max is the child
// level's nBranches, length_max the stem's own sampled nLength ± nLengthV.
double children_of_first_level(double stems_max, double length, double parent_length,
                               double length_max);

// §4.3 number of children of a stem at level ≥ 2 at `offset` metres along its parent.
double children_of_deeper_level(double stems_max, double offset, double parent_length);

// §4.5 leaves on a stem at `offset` metres along its parent.
double leaves_per_branch(double leaves, double offset, double parent_length, double quality);

// §4.3 length of a level-1 stem at `offset` metres along the trunk.
double first_level_length(int shape, double trunk_length, double length_max, double offset,
                          double base_length, const Envelope& envelope);

// §4.3 length of a stem at level ≥ 2.
double deeper_level_length(double length_max, double parent_length, double offset);

// §4.3 down angle (degrees) when nDownAngleV < 0: varies along the parent.
double down_angle_along_parent(double down_angle, double down_angle_v, double parent_length,
                               double offset, double base_length);

// §4.2 split angle (degrees): (SplitAngle ± V) - declination, at least 0.
double split_angle(double split_angle_sampled, double declination_degrees);

// §4.2 magnitude (degrees) of the spread of a stem and its clone about the tree's z axis, given
// a uniform random number u in [0, 1).
double split_spread(double declination_degrees, double u);

// §4.2 Floyd–Steinberg style error diffusion of fractional split counts (one state per level).
struct SplitDiffusion {
  double error = 0.0;
  // Returns the integer number of clones for one segment and updates the error.
  int next(double seg_splits);
};

// §4.7 sway angles (degrees) at normalised position z on a stem, time in seconds.
struct Sway {
  double x = 0.0;
  double y = 0.0;
};
Sway sway_angles(double wind_speed, double wind_gust, double stem_length, double stem_radius,
                 double radius_z, double z, int curve_res, double time, double offset_x,
                 double offset_y);

// §4.8 vertical attraction (radians) for one segment: declination and orientation from the
// z-components of the segment frame's z and y axes.
double attraction_up(double attraction, double z_of_z, double z_of_y, int curve_res);

}  // namespace arbor::generator::wp
