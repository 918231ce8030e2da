// Embree geometry lifecycle for a tree prototype (new → buffers → commit → attach → release) and
// hit interpretation (normals, leaf sides, bark coordinates).
#include "tracer/embree/embree_scene.h"

#include "tracer/embree/embree_internal.h"

#include "generator/geometry/leaf_shapes.h"

#include <algorithm>
#include <cstring>

#include <glm/geometric.hpp>

namespace arbor::tracer {

namespace {

// The level of detail of the instance a filter's ray is in (null: everything kept).
const scene::InstanceLod* instance_lod(const RTCFilterFunctionNArguments* args,
                                       const PrototypeLod& lod) {
  const unsigned inst = args->context->instID[0];
  if (!lod.instances || inst >= lod.instances->size()) return nullptr;
  return &(*lod.instances)[inst];
}

// The leaf point of a hit at (u, v) on an enlarged card, on the leaf at the instance's own scale:
// the card is the leaf × card_scale about its centre (LeafCard::centre), the instance's leaf is
// × leaf_scale about the same point.
glm::vec2 leaf_point_at(const generator::LeafCard& c, float u, float v, float reach) {
  if (reach == 1.0f) return c.leaf_point(u, v);  // bit for bit as without level of detail
  const glm::vec2 centre = c.centre();
  return centre + reach * (c.leaf_point(u, v) - centre);
}

// Embree's filter for leaf cards (closest-hit and occlusion queries alike): a hit on a card
// counts only inside its leaf's outline, so the ray goes on past the card's corners; with level
// of detail, only on a leaf the instance keeps, at the instance's leaf scale.
void cut_out_leaf(const RTCFilterFunctionNArguments* args) {
  const auto* data = static_cast<const TreePrototype::FilterData*>(args->geometryUserPtr);
  const generator::LeafCards& cards = data->geometry->cards;
  const scene::InstanceLod* lod = instance_lod(args, data->lod);
  const float reach = data->lod.card_scale / (lod ? lod->leaf_scale : 1.0f);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const generator::LeafCard& c = cards.cards[RTCHitN_primID(args->hit, args->N, i)];
    if (lod && !lod->keeps(scene::kLodLeaves, static_cast<std::uint32_t>(c.leaf))) {
      args->valid[i] = 0;
      continue;
    }
    const glm::vec2 p =
        leaf_point_at(c, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i), reach);
    if (!generator::leaf_outline(c.shape).contains(p)) args->valid[i] = 0;
  }
}

// Embree's filter for limbs and their ramiforms with level of detail: a hit counts only on an
// item the instance keeps (Weber & Penn §5's masses; scene/lod.h). `Item` gives primitive i's
// (lod_level, lod_item) holder: a curve segment, or a ramiform's fork (a collar goes with its
// child limb's first segment).
template <typename Item>
void thin(const RTCFilterFunctionNArguments* args, Item item) {
  const auto* data = static_cast<const TreePrototype::FilterData*>(args->geometryUserPtr);
  const scene::InstanceLod* lod = instance_lod(args, data->lod);
  if (!lod) return;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const auto& it = item(*data->geometry, RTCHitN_primID(args->hit, args->N, i));
    if (!lod->keeps(it.lod_level, it.lod_item)) args->valid[i] = 0;
  }
}
void thin_limbs(const RTCFilterFunctionNArguments* args) {
  thin(
      args, [](const generator::TreeGeometry& g, unsigned prim) -> const auto& {
        return g.curves.segments[prim];
      });
}
void thin_ramiforms(const RTCFilterFunctionNArguments* args) {
  thin(
      args, [](const generator::TreeGeometry& g, unsigned prim) -> const auto& {
        return g.ramiforms.forks[prim / generator::RamiformSet::kTrianglesPerFork];
      });
}

// A shaped leaf's shading normal at (u, v) on its card: the corners' normals interpolated
// bilinearly, on the side `seen` (the geometric normal facing the ray).
glm::vec3 card_normal(const glm::vec3* n, float u, float v, const glm::vec3& seen) {
  const glm::vec3 s =
      (n[0] * (1.0f - u) + n[1] * u) * (1.0f - v) + (n[3] * (1.0f - u) + n[2] * u) * v;
  return glm::normalize(glm::dot(s, seen) < 0.0f ? -s : s);
}

