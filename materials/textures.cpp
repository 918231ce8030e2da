// HeightMap loading and wrapped bilinear lookup.
#include "materials/textures.h"

#include <cmath>

#include <glm/common.hpp>

#include "common/error.h"
#include "common/image_library.h"
#include "common/math.h"

namespace arbor::materials {

namespace {
// Bilinear lookup of a width × height image that repeats in both directions (period 1 in u, v).
template <typename T>
T wrapped_bilinear(const std::vector<T>& values, int width, int height, double u, double v) {
  auto at = [&](int x, int y) {
    x %= width;
    y %= height;
    if (x < 0) x += width;
    if (y < 0) y += height;
    return values[static_cast<std::size_t>(y) * width + x];
  };
  const double x = (u - std::floor(u)) * width - 0.5, y = (v - std::floor(v)) * height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
  const float tx = static_cast<float>(x - fx), ty = static_cast<float>(y - fy);
  return (at(ix, iy) * (1 - tx) + at(ix + 1, iy) * tx) * (1 - ty) +
         (at(ix, iy + 1) * (1 - tx) + at(ix + 1, iy + 1) * tx) * ty;
}
// Every pixel of `image` through `texel(px, channels, x, y)`, row by row; sets width and height.
template <typename T, typename Texel>
std::vector<T> load_texels(const DecodedImage& image, const std::string& path, int& width,
                           int& height, Texel texel) {
  width = image.width;
  height = image.height;
  if (width < 1 || height < 1) throw InputError({path, 0, 0}, "the image is empty");
  std::vector<T> values(static_cast<std::size_t>(width) * height);
  const std::size_t channels = static_cast<std::size_t>(image.channels);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      values[p] = texel(&image.pixels[p * channels], image.channels, x, y);
    }
  }
  return values;
}

}  // namespace

HeightMap::HeightMap(const std::string& path) {
  values_ = load_texels<float>(
      read_image_file(path, "image", true), path, width_, height_,
      [&](const float* px, int channels, int, int) {
        const float v = channels >= 3 ? luminance(px[0], px[1], px[2]) : px[0];
        if (!std::isfinite(v))
          throw InputError({path, 0, 0}, "the image has a pixel that is not finite");
        return v;
      });
}

HeightMap::HeightMap(std::vector<float> values, int width, int height)
    : values_(std::move(values)), width_(width), height_(height) {}

float HeightMap::sample(double u, double v) const {
  return wrapped_bilinear(values_, width_, height_, u, v);
}

ColorMap::ColorMap(const std::string& path, const std::string& ocio_config) {
  DecodedImage image = read_image_file(path, "image", true);
  // OIIO names the file's encoding ("sRGB" for PNG/JPEG, "Linear" for EXR).
  const std::string declared = image.attribute("oiio:ColorSpace", "Linear");
  const bool srgb =
      declared.find("sRGB") != std::string::npos || declared.find("srgb") != std::string::npos;
  if (srgb) {
    const std::string why =
        image_library("read " + path)
            .convert(image, ocio_config, "sRGB - Texture", "scene_linear", "", "");
    if (!why.empty())
      throw InputError({path, 0, 0}, "cannot convert the image to scene-linear: " + why);
  }
  values_ = load_texels<glm::vec3>(
      image, path, width_, height_, [&](const float* px, int channels, int x, int y) {
        const glm::vec3 c = channels >= 3 ? glm::vec3(px[0], px[1], px[2]) : glm::vec3(px[0]);
        for (int k = 0; k < 3; ++k) {
          if (!std::isfinite(c[k]) || c[k] < 0.0f || c[k] > 1.0f + 1e-4f) {
            throw InputError({path, 0, 0}, "albedo texels must be in [0, 1]; pixel (" +
                                               std::to_string(x) + ", " + std::to_string(y) +
                                               ") is not");
          }
        }
        return glm::min(c, glm::vec3(1.0f));
      });
}

glm::vec3 ColorMap::sample(double u, double v) const {
  return wrapped_bilinear(values_, width_, height_, u, v);
}

}  // namespace arbor::materials
