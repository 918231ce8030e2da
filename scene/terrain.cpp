// The terrain's height field: the procedural models (fBm hills, ridged mountains), the elevation
// image, and the surface Embree renders from them.
#include "scene/terrain.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "common/image_library.h"
#include "common/math.h"
#include "common/range.h"
#include "common/rng.h"
#include "materials/bark_noise.h"

namespace arbor::scene {

namespace {

constexpr int kMaxSamples = 32767;  // along a side: Embree's largest grid

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// The procedural models before they are scaled to the relief (docs/landscape.md, "Terrain"):
// fractional Brownian motion (Musgrave's fBm: seven octaves of gradient noise, each at twice the
// frequency and 0.45 of the amplitude, H = 1.15: the finer octaves roughen without steepening) for
// hills; Musgrave's ridged multifractal (eight octaves of (1 − |noise|)², each weighted by the one
// before, so ridges are sharp and valleys smooth) for mountains. `x`, `y` in units of the largest
// wavelength; `o` the seed's offset.
double fbm(double x, double y, const glm::dvec3& o) {
  double h = 0.0, amplitude = 1.0, f = 1.0;
  for (int k = 0; k < 7; ++k) {
    h += amplitude * materials::gradient_noise(f * x + o.x, f * y + o.y, o.z + 1.37 * k);
    amplitude *= 0.45;
    f *= 2.03;
  }
  return h;
}

double ridged(double x, double y, const glm::dvec3& o) {
  double h = 0.0, amplitude = 1.0, f = 1.0, weight = 1.0;
  for (int k = 0; k < 8; ++k) {
    double r = 1.0 - std::abs(materials::gradient_noise(f * x + o.x, f * y + o.y, o.z + 1.37 * k));
    r *= r * weight;
    weight = std::clamp(2.0 * r, 0.0, 1.0);
    h += amplitude * r;
    amplitude *= 0.5;
    f *= 2.03;
  }
  return h;
}

// Rows [0, rows) of work spread over the machine's cores; each row's result depends on the row
// alone, so the field is the same at any thread count.
template <class Row>
void for_rows(int rows, Row row) {
  const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(), 16u));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) {
    pool.emplace_back([&, t] {
      for (int j = static_cast<int>(t); j < rows; j += static_cast<int>(threads)) row(j);
    });
  }
  for (int j = 0; j < rows; j += static_cast<int>(threads)) row(j);
  for (std::thread& t : pool) t.join();
}

// The surround's grid around a square of `side` sampled `spacing` apart: `cells` of it along the
// square's side (the square's edges on its lines), `beyond` more past each edge to reach
// `surround` sides, `step` metres apart: at least 8 of the square's spacings, and at most about
// 1024 samples across in all.
struct SurroundGrid {
  int cells = 0, beyond = 0;
  double step = 0.0;
  int samples() const { return cells + 2 * beyond + 1; }
};
SurroundGrid surround_grid(double side, double spacing, double surround) {
  SurroundGrid g;
  const double target = std::max(8.0 * spacing, side * (1.0 + 2.0 * surround) / 1024.0);
  g.cells = std::max(1, static_cast<int>(std::lround(side / target)));
  g.step = side / g.cells;
  g.beyond = static_cast<int>(std::ceil(surround * side / g.step - 1e-9));
  return g;
}

DecodedImage elevation_header(const spec::TerrainDesc& d, bool pixels) {
  try {
    DecodedImage image = read_image_file(d.path, "elevation image", false);
    if (image.width < 2 || image.height < 2 || image.width > kMaxSamples ||
        image.height > kMaxSamples) {
      throw InputError(d.path_where,
                       "terrain.path " + d.path + " is " + std::to_string(image.width) + " × " +
                           std::to_string(image.height) + " pixels; an elevation image has 2 to " +
                           std::to_string(kMaxSamples) + " pixels a side");
    }
    if (pixels) image = read_image_file(d.path, "elevation image", true);
    return image;
  } catch (const InputError& e) {
    if (e.where().line > 0) throw;
    throw InputError(d.path_where, "terrain.path " + d.path + ": " + e.message());
  }
}

}  // namespace

spec::CameraDesc placed_camera(const spec::CameraDesc& camera, const Terrain& terrain) {
  spec::CameraDesc c = camera;
  if (!c.above_ground) return c;
  c.position[2] = terrain.height(c.position[0], c.position[1]) + *c.above_ground;
  if (c.focus_distance == 0.0) {
    const glm::dvec3 d(c.look_at[0] - c.position[0], c.look_at[1] - c.position[1],
                       c.look_at[2] - c.position[2]);
    c.focus_distance = glm::length(d);
  }
  return c;
}