// The cards' corners enlarged by `scale` about each card's centre (LeafCard::centre).
std::vector<glm::vec3> enlarged_corners(const generator::LeafCards& lc, float scale) {
  std::vector<glm::vec3> out(lc.corners.size());
  for (std::size_t i = 0; i < lc.size(); ++i) {
    const generator::LeafCard& c = lc.cards[i];
    const glm::vec3* q = &lc.corners[4 * i];
    const glm::vec2 centre = c.centre();
    const glm::vec3 middle = q[0] + (q[1] - q[0]) * ((centre.x - c.x0) / (c.x1 - c.x0)) +
                             (q[3] - q[0]) * ((centre.y - c.y0) / (c.y1 - c.y0));
    for (std::size_t k = 0; k < 4; ++k) out[4 * i + k] = middle + scale * (q[k] - middle);
  }
  return out;
}

}  // namespace

TreePrototype::TreePrototype(const EmbreeDevice& device, const generator::TreeGeometry& geometry,
                             const PrototypeLod& lod)
    : geometry_(geometry), filter_{&geometry, lod} {
  scene_ = new_scene(device);
  // A ramiform's collar is a fine triangle mesh over the limbs: Embree's robust mode keeps rays
  // from slipping through it at its vertices onto the limbs beneath.
  if (geometry.ramiforms.triangle_count() > 0)
    rtcSetSceneFlags(scene_.get(), RTC_SCENE_FLAG_ROBUST);
  const generator::CurveSet& c = geometry.curves;
  if (c.size() > 0) {
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_ROUND_HERMITE_CURVE);
    std::vector<std::uint32_t> index(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) index[i] = static_cast<std::uint32_t>(2 * i);
    fill(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT, index.data(), sizeof(std::uint32_t),
         index.size());
    fill(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT4, c.points.data(), sizeof(glm::vec4),
         c.points.size());
    fill(g, RTC_BUFFER_TYPE_TANGENT, RTC_FORMAT_FLOAT4, c.tangents.data(), sizeof(glm::vec4),
         c.tangents.size());
    if (lod.thin_limbs) {
      rtcSetGeometryUserData(g, &filter_);
      rtcSetGeometryIntersectFilterFunction(g, thin_limbs);
      rtcSetGeometryOccludedFilterFunction(g, thin_limbs);
    }
    curve_id_ = attach(scene_.get(), g);
  }
  const generator::GridSet& gs = geometry.grids;
  if (!gs.grids.empty()) {
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_GRID);
    std::vector<RTCGrid> grids(gs.grids.size());
    for (std::size_t i = 0; i < grids.size(); ++i) {
      grids[i] = {gs.grids[i].first_vertex, gs.grids[i].width, gs.grids[i].width,
                  gs.grids[i].height};
    }
    fill(g, RTC_BUFFER_TYPE_GRID, RTC_FORMAT_GRID, grids.data(), sizeof(RTCGrid), grids.size());
    fill(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, gs.vertices.data(), sizeof(glm::vec3),
         gs.vertices.size());
    grid_id_ = attach(scene_.get(), g);
  }
  const generator::LeafMesh& lm = geometry.leaves;
  if (lm.triangle_count() > 0) {
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    fill(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, lm.indices.data(), 3 * sizeof(std::uint32_t),
         lm.triangle_count());
    fill(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, lm.positions.data(), sizeof(glm::vec3),
         lm.positions.size());
    leaf_id_ = attach(scene_.get(), g);
  }
  const generator::LeafCards& lc = geometry.cards;
  if (lc.size() > 0) {
    // The corners are shared with the geometry, not copied; the quads' indices are 4i .. 4i+3.
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_QUAD);
    auto* index = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(std::uint32_t), lc.size()));
    if (index) {
      for (std::uint32_t k = 0; k < 4 * lc.size(); ++k) index[k] = k;
    }
    if (lod.card_scale == 1.0f) {
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, lc.corners.data(),
                                 0, sizeof(glm::vec3), lc.corners.size());
    } else {
      const std::vector<glm::vec3> corners = enlarged_corners(lc, lod.card_scale);
      fill(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, corners.data(), sizeof(glm::vec3),
           corners.size());
    }
    rtcSetGeometryUserData(g, &filter_);
    rtcSetGeometryIntersectFilterFunction(g, cut_out_leaf);
    rtcSetGeometryOccludedFilterFunction(g, cut_out_leaf);
    card_id_ = attach(scene_.get(), g);
  }
  if (geometry.ramiforms.triangle_count() > 0)
    ramiform_id_ = attach_ramiforms(device, lod.thin_limbs);
  rtcCommitScene(scene_.get());
  device.check("building the tree's BVH");
}

