// pbrt-v4 export of a tree: limbs as curves, trunk and leaves as triangle meshes.
#pragma once

#include <string>

#include "generator/export/text_output.h"
#include "generator/species.h"
#include "generator/geometry/tree_geometry.h"

namespace arbor::generator {

// Writes a file to `Include` inside a pbrt-v4 world block: each curve segment as a cubic Bézier
// "curve" of type "cylinder" (the exact Hermite segment converted to Bézier form, width = 2 ×
// radius at each end), displaced trunk grids as "trianglemesh" with normals, leaves as one
// "trianglemesh" with uv under a "diffusetransmission" material (pbrt_leaf_material). Atomic.
void write_pbrt(const TreeGeometry& geometry, const BarkLook& bark, const LeafLook& leaf,
                const std::string& path, UpAxis up = UpAxis::Z);

// The shapes of write_pbrt, appended to `out` (handed to `file` a megabyte at a time): the bark
// shapes in one attribute block opened by the statement `bark_material` (`Material …` or
// `NamedMaterial "…"`), the leaves in another opened by `leaf_material`.
void append_pbrt_shapes(const TreeGeometry& geometry, const std::string& bark_material,
                        const std::string& leaf_material, UpAxis up, std::string& out,
                        AtomicFile& file);

// `"rgb NAME" [ r g b ]`.
std::string pbrt_rgb(const char* name, const Rgb& c);
// A leaf as pbrt-v4 can state it: "diffusetransmission" (its type and parameters, to follow
// `Material` or `"string type"`). It has one reflectance for both faces: the mean of the front and
// back reflectances; the cuticle's gloss has no place in it.
std::string pbrt_leaf_material(const Rgb& front, const Rgb& back, const Rgb& transmittance);

}  // namespace arbor::generator