std::size_t terrain_vertices(const spec::TerrainDesc& d) {
  if (!d.enabled) return 0;
  if (d.kind == spec::TerrainKind::Image) {
    const DecodedImage header = elevation_header(d, false);
    return static_cast<std::size_t>(header.width) * static_cast<std::size_t>(header.height);
  }
  const auto n = static_cast<std::size_t>(std::ceil(d.size / d.resolution - 1e-9)) + 1;
  if (d.surround <= 0.0) return n * n;
  const auto around = static_cast<std::size_t>(
      surround_grid(d.size, spec::terrain_spacing(d), d.surround).samples());
  return n * n + around * around;
}

Terrain::Terrain(const spec::TerrainDesc& d) : rock_slope_(d.rock_slope) {
  // The heights are made in the vertices' z (the one copy Embree renders from), then moved to
  // run from 0 to the relief.
  const bool image = d.kind == spec::TerrainKind::Image;
  std::function<double(double, double)> raw;  // the procedural model, metres from the corner
  if (image) {
    const DecodedImage pixels = elevation_header(d, true);
    nx_ = pixels.width;
    ny_ = pixels.height;
    spacing_ = d.metres_per_pixel;
    vertices_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 2);
    // Row 0 of the image is its top, the north (+y) edge.
    for (int j = 0; j < ny_; ++j) {
      for (int i = 0; i < nx_; ++i) {
        const float v = pixels.pixels[(static_cast<std::size_t>(ny_ - 1 - j) * nx_ + i) *
                                      static_cast<std::size_t>(pixels.channels)];
        if (!std::isfinite(v)) {
          throw InputError(d.path_where, "terrain.path " + d.path + " has a pixel that is not " +
                                             "finite, at (" + std::to_string(i) + ", " +
                                             std::to_string(ny_ - 1 - j) + ")");
        }
        vertices_[index(i, j)].z = static_cast<float>(v * d.height_scale);
      }
    }
  } else {
    spacing_ = spec::terrain_spacing(d);
    nx_ = ny_ = static_cast<int>(std::lround(d.size / spacing_)) + 1;
    vertices_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 2);
    Rng rng(derive_key(d.seed, 0x7e77a1u));
    const glm::dvec3 offset(1000.0 * rng.uniform(), 1000.0 * rng.uniform(), 100.0 * rng.uniform());
    const bool hills = d.kind == spec::TerrainKind::Hills;
    const double wavelength = d.size / (hills ? 1.5 : 2.0);
    raw = [hills, wavelength, offset](double x, double y) {
      return hills ? fbm(x / wavelength, y / wavelength, offset)
                   : ridged(x / wavelength, y / wavelength, offset);
    };
    for_rows(ny_, [&](int j) {
      for (int i = 0; i < nx_; ++i)
        vertices_[index(i, j)].z = static_cast<float>(raw(i * spacing_, j * spacing_));
    });
  }
  if (!image && d.surround <= 0.0) {
    // Without a surround the edges fall to the lowest level over the outer tenth of the side,
    // so the terrain meets the ground plane around it without a step.
    float lo = vertices_[0].z;
    for (std::size_t k = 0; k + 2 < vertices_.size(); ++k) lo = std::min(lo, vertices_[k].z);
    for_rows(ny_, [&](int j) {
      for (int i = 0; i < nx_; ++i) {
        const double edge = std::min({i, j, nx_ - 1 - i, ny_ - 1 - j}) / double(nx_ - 1);
        float& z = vertices_[index(i, j)].z;
        z = static_cast<float>((z - lo) * smoothstep(0.0, 0.1, edge));
      }
    });
  }
  // Lowest at 0, highest at the relief (an image's own relief).
  float lo = vertices_[0].z, hi = lo;
  for (std::size_t k = 0; k + 2 < vertices_.size(); ++k) {
    lo = std::min(lo, vertices_[k].z);
    hi = std::max(hi, vertices_[k].z);
  }
  const double range = static_cast<double>(hi) - lo;
  const double scale = image ? 1.0 : (range > 0.0 ? d.relief / range : 0.0);
  relief_ = image ? range : d.relief;
  origin_ = -0.5 * glm::dvec2(spacing_ * (nx_ - 1), spacing_ * (ny_ - 1));
  for_rows(ny_, [&](int j) {
    for (int i = 0; i < nx_; ++i) {
      glm::vec3& v = vertices_[index(i, j)];
      v = glm::vec3(origin_.x + i * spacing_, origin_.y + j * spacing_, (v.z - lo) * scale);
    }
  });
  if (!image && d.surround > 0.0) make_surround(d, raw, lo, scale);
}