TreePrototype::~TreePrototype() = default;

unsigned TreePrototype::attach_ramiforms(const EmbreeDevice& device, bool thin_limbs) {
  const generator::RamiformSet& rs = geometry_.ramiforms;
  RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  fill(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, rs.indices.data(), 3 * sizeof(std::uint32_t),
       rs.triangle_count());
  fill(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, rs.positions.data(), sizeof(glm::vec3),
       rs.positions.size());
  if (thin_limbs) {
    rtcSetGeometryUserData(g, &filter_);
    rtcSetGeometryIntersectFilterFunction(g, thin_ramiforms);
    rtcSetGeometryOccludedFilterFunction(g, thin_ramiforms);
  }
  return attach(scene_.get(), g);
}

void TreePrototype::describe_ramiform(const Ray& ray, unsigned primitive, float u, float v,
                                      const glm::vec3& ng, SurfaceHit& hit) const {
  const generator::RamiformSet& rs = geometry_.ramiforms;
  const std::uint32_t* tri = &rs.indices[3 * static_cast<std::size_t>(primitive)];
  const float w0 = 1.0f - u - v;
  const auto lerp = [&](const std::vector<glm::vec3>& a) {
    return a[tri[0]] * w0 + a[tri[1]] * u + a[tri[2]] * v;
  };
  hit.kind = SurfaceKind::Ramiform;
  hit.material = generator::kMaterialBark;
  hit.geometric_normal = glm::dot(ng, ray.direction) < 0.0f ? ng : -ng;
  hit.shading_normal = glm::normalize(lerp(rs.normals));
  if (glm::dot(hit.shading_normal, hit.geometric_normal) < 0.0f)
    hit.shading_normal = -hit.shading_normal;
  const glm::vec3 bark = lerp(rs.bark);
  hit.bark.along = bark.x;
  hit.bark.azimuth = bark.y;
  hit.bark.radius = bark.z;
  hit.bark.around = bark.y * bark.z;
  hit.tangent = glm::normalize(lerp(rs.tangents));
  hit.color = glm::vec3(1.0f);
}

