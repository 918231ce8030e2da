// Bark colour that belongs to the bark (issue 29): an albedo driven by the same bark coordinates
// as the bump map, so colour and relief agree — the ridges' albedo on the ridges and the furrows'
// in the furrows, lenticels (short dark dashes across the limb, as on aspen and birch), scars
// (larger dark eyes where branches were shed, on limbs thicker than 3 cm), and a darker, more
// deeply furrowed trunk base. docs/species-format.md gives the keys and their defaults.
#pragma once

#include <glm/vec3.hpp>

namespace arbor::materials {

struct BarkPattern {
  bool furrows = false;           // colour the furrows with furrow_albedo
  glm::vec3 furrow_albedo{0.3f};  // albedo where the bark height is low; the base's colour
  float lenticels = 0.0f;         // per m² of bark (0: none)
  glm::vec3 lenticel_albedo{0.06f, 0.05f, 0.045f};
  float scars = 0.0f;  // per m² of bark on limbs thicker than 3 cm (0: none)
  glm::vec3 scar_albedo{0.05f, 0.045f, 0.04f};
  float base_height = 0.0f;  // metres: below, the trunk darkens and its furrows deepen (0: none)

  bool any() const { return furrows || lenticels > 0.0f || scars > 0.0f || base_height > 0.0f; }
  // How much of the base's darkening applies at height z (m above the ground): 1 at the ground,
  // 0 from base_height up.
  float base(float z) const;
  // The albedo at a point of bark: `ridge` is the bark's own albedo, `height` its bark height in
  // [0, 1] there (bark_noise.h or the bump map), `along`, `azimuth`, `radius` its bark coordinates
  // and z its height above the ground.
  glm::vec3 albedo(const glm::vec3& ridge, double height, double along, double azimuth,
                   double radius, float z) const;
};

// The share of a surface covered by marks of `density` per m², each `width` × `height` metres
// (an ellipse), at bark coordinates (along, around = azimuth × radius): one mark per cell of a
// grid of 1/√density cells, placed in its cell by a hash of the cell; whole cells round the limb.
// Soft-edged: coverage in [0, 1]. `salt` tells the kinds of mark apart.
float mark_coverage(double along, double azimuth, double radius, float density, float width,
                    float height, unsigned salt);
// The same on a plane, at (x, y) metres: marks `width` along x and `height` along y, one per
// square cell of 1/√density.
float mark_coverage_plane(double x, double y, float density, float width, float height,
                          unsigned salt);

}  // namespace arbor::materials
