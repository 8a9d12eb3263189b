// Triangle meshes of MuJoCo's primitive geoms, for the tree path of served pairs (docs/design.md,
// "The MuJoCo layer"; the tolerances are in docs/library.md). Every mesh is closed,
// outward-oriented (counter-clockwise seen from outside), convex, and in the geom frame (centre at
// the origin; capsule and cylinder axes along z), as MuJoCo places the primitive: geom_size holds
// the box half-extents, the sphere radius, the capsule's and cylinder's radius and half-length, the
// ellipsoid's three radii.
//
// Box: exact. 8 corners at (+-hx, +-hy, +-hz), 12 triangles, tolerance 0.
//
// Curved primitives are CIRCUMSCRIBED: the true solid lies inside the tessellation's solid, so a
// tessellation can only report extra contacts, never miss one (the construction: primitives.cpp).
//
// Resolution: N = kTessAround = 32 around the axis, M = kTessProfile = 15 profile segments over
// the half circle. Triangles: sphere, ellipsoid, capsule 2 N (M - 1) = 896; cylinder 4 N = 128.
// Adjacent facets meet at 360/N = 11.25 and 180/M = 12 degrees, below contact.h's sharp-edge
// angle (30), so only box edges and cylinder rims are sharp edges for contact generation.
//
// Tolerance: every point of the tessellation's surface lies outside the true surface (or on it)
// and within this distance of it (the maximum is reached at vertices, since the distance to a
// convex solid is convex along each flat facet), in metres:
//   sphere, capsule:  r (k_round - 1)       k_round  = (1 + 2 kTessPad) / (cos(pi/2M) cos(pi/N))
//   cylinder:         r (k_around - 1)      k_around = (1 + 2 kTessPad) / cos(pi/N)
//   ellipsoid:        max(radii) (k_round - 1)
//   box:              0
// With N = 32, M = 15: k_round - 1 = 0.0103735 (1.04 % of the radius: 0.083 mm for an 8 mm
// fingertip) and k_around - 1 = 0.0048386 (0.48 %). tessellation_tolerance() computes these.
#pragma once

#include <mujoco/mujoco.h>

#include "graspcd/core/geometry.h"

namespace graspcd::mujoco {

inline constexpr int kTessAround = 32;     // N: vertices per ring around the axis
inline constexpr int kTessProfile = 15;    // M: profile segments over the half circle (odd)
inline constexpr double kTessPad = 1e-12;  // relative outward pad of curved radii

// The factors of the tolerance formulas above.
double tess_round_factor();   // k_round
double tess_around_factor();  // k_around

// The tessellations of the table above, in the geom frame; sizes in metres, as MuJoCo's geom_size
// gives them (box half-extents, radii, half-lengths). Each throws std::invalid_argument for a size
// that is not positive and finite.
TriangleMesh tessellate_box(const Vec3& half);
TriangleMesh tessellate_sphere(double radius);
TriangleMesh tessellate_ellipsoid(const Vec3& radii);
TriangleMesh tessellate_capsule(double radius, double half_length);
TriangleMesh tessellate_cylinder(double radius, double half_height);

// True for the geom types the MuJoCo layer tessellates or serves exactly: sphere, capsule,
// ellipsoid, cylinder, box.
bool is_primitive(int geom_type);
// "plane", "hfield", "sphere", "capsule", "ellipsoid", "cylinder", "box", "mesh", or "type N".
const char* geom_type_name(int geom_type);

// The tessellation of a primitive of MuJoCo's `geom_type` with its geom_size (3 numbers), in the
// geom frame. Throws std::invalid_argument for a type that is not a primitive or a size that is
// not positive and finite.
TriangleMesh tessellate_primitive(int geom_type, const mjtNum* size);
// The documented tolerance (metres) of that tessellation: see the table above.
double tessellation_tolerance(int geom_type, const mjtNum* size);

}  // namespace graspcd::mujoco
