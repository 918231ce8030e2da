// A rendered image as the film holds it (beauty, variance, AOVs) and what its render cost: the
// plain data the image writers take.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace arbor::imaging {

struct Image {
  int width = 0, height = 0;            // the pixels held: the whole image, or a crop of it
  int x0 = 0, y0 = 0;                   // where they sit in the whole image
  int full_width = 0, full_height = 0;  // the whole image
  std::vector<glm::vec3> beauty;        // mean, output colour space
  std::vector<glm::vec3> variance;      // variance of the mean (sample variance / n), per channel
  std::vector<glm::vec3> albedo;        // first hit, output colour space
  std::vector<glm::vec3> normal;        // first hit, world space
  std::vector<float> depth;             // distance to the first hit along the camera ray
  std::vector<float> samples;           // finite samples the pixel took
  std::vector<float>
      alpha;  // 1; with a transparent sky, the share of camera rays that hit something
  // Compositing ids (1-based into object_names / material_names) with the share of the pixel's
  // samples that saw each, id_slots a pixel, most covering first (ties: lower id), 0 when empty;
  // id_slots is 0 when the render kept no ids.
  std::size_t id_slots = 0;
  std::vector<std::uint32_t> object_ids, material_ids;
  std::vector<float> object_cover, material_cover;
  std::vector<std::string> object_names, material_names;
  // Integrator-specific AOVs (the treemaker integrator's), pixel means: extra_names.size()
  // floats per pixel; colour triples are in the output colour space, like the beauty.
  std::vector<std::string> extra_names;
  std::vector<float> extra;
};

struct RenderStats {
  double seconds = 0.0;
  std::uint64_t samples = 0, rays = 0;
  std::uint64_t nonfinite = 0;  // samples whose radiance was NaN or infinite (left out, counted)
};

}  // namespace arbor::imaging
