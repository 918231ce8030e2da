// Procedural bark: a furrowed height field on a limb's surface, in metres.
#pragma once

namespace arbor::materials {

// Height in [0, 1] of furrowed bark at arc length `along` (m), azimuth (radians) and radius (m).
// Evaluated as 3D noise at the surface point of a straightened limb, so it tiles seamlessly round
// the limb, and furrows keep their size in metres on tapered limbs (Bloomenthal §8's goal).
double bark_height(double along, double azimuth, double radius);

// 3D gradient noise in about [-1, 1] (Perlin's improved noise with a hashed lattice).
double gradient_noise(double x, double y, double z);

}  // namespace arbor::materials
