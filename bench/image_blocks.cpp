// The image error of an approximate render A against a full render B of the same view, as the
// level-of-detail bench reports it (bench/lod.sh): each channel's image mean and their relative
// difference, and the means of BLOCK × BLOCK pixel blocks tested against their noise (z = the
// difference over the root of the two block means' variances, from the images' variance.R/G/B).
// Prints one JSON object.
//
//   image_blocks A.exr B.exr [BLOCK (16)]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "imaging/compare.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: image_blocks A.exr B.exr [BLOCK]\n");
    return 2;
  }
  try {
    const auto a = arbor::imaging::read_compare_image(argv[1]);
    const auto b = arbor::imaging::read_compare_image(argv[2]);
    const int block = argc > 3 ? std::max(1, std::atoi(argv[3])) : 16;
    if (a.width != b.width || a.height != b.height || a.variance.empty() || b.variance.empty()) {
      std::fprintf(stderr, "image_blocks: the images differ in size or lack variance\n");
      return 2;
    }
    const std::size_t n = static_cast<std::size_t>(a.width) * a.height;
    double mean_a[3] = {}, mean_b[3] = {};
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) {
        mean_a[c] += a.rgb[3 * i + c] / static_cast<double>(n);
        mean_b[c] += b.rgb[3 * i + c] / static_cast<double>(n);
      }
    }
    long blocks = 0, beyond3 = 0;
    double max_z = 0.0, sum_z2 = 0.0;
    for (int by = 0; by + block <= a.height; by += block) {
      for (int bx = 0; bx + block <= a.width; bx += block) {
        for (int c = 0; c < 3; ++c) {
          double sa = 0, sb = 0, va = 0, vb = 0;
          for (int y = by; y < by + block; ++y) {
            for (int x = bx; x < bx + block; ++x) {
              const std::size_t k = 3 * (static_cast<std::size_t>(y) * a.width + x) + c;
              sa += a.rgb[k];
              sb += b.rgb[k];
              va += a.variance[k];
              vb += b.variance[k];
            }
          }
          const double m = static_cast<double>(block) * block;
          const double z = (sa - sb) / m / std::sqrt(std::max((va + vb) / (m * m), 1e-30));
          ++blocks;
          beyond3 += std::fabs(z) > 3.0 ? 1 : 0;
          max_z = std::max(max_z, std::fabs(z));
          sum_z2 += z * z;
        }
      }
    }
    std::printf(
        "{\"mean_a\": [%.6g, %.6g, %.6g], \"mean_b\": [%.6g, %.6g, %.6g], "
        "\"mean_rel_diff\": [%.5f, %.5f, %.5f], \"block\": %d, \"block_channels\": %ld, "
        "\"beyond_3_sigma\": %ld, \"max_abs_z\": %.3f, \"rms_z\": %.3f}\n",
        mean_a[0], mean_a[1], mean_a[2], mean_b[0], mean_b[1], mean_b[2],
        mean_a[0] / mean_b[0] - 1.0, mean_a[1] / mean_b[1] - 1.0, mean_a[2] / mean_b[2] - 1.0,
        block, blocks, beyond3, max_z, std::sqrt(sum_z2 / std::max(1L, blocks)));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "image_blocks: %s\n", e.what());
    return 2;
  }
  return 0;
}
