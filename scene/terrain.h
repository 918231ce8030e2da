// A terrain (docs/landscape.md): a height field over a rectangle (a square when procedural),
// sampled on a regular grid and rendered as Embree's grid primitive, whose cells are the two
// triangles (v0, v1, v3) and (v2, v3, v1) of the quad v0 = (i, j), v1 = (i + 1, j), v2 = (i + 1, j
// + 1), v3 = (i, j + 1). height() is that surface exactly, so what stands on it is placed on what
// is rendered; normal() is the smooth shading normal (vertex normals from central differences,
// bilinear over the cell); cover() is the ground's soil and rock by slope, curvature and altitude.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "spec/scene_desc.h"

namespace arbor::scene {

class Terrain {
 public:
  Terrain() = default;
  // From a procedural model or an elevation image; InputError at the table for an image that
  // cannot be read or is too large, or heights that are not finite.
  explicit Terrain(const spec::TerrainDesc& desc);

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

  // The rendered surface's height at world (x, y); outside the square the surround's, and
  // beyond that the ground plane's level (floor()).
  double height(double x, double y) const;
  // The smooth shading normal at (x, y) (up outside the square).
  glm::vec3 normal(double x, double y) const;
  // The ground's cover at (x, y): (soil, rock), each in [0, 1], rock over soil: rock on faces
  // steeper than rock_slope and on ridges and summits, soil in the band below.
  glm::vec2 cover(double x, double y) const;
  // The slope in degrees at (x, y) from the smooth normal.
  double slope(double x, double y) const;
  std::size_t bytes() const;  // with the surround's and the skirt's

  // The far terrain around the square (docs/landscape.md, "The surround"): the procedural model
  // continued `surround` sides beyond each edge on a coarser grid, its vertices inside the square
  // sunk under it; null when there is none. Outside the square height(), normal(), cover() and
  // slope() are the surround's.
  const Terrain* surround() const { return surround_.get(); }
  // The skirt that closes the seam between the square and the surround: a wall hung from the
  // square's edge down under the surround, two triangles a cell of the edge (counter-clockwise
  // seen from outside); empty without a surround.
  const std::vector<glm::vec3>& skirt_positions() const { return skirt_positions_; }
  const std::vector<std::uint32_t>& skirt_indices() const { return skirt_indices_; }
  // The lowest level, where the ground plane lies: 0, or the surround's lowest point if lower.
  double floor() const { return floor_; }

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(i);
  }
  // The cell under (x, y) and the position in it; false outside the square.
  bool cell(double x, double y, int& i, int& j, double& fx, double& fy) const;
  glm::vec3 vertex_normal(int i, int j) const;
  // The heights normals and cover are taken from: the rendered ones, or (the surround) those
  // before its cells under the square were sunk.
  float shading_at(int i, int j) const {
    return shading_heights_.empty() ? at(i, j) : shading_heights_[index(i, j)];
  }
  // Makes the surround of this square (its heights already scaled by `scale` after `lo` was
  // taken off), `raw` the procedural model at a point in metres from the square's corner.
  void make_surround(const spec::TerrainDesc& d, const std::function<double(double, double)>& raw,
                     double lo, double scale);
  double laplacian(int i, int j) const;  // of the heights, 1/m

  int nx_ = 0, ny_ = 0;
  double spacing_ = 1.0, relief_ = 0.0, rock_slope_ = 35.0;
  glm::dvec2 origin_{0.0};
  std::vector<glm::vec3> vertices_;
  std::vector<float> shading_heights_;  // the surround's, unsunk; empty otherwise
  std::shared_ptr<const Terrain> surround_;
  std::vector<glm::vec3> skirt_positions_;
  std::vector<std::uint32_t> skirt_indices_;
  double floor_ = 0.0;
};

// The camera with its eye placed on `terrain` when it asks to stand on it (above_ground: z is the
// terrain's height under (x, y) plus that), its focus distance then measured to look_at when the
// scene gave none.
spec::CameraDesc placed_camera(const spec::CameraDesc& camera, const Terrain& terrain);

// The vertices a terrain of `desc` has (for memory estimates before any is built): from its size
// and resolution, or the image's header (InputError when it cannot be read or is too large).
std::size_t terrain_vertices(const spec::TerrainDesc& desc);

}  // namespace arbor::scene
