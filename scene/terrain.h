// A terrain (docs/landscape.md): a height field over a rectangle (a square when procedural),
// sampled on a regular grid and rendered as Embree's grid primitive, whose cells are the two
// triangles (v0, v1, v3) and (v2, v3, v1) of the quad v0 = (i, j), v1 = (i + 1, j), v2 = (i + 1, j
// + 1), v3 = (i, j + 1). height() is that surface exactly, so what stands on it is placed on what
// is rendered; normal() is the smooth shading normal (vertex normals from central differences,
// bilinear over the cell); cover() is the ground's soil and rock by slope, curvature and altitude.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "formats/scene_desc.h"

namespace arbor::scene {

class Terrain {
 public:
  Terrain() = default;
  // From a procedural model or an elevation image; InputError at the table for an image that
  // cannot be read or is too large, or heights that are not finite.
  explicit Terrain(const formats::TerrainDesc& desc);

  bool empty() const { return nx_ == 0; }
  int columns() const { return nx_; }            // vertices along x
  int rows() const { return ny_; }               // vertices along y
  double spacing() const { return spacing_; }    // metres between them
  glm::dvec2 origin() const { return origin_; }  // the corner (x0, y0)
  glm::dvec2 extent() const { return {spacing_ * (nx_ - 1), spacing_ * (ny_ - 1)}; }
  double relief() const { return relief_; }
  // Vertex (i, j) at x0 + i·spacing, y0 + j·spacing: row j, column i; what Embree renders, with
  // room for the 16 bytes Embree may read past the last.
  const std::vector<glm::vec3>& vertices() const { return vertices_; }
  float at(int i, int j) const { return vertices_[index(i, j)].z; }

  // The rendered surface's height at world (x, y); 0 outside the square.
  double height(double x, double y) const;
  // The smooth shading normal at (x, y) (up outside the square).
  glm::vec3 normal(double x, double y) const;
  // The ground's cover at (x, y): (soil, rock), each in [0, 1], rock over soil: rock on faces
  // steeper than rock_slope and on ridges and summits, soil in the band below.
  glm::vec2 cover(double x, double y) const;
  // The slope in degrees at (x, y) from the smooth normal.
  double slope(double x, double y) const;
  std::size_t bytes() const { return vertices_.size() * sizeof(glm::vec3); }

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(i);
  }
  // The cell under (x, y) and the position in it; false outside the square.
  bool cell(double x, double y, int& i, int& j, double& fx, double& fy) const;
  glm::vec3 vertex_normal(int i, int j) const;
  double laplacian(int i, int j) const;  // of the heights, 1/m

  int nx_ = 0, ny_ = 0;
  double spacing_ = 1.0, relief_ = 0.0, rock_slope_ = 35.0;
  glm::dvec2 origin_{0.0};
  std::vector<glm::vec3> vertices_;
};

// The camera with its eye placed on `terrain` when it asks to stand on it (above_ground: z is the
// terrain's height under (x, y) plus that), its focus distance then measured to look_at when the
// scene gave none.
formats::CameraDesc placed_camera(const formats::CameraDesc& camera, const Terrain& terrain);

// The vertices a terrain of `desc` has (for memory estimates before any is built): from its size
// and resolution, or the image's header (InputError when it cannot be read or is too large).
std::size_t terrain_vertices(const formats::TerrainDesc& desc);

}  // namespace arbor::scene