void Terrain::make_surround(const spec::TerrainDesc& d,
                            const std::function<double(double, double)>& raw, double lo,
                            double scale) {
  const SurroundGrid g = surround_grid(extent().x, spacing_, d.surround);
  auto s = std::make_shared<Terrain>();
  s->nx_ = s->ny_ = g.samples();
  s->spacing_ = g.step;
  s->relief_ = relief_;
  s->rock_slope_ = rock_slope_;
  s->origin_ = origin_ - glm::dvec2(g.beyond * g.step);
  const std::size_t n = static_cast<std::size_t>(s->nx_) * static_cast<std::size_t>(s->ny_);
  s->vertices_.resize(n + 2);
  s->shading_heights_.resize(n);
  const int first = g.beyond, last = g.beyond + g.cells;  // the square's edges, in samples
  const auto inside = [&](int i, int j) { return i > first && i < last && j > first && j < last; };
  for_rows(s->ny_, [&](int j) {
    for (int i = 0; i < s->nx_; ++i) {
      const double x = s->origin_.x + i * g.step, y = s->origin_.y + j * g.step;
      const double h = (raw(x - origin_.x, y - origin_.y) - lo) * scale;
      s->vertices_[s->index(i, j)] =
          glm::vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(h));
    }
  });
  // The lowest level around the square (0 if none is lower), to which the surround's own outer
  // tenth falls and on which the ground plane lies.
  double floor = 0.0;
  for (int j = 0; j < s->ny_; ++j) {
    for (int i = 0; i < s->nx_; ++i) {
      if (!inside(i, j)) floor = std::min(floor, static_cast<double>(s->at(i, j)));
    }
  }
  // Sunk under the square: its inner samples well below its lowest point, those on its edge by
  // a small margin (a two-hundredth of the relief and a quarter metre: the detail the coarser
  // grid misses along the edge can still rise above it, in a strip a fraction of a metre wide at
  // the square's very edge; a larger margin left a cliff of that height all round); the skirt
  // closes the seam where the square is higher.
  const double margin = 0.005 * relief_ + 0.25, deep = floor - 0.05 * relief_ - 5.0;
  for (int j = 0; j < s->ny_; ++j) {
    for (int i = 0; i < s->nx_; ++i) {
      float& z = s->vertices_[s->index(i, j)].z;
      const double edge =
          std::min({i, j, s->nx_ - 1 - i, s->ny_ - 1 - j}) / static_cast<double>(s->nx_ - 1);
      z = static_cast<float>(floor + (z - floor) * smoothstep(0.0, 0.1, edge));
      s->shading_heights_[s->index(i, j)] = z;
      if (inside(i, j))
        z = static_cast<float>(deep);
      else if (i >= first && i <= last && j >= first && j <= last)
        z -= static_cast<float>(margin);
    }
  }
  s->floor_ = floor_ = floor;
  // The skirt: each edge's vertices in the order that runs left to right seen from outside.
  const auto wall = [&](int i0, int j0, int di, int dj, int count) {
    for (int k = 0; k + 1 < count; ++k) {
      const glm::vec3 a = vertices_[index(i0 + k * di, j0 + k * dj)];
      const glm::vec3 b = vertices_[index(i0 + (k + 1) * di, j0 + (k + 1) * dj)];
      const auto base = static_cast<std::uint32_t>(skirt_positions_.size());
      skirt_positions_.insert(skirt_positions_.end(),
                              {a, b, glm::vec3(a.x, a.y, static_cast<float>(deep)),
                               glm::vec3(b.x, b.y, static_cast<float>(deep))});
      // (a', b', b) and (a', b, a)
      skirt_indices_.insert(skirt_indices_.end(),
                            {base + 2, base + 3, base + 1, base + 2, base + 1, base});
    }
  };
  wall(0, 0, 1, 0, nx_);               // south, seen from −y: x grows to the right
  wall(nx_ - 1, 0, 0, 1, ny_);         // east, seen from +x: y grows
  wall(nx_ - 1, ny_ - 1, -1, 0, nx_);  // north
  wall(0, ny_ - 1, 0, -1, ny_);        // west
  surround_ = std::move(s);
}

std::size_t Terrain::bytes() const {
  std::size_t b = vertices_.size() * sizeof(glm::vec3) + shading_heights_.size() * sizeof(float) +
                  skirt_positions_.size() * sizeof(glm::vec3) +
                  skirt_indices_.size() * sizeof(std::uint32_t);
  return surround_ ? b + surround_->bytes() : b;
}

