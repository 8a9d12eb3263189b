#include "graspcd/mujoco/primitives.h"

// The curved primitives, circumscribed (primitives.h): a surface of revolution about z,
// polygonised twice:
//   1. The meridian profile, a polygon in the (rho, z) half-plane circumscribing the true profile:
//      for the sphere, the half of a regular 2M-gon around the circle of radius r, its vertices
//      at angles -pi/2 + k pi/M (k = 0..M) and radius r / cos(pi/(2M)), so its edges are tangent
//      to the circle. M is odd, so the edge at the equator is vertical and tangent at rho = r.
//      Capsule: the sphere's profile with the lower half moved down by the half-length h and the
//      upper half moved up by h (the Minkowski sum with the axis segment; its side is exactly the
//      cylinder rho = r). Cylinder: the rectangle rho <= r, |z| <= h, exact.
//   2. Around z, every profile vertex (rho, z) with rho > 0 becomes a ring of N vertices at
//      angles 2 pi j / N and radius rho / cos(pi/N) (the regular N-gon circumscribing the circle
//      of radius rho); profile vertices on the axis (rho = 0) are single pole vertices. Adjacent
//      rings share their angles, so each band is made of planar trapezoids (two triangles each)
//      and every horizontal section of the solid is the N-gon around that section of the
//      revolved profile, which contains the true section.
//   Ellipsoid: the unit sphere's tessellation scaled by the three radii; an affine map keeps
//   "contains", so it circumscribes the ellipsoid.
//   All curved radii are multiplied by (1 + kTessPad) against rounding of sines and cosines.

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace graspcd::mujoco {
namespace {

const double kPi = std::acos(-1.0);

static_assert(kTessProfile % 2 == 1, "the equator must be the middle of a profile edge");
static_assert(kTessAround >= 12, "facets must meet below contact.h's sharp-edge angle");

// A point (rho, z) of a meridian profile, rho >= 0.
using ProfilePoint = std::array<double, 2>;

// The circumscribed half 2M-gon of a circle of radius r (primitives.h, step 1), bottom to top:
// vertex k at angle -pi/2 + k pi/M and radius r / cos(pi/(2M)), so that every edge is tangent to
// the circle (the classical circumscribed regular polygon). `half_length` > 0 moves the lower
// half down and the upper half up (the capsule).
std::vector<ProfilePoint> round_profile(double r, double half_length) {
  const int m = kTessProfile;
  const double rp = r * (1 + kTessPad) / std::cos(kPi / (2 * m));
  std::vector<ProfilePoint> out;
  for (int k = 0; k <= m; ++k) {
    const double theta = -kPi / 2 + kPi * k / m;
    double rho = rp * std::cos(theta);
    double z = rp * std::sin(theta);
    if (k == 0 || k == m) rho = 0;  // the poles, on the axis exactly
    z += 2 * k < m ? -half_length : half_length;
    out.push_back({rho, z});
  }
  return out;
}

// The surface of revolution of `profile` about z (primitives.h, step 2): the first and last
// profile points lie on the axis and become poles; every other point becomes a ring of N
// vertices at angles 2 pi j / N and radius rho / cos(pi/N). Faces counter-clockwise seen from
// outside, for a profile that runs from bottom to top on the side rho > 0.
TriangleMesh revolve(const std::vector<ProfilePoint>& profile) {
  const int n = kTessAround;
  const int rings = static_cast<int>(profile.size()) - 2;
  const double widen = 1 / std::cos(kPi / n);
  TriangleMesh mesh;
  mesh.vertices.emplace_back(0, 0, profile.front()[1]);
  for (int i = 1; i <= rings; ++i) {
    const double rho = profile[static_cast<std::size_t>(i)][0] * widen;
    const double z = profile[static_cast<std::size_t>(i)][1];
    for (int j = 0; j < n; ++j) {
      const double phi = 2 * kPi * j / n;
      mesh.vertices.emplace_back(rho * std::cos(phi), rho * std::sin(phi), z);
    }
  }
  mesh.vertices.emplace_back(0, 0, profile.back()[1]);
  const std::int32_t top = static_cast<std::int32_t>(mesh.vertices.size()) - 1;
  const auto ring = [&](int i, int j) {
    return static_cast<std::int32_t>(1 + (i - 1) * n + j % n);
  };
  for (int j = 0; j < n; ++j) {
    mesh.faces.push_back({0, ring(1, j + 1), ring(1, j)});
    for (int i = 1; i < rings; ++i) {
      mesh.faces.push_back({ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)});
      mesh.faces.push_back({ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)});
    }
    mesh.faces.push_back({top, ring(rings, j), ring(rings, j + 1)});
  }
  return mesh;
}