void TreePrototype::describe_hit(const Ray& ray, unsigned geom_id, unsigned primitive, float u,
                                 float v, float t, const glm::vec3& embree_ng, SurfaceHit& hit,
                                 float leaf_scale) const {
  hit.t = t;
  hit.primitive = primitive;
  hit.u = u;
  hit.v = v;
  hit.position = ray.origin + ray.direction * t;
  hit.leaf = -1;
  const glm::vec3 ng = glm::normalize(embree_ng);
  if (geom_id == curve_id_) {
    const generator::CurveSet& c = geometry_.curves;
    hit.kind = SurfaceKind::Curve;
    hit.material = c.segments[primitive].material;
    hit.geometric_normal = glm::dot(ng, ray.direction) < 0.0f ? ng : -ng;
    hit.shading_normal = hit.geometric_normal;
    hit.bark = generator::curve_bark(c, primitive, u, hit.position);
    hit.tangent = glm::normalize(glm::vec3(c.derivative(primitive, u)));
    hit.color = c.segments[primitive].color;
    if (c.segments[primitive].material == generator::kMaterialLeafFront) {
      // A leaf's petiole (generator/geometry/leaf_cards.h): its leaf's tissue, its leaf's own tint,
      // the texture's midrib at the blade's base.
      hit.kind = SurfaceKind::Leaf;
      hit.leaf = static_cast<std::int32_t>(c.segments[primitive].lod_item);
      hit.uv = {0.5f, 0.0f};
      hit.crown_height = crown_height(hit.position.z);
    }
  } else if (geom_id == grid_id_) {
    const generator::GridSet& g = geometry_.grids;
    const generator::DisplacedGrid& d = g.grids[primitive];
    hit.kind = SurfaceKind::Grid;
    hit.material = d.material;
    hit.geometric_normal = glm::dot(ng, ray.direction) < 0.0f ? ng : -ng;
    hit.shading_normal = generator::grid_normal(g, primitive, u, v);
    if (glm::dot(hit.shading_normal, hit.geometric_normal) < 0.0f)
      hit.shading_normal = -hit.shading_normal;
    hit.bark = generator::grid_bark(g, primitive, u, v);
    // Along the trunk: between the rings around this hit.
    const auto row = std::min(static_cast<std::uint32_t>(v * (d.height - 1)), d.height - 2u);
    const auto col = std::min(static_cast<std::uint32_t>(u * (d.width - 1)), d.width - 2u);
    const std::size_t base = d.first_vertex + static_cast<std::size_t>(row) * d.width + col;
    const glm::vec3 along = g.vertices[base + d.width] - g.vertices[base];
    hit.tangent = glm::length(along) > 0.0f ? glm::normalize(along) : glm::vec3(0, 0, 1);
    hit.color = glm::vec3(1.0f);
  } else if (geom_id == ramiform_id_) {
    describe_ramiform(ray, primitive, u, v, ng, hit);
  } else if (geom_id == card_id_) {
    hit.kind = SurfaceKind::Leaf;
    const generator::LeafCards& lc = geometry_.cards;
    const generator::LeafCard& card = lc.cards[primitive];
    const glm::vec3* q = &lc.corners[4 * static_cast<std::size_t>(primitive)];
    const TriangleSide side = side_seen(q[0], q[1], q[3], ray.direction);
    hit.material = side.front ? generator::kMaterialLeafFront : generator::kMaterialLeafBack;
    hit.geometric_normal = side.normal;
    hit.shading_normal = hit.geometric_normal;
    if (!lc.normals.empty())  // a shaped leaf: its bent surface's normal
      hit.shading_normal = card_normal(&lc.normals[4 * std::size_t{primitive}], u, v, side.normal);
    hit.leaf = card.leaf;
    hit.color = glm::vec3(1.0f);
    hit.crown_height = crown_height(q[0].z);
    const glm::vec2 p = leaf_point_at(card, u, v, filter_.lod.card_scale / leaf_scale);
    hit.uv = {p.x + 0.5f, p.y};
    hit.tangent = glm::normalize(q[1] - q[0]);
  } else {
    hit.kind = SurfaceKind::Leaf;
    const generator::LeafMesh& lm = geometry_.leaves;
    const std::uint32_t* tri = &lm.indices[3 * static_cast<std::size_t>(primitive)];
    const glm::vec3 a = lm.positions[tri[0]], b = lm.positions[tri[1]], c = lm.positions[tri[2]];
    const TriangleSide side = side_seen(a, b, c, ray.direction);
    hit.material = side.front ? lm.front_material[primitive] : lm.back_material[primitive];
    hit.geometric_normal = side.normal;
    hit.shading_normal = hit.geometric_normal;
    hit.leaf = lm.leaf[primitive];
    hit.color = lm.color.empty() ? glm::vec3(1.0f) : lm.color[primitive];
    hit.crown_height = crown_height(a.z);
    hit.uv = lm.uvs[tri[0]] * (1.0f - u - v) + lm.uvs[tri[1]] * u + lm.uvs[tri[2]] * v;
    hit.tangent = glm::normalize(b - a);
  }
}

}  // namespace arbor::tracer