bool Terrain::cell(double x, double y, int& i, int& j, double& fx, double& fy) const {
  if (empty()) return false;
  const double u = (x - origin_.x) / spacing_, v = (y - origin_.y) / spacing_;
  if (!(u >= 0.0 && v >= 0.0 && u <= nx_ - 1 && v <= ny_ - 1)) return false;
  i = std::min(static_cast<int>(u), nx_ - 2);
  j = std::min(static_cast<int>(v), ny_ - 2);
  fx = u - i;
  fy = v - j;
  return true;
}

double Terrain::height(double x, double y) const {
  int i, j;
  double fx, fy;
  if (!cell(x, y, i, j, fx, fy)) return surround_ ? surround_->height(x, y) : floor_;
  const double h0 = at(i, j), h1 = at(i + 1, j), h2 = at(i + 1, j + 1), h3 = at(i, j + 1);
  // Embree's quad (v0, v1, v2, v3) as the triangles (v0, v1, v3) and (v2, v3, v1).
  if (fx + fy <= 1.0) return h0 + fx * (h1 - h0) + fy * (h3 - h0);
  return h2 + (1.0 - fx) * (h3 - h2) + (1.0 - fy) * (h1 - h2);
}

glm::vec3 Terrain::vertex_normal(int i, int j) const {
  const int il = std::max(i - 1, 0), ir = std::min(i + 1, nx_ - 1);
  const int jd = std::max(j - 1, 0), ju = std::min(j + 1, ny_ - 1);
  const double dx = (shading_at(ir, j) - shading_at(il, j)) / ((ir - il) * spacing_);
  const double dy = (shading_at(i, ju) - shading_at(i, jd)) / ((ju - jd) * spacing_);
  return glm::normalize(glm::vec3(static_cast<float>(-dx), static_cast<float>(-dy), 1.0f));
}

double Terrain::laplacian(int i, int j) const {
  const int il = std::max(i - 1, 0), ir = std::min(i + 1, nx_ - 1);
  const int jd = std::max(j - 1, 0), ju = std::min(j + 1, ny_ - 1);
  return (shading_at(ir, j) + shading_at(il, j) + shading_at(i, ju) + shading_at(i, jd) -
          4.0 * shading_at(i, j)) /
         (spacing_ * spacing_);
}

glm::vec3 Terrain::normal(double x, double y) const {
  int i, j;
  double fx, fy;
  if (!cell(x, y, i, j, fx, fy))
    return surround_ ? surround_->normal(x, y) : glm::vec3(0.0f, 0.0f, 1.0f);
  const auto a = static_cast<float>(fx), b = static_cast<float>(fy);
  const glm::vec3 n =
      (1.0f - a) * (1.0f - b) * vertex_normal(i, j) + a * (1.0f - b) * vertex_normal(i + 1, j) +
      a * b * vertex_normal(i + 1, j + 1) + (1.0f - a) * b * vertex_normal(i, j + 1);
  return glm::normalize(n);
}

double Terrain::slope(double x, double y) const {
  return std::acos(std::clamp(static_cast<double>(normal(x, y).z), -1.0, 1.0)) * 180.0 / kPi;
}

glm::vec2 Terrain::cover(double x, double y) const {
  int i, j;
  double fx, fy;
  if (!cell(x, y, i, j, fx, fy)) return surround_ ? surround_->cover(x, y) : glm::vec2(0.0f);
  // Convexity (ridges, summits: the heights' Laplacian below 0), bilinear over the cell, in 1/m.
  const double convex =
      -((1 - fx) * (1 - fy) * laplacian(i, j) + fx * (1 - fy) * laplacian(i + 1, j) +
        fx * fy * laplacian(i + 1, j + 1) + (1 - fx) * fy * laplacian(i, j + 1));
  // Rock where the slope, raised by up to 15° on ridges (convexity 0.05/m: a ridge of 20 m
  // radius) and by up to 10° on the top fifth of the relief, passes rock_slope; soil on the 10°
  // below; gullies and hollows (concave) lower it by up to 5°, keeping their soil.
  const double top = relief_ > 0.0 ? smoothstep(0.8, 1.0, height(x, y) / relief_) : 0.0;
  const double effective =
      slope(x, y) + 15.0 * std::clamp(convex / 0.05, -1.0 / 3.0, 1.0) + 10.0 * top;
  const double rock = smoothstep(rock_slope_ - 3.0, rock_slope_ + 3.0, effective);
  const double soil = smoothstep(rock_slope_ - 12.0, rock_slope_ - 4.0, effective);
  return {static_cast<float>(soil), static_cast<float>(rock)};
}

}  // namespace arbor::scene
