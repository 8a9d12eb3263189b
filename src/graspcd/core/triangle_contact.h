// The contact of one intersecting triangle pair, in the form MuJoCo's solver can use. Pure
// geometry (no MuJoCo; the MuJoCo layer writes contacts into mjContact): everything is in geom1's
// frame, geom2's triangles already posed.
//
// Orientation: mesh faces are assumed counter-clockwise seen from outside (outward normals), as
// in a closed, consistently oriented mesh; the normal's sign comes from that orientation.
#pragma once

#include <cstdint>

#include "graspcd/core/geometry.h"

namespace graspcd {

// One contact in geom1's frame: `normal` is unit and points from geom1 toward geom2; `depth` >= 0
// is the penetration along it (MuJoCo's dist = -depth); `pos` lies midway between the surfaces.
struct TriContact {
  Vec3 pos = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  double depth = 0;
};

// The contact of one intersecting triangle pair (a of geom1, b of geom2): the smallest push that
// separates the pair locally, over three kinds of direction.
// - Face directions, in the manner of Bullet's GImpact clip method
//   (btPrimitiveTriangle::find_triangle_collision_clip_method): b is clipped to the prism over a
//   (Sutherland-Hodgman against a's three edge planes) and its penetration measured below a's
//   plane along a's outward normal n_a; symmetrically a inside b's prism along -n_b (b's outward
//   normal points from geom2 toward geom1). One-sided: they respect which side is inside.
// - Edge-edge directions ea_i x eb_j, as in the SAT of Bullet's gim_tri_collision: the
//   overlap of the triangles' projections, the sign from the faces' orientation (out of a, into
//   b) or, where that is undecided, from the smaller side. These catch faces
//   that cross along the solids' edges, where neither face normal is the penetration direction.
//   Only sharp edges take part (bit k of `sharp_a` / `sharp_b`: edge v[k] -> v[k+1] is a
//   feature edge of its mesh, see sharp_edge_masks in mesh_features.h): a diagonal inside a flat
//   face or an edge of a finely tessellated smooth surface is no edge of the solid, and the
//   overlap of two small triangles along it would understate the penetration in a meaningless
//   direction.
// Depth is clipped to `max_depth` (metres). Position: the midpoint of the intersection segment
// (on both surfaces), or for coplanar or touching pairs the deepest clipped point moved half the
// depth along the normal. `fallback_normal` (unit, e.g. geom1's centre toward geom2's) is used
// only when no direction exists (two zero-area triangles with parallel edges).
TriContact triangle_pair_contact(const Triangle& a, const Triangle& b, double max_depth,
                                 const Vec3& fallback_normal, std::uint8_t sharp_a = 7,
                                 std::uint8_t sharp_b = 7);

}  // namespace graspcd
