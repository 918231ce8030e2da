// Gradient noise and the furrowed-bark height field built from it.
#include "materials/bark_noise.h"

#include <cmath>
#include <cstdint>

namespace arbor::materials {

namespace {

std::uint32_t lattice_hash(std::int32_t x, std::int32_t y, std::int32_t z) {
  std::uint32_t h = static_cast<std::uint32_t>(x) * 0x8da6b343u ^
                    static_cast<std::uint32_t>(y) * 0xd8163841u ^
                    static_cast<std::uint32_t>(z) * 0xcb1ab31fu;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  h *= 0x297a2d39u;
  return h ^ (h >> 15);
}

double gradient_dot(std::uint32_t h, double x, double y, double z) {
  // The 12 edge directions of a cube (Perlin 2002), each as ±v[a] ± v[b]: a table lookup rather
  // than a switch, whose jump on a random hash was mispredicted nearly every time. Multiplying by
  // ±1 is exact, so every value is the switch's, bit for bit.
  struct Edge {
    int a;
    double sa;
    int b;
    double sb;
  };
  static constexpr Edge kEdges[12] = {{0, 1, 1, 1}, {0, -1, 1, 1}, {0, 1, 1, -1}, {0, -1, 1, -1},
                                      {0, 1, 2, 1}, {0, -1, 2, 1}, {0, 1, 2, -1}, {0, -1, 2, -1},
                                      {1, 1, 2, 1}, {1, -1, 2, 1}, {1, 1, 2, -1}, {1, -1, 2, -1}};
  const double v[3] = {x, y, z};
  const Edge& e = kEdges[h % 12u];
  return e.sa * v[e.a] + e.sb * v[e.b];
}

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
double lerp(double a, double b, double t) { return a + (b - a) * t; }

}  // namespace

double gradient_noise(double x, double y, double z) {
  const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const auto ix = static_cast<std::int32_t>(fx), iy = static_cast<std::int32_t>(fy),
             iz = static_cast<std::int32_t>(fz);
  const double dx = x - fx, dy = y - fy, dz = z - fz;
  const double u = fade(dx), v = fade(dy), w = fade(dz);
  auto g = [&](int a, int b, int c) {
    return gradient_dot(lattice_hash(ix + a, iy + b, iz + c), dx - a, dy - b, dz - c);
  };
  return lerp(lerp(lerp(g(0, 0, 0), g(1, 0, 0), u), lerp(g(0, 1, 0), g(1, 1, 0), u), v),
              lerp(lerp(g(0, 0, 1), g(1, 0, 1), u), lerp(g(0, 1, 1), g(1, 1, 1), u), v), w);
}

double bark_height(double along, double azimuth, double radius) {
  // Furrows: ridged noise stretched along the limb (plates ~12 cm long, ~3 cm across).
  const double x = radius * std::cos(azimuth), y = radius * std::sin(azimuth);
  double h = 0.0, amplitude = 0.6, frequency = 1.0, total = 0.0;
  for (int octave = 0; octave < 3; ++octave) {
    const double n =
        gradient_noise(along * 8.0 * frequency, x * 33.0 * frequency, y * 33.0 * frequency);
    h += amplitude * (1.0 - std::fabs(n));
    total += amplitude;
    amplitude *= 0.45;
    frequency *= 2.1;
  }
  return h / total;
}

}  // namespace arbor::materials