void check_size(double x, const char* what) {
  if (!(x > 0) || !std::isfinite(x)) {
    throw std::invalid_argument(std::string("primitive ") + what + " must be positive and finite");
  }
}

}  // namespace

double tess_round_factor() {
  return (1 + 2 * kTessPad) / (std::cos(kPi / (2 * kTessProfile)) * std::cos(kPi / kTessAround));
}

double tess_around_factor() { return (1 + 2 * kTessPad) / std::cos(kPi / kTessAround); }

// The box's 8 corners in sign-bit order (x fastest, as obb_corners) and two triangles per face.
TriangleMesh tessellate_box(const Vec3& half) {
  for (int k = 0; k < 3; ++k) check_size(half[k], "half-extent");
  TriangleMesh mesh;
  for (int c = 0; c < 8; ++c) {
    mesh.vertices.emplace_back((c & 1) ? half[0] : -half[0], (c & 2) ? half[1] : -half[1],
                               (c & 4) ? half[2] : -half[2]);
  }
  mesh.faces = {{0, 2, 3}, {0, 3, 1},   // -z
                {4, 5, 7}, {4, 7, 6},   // +z
                {0, 1, 5}, {0, 5, 4},   // -y
                {2, 6, 7}, {2, 7, 3},   // +y
                {0, 4, 6}, {0, 6, 2},   // -x
                {1, 3, 7}, {1, 7, 5}};  // +x
  return mesh;
}

TriangleMesh tessellate_sphere(double radius) {
  check_size(radius, "radius");
  return revolve(round_profile(radius, 0));
}

TriangleMesh tessellate_ellipsoid(const Vec3& radii) {
  for (int k = 0; k < 3; ++k) check_size(radii[k], "radius");
  TriangleMesh mesh = revolve(round_profile(1, 0));
  for (Vec3& v : mesh.vertices) v = v.cwiseProduct(radii);
  return mesh;
}

TriangleMesh tessellate_capsule(double radius, double half_length) {
  check_size(radius, "radius");
  check_size(half_length, "half-length");
  return revolve(round_profile(radius, half_length));
}

// The rectangle profile: bottom centre, bottom rim, top rim, top centre (caps are exact planes).
TriangleMesh tessellate_cylinder(double radius, double half_height) {
  check_size(radius, "radius");
  check_size(half_height, "half-height");
  const double rho = radius * (1 + kTessPad);
  return revolve({{0, -half_height}, {rho, -half_height}, {rho, half_height}, {0, half_height}});
}

bool is_primitive(int geom_type) {
  return geom_type == mjGEOM_SPHERE || geom_type == mjGEOM_CAPSULE ||
         geom_type == mjGEOM_ELLIPSOID || geom_type == mjGEOM_CYLINDER || geom_type == mjGEOM_BOX;
}

const char* geom_type_name(int geom_type) {
  switch (geom_type) {
    case mjGEOM_PLANE:
      return "plane";
    case mjGEOM_HFIELD:
      return "hfield";
    case mjGEOM_SPHERE:
      return "sphere";
    case mjGEOM_CAPSULE:
      return "capsule";
    case mjGEOM_ELLIPSOID:
      return "ellipsoid";
    case mjGEOM_CYLINDER:
      return "cylinder";
    case mjGEOM_BOX:
      return "box";
    case mjGEOM_MESH:
      return "mesh";
    default:
      return "unknown type";
  }
}

TriangleMesh tessellate_primitive(int geom_type, const mjtNum* size) {
  switch (geom_type) {
    case mjGEOM_SPHERE:
      return tessellate_sphere(size[0]);
    case mjGEOM_CAPSULE:
      return tessellate_capsule(size[0], size[1]);
    case mjGEOM_ELLIPSOID:
      return tessellate_ellipsoid(Vec3(size[0], size[1], size[2]));
    case mjGEOM_CYLINDER:
      return tessellate_cylinder(size[0], size[1]);
    case mjGEOM_BOX:
      return tessellate_box(Vec3(size[0], size[1], size[2]));
    default:
      throw std::invalid_argument(std::string("a ") + geom_type_name(geom_type) +
                                  " geom is not a primitive graspcd tessellates");
  }
}

double tessellation_tolerance(int geom_type, const mjtNum* size) {
  switch (geom_type) {
    case mjGEOM_SPHERE:
    case mjGEOM_CAPSULE:
      return size[0] * (tess_round_factor() - 1);
    case mjGEOM_ELLIPSOID:
      return std::max({size[0], size[1], size[2]}) * (tess_round_factor() - 1);
    case mjGEOM_CYLINDER:
      return size[0] * (tess_around_factor() - 1);
    case mjGEOM_BOX:
      return 0;
    default:
      throw std::invalid_argument(std::string("a ") + geom_type_name(geom_type) +
                                  " geom is not a primitive graspcd tessellates");
  }
}

}  // namespace graspcd::mujoco
