// Image textures read through OpenImageIO (any format it reads), sampled with wrap-around.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace arbor::materials {

// A single-channel image (the luminance of colour images), repeating in both directions.
class HeightMap {
 public:
  // Throws InputError naming the file when it cannot be read or has non-finite pixels.
  explicit HeightMap(const std::string& path);
  HeightMap(std::vector<float> values, int width, int height);

  // Bilinear sample at (u, v); both wrap with period 1.
  float sample(double u, double v) const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  std::vector<float> values_;
  int width_ = 0, height_ = 0;
};

// An RGB albedo image converted to scene-linear through OCIO (from the colour space OIIO reports
// for the file: sRGB for 8-bit formats, linear for EXR), repeating in both directions. Texels
// must lie in [0, 1] (an albedo above 1 would create energy).
class ColorMap {
 public:
  ColorMap(const std::string& path, const std::string& ocio_config);
  // Bilinear sample at (u, v); both wrap with period 1.
  glm::vec3 sample(double u, double v) const;

 private:
  std::vector<glm::vec3> values_;
  int width_ = 0, height_ = 0;
};

}  // namespace arbor::materials
