// Primitive geoms in the MuJoCo layer. The tessellations (graspcd/mujoco/primitives.h): closed,
// outward, convex, the box exact, curved primitives circumscribed (sampled points of the true
// surface never lie outside the tessellation's solid) within their documented tolerance, which is
// nearly reached. Served pairs with primitives in MuJoCo: a tessellated primitive never misses a
// contact that the true surfaces have and reports none beyond the tolerance; box-box pairs are
// exact and never touch triangles (bit-for-bit MuJoCo's contacts); the box hand
// (mjcf/hand_boxes.xml) closes, lifts and holds with graspcd exactly as natively.
#include "graspcd/mujoco/primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/core/contact.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/registry.h"
#include "graspcd/support/seeded.h"
#include "helpers/scene_support.h"

namespace graspcd::mujoco::primitives_test {
namespace {

using testing::contacts_between;
using testing::DataPtr;
using testing::load_scene;
using testing::ModelPtr;
using testing::TempDir;

const double kPi = std::acos(-1.0);

// ---------------------------------------------------------------------------------------------
// The true shapes: signed distance to the solid (positive outside), for points outside at least,
// and points of the true surface by two parameters (u, v) in [0, 1).

// Distance from y (outside or on the ellipsoid with radii e) to the ellipsoid: Eberly, "Distance
// from a Point to an Ellipse, an Ellipsoid, or a Hyperellipsoid" (Geometric Tools, 2013): the
// closest point is x_i = e_i^2 y_i / (t + e_i^2) for the root t >= 0 of
// F(t) = sum (e_i y_i / (t + e_i^2))^2 - 1, decreasing; bisection on [0, max(e) |y|].
double ellipsoid_distance(const Vec3& radii, const Vec3& y) {
  const auto f = [&](double t) {
    double s = 0;
    for (int i = 0; i < 3; ++i) {
      const double q = radii[i] * y[i] / (t + radii[i] * radii[i]);
      s += q * q;
    }
    return s - 1;
  };
  if (f(0) <= 0) return 0;  // inside or on
  double lo = 0, hi = radii.maxCoeff() * y.norm();
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? lo : hi) = mid;
  }
  Vec3 x;
  for (int i = 0; i < 3; ++i) x[i] = radii[i] * radii[i] * y[i] / (hi + radii[i] * radii[i]);
  return (y - x).norm();
}

struct Shape {
  int type = mjGEOM_SPHERE;
  mjtNum size[3] = {0, 0, 0};
  std::string name() const {
    char buf[128];
    std::snprintf(buf, sizeof(buf), "%s %g %g %g", geom_type_name(type), size[0], size[1], size[2]);
    return buf;
  }
  // Distance from an outside point to the solid (0 inside).
  double distance(const Vec3& p) const {
    const double r = size[0];
    switch (type) {
      case mjGEOM_SPHERE:
        return std::max(0.0, p.norm() - r);
      case mjGEOM_CAPSULE: {
        const double z = std::clamp(p[2], -size[1], size[1]);
        return std::max(0.0, (p - Vec3(0, 0, z)).norm() - r);
      }
      case mjGEOM_CYLINDER: {
        const double radial = std::max(0.0, std::hypot(p[0], p[1]) - r);
        const double axial = std::max(0.0, std::abs(p[2]) - size[1]);
        return std::hypot(radial, axial);
      }
      case mjGEOM_ELLIPSOID:
        return ellipsoid_distance(Vec3(size[0], size[1], size[2]), p);
      default: {  // box
        const Vec3 out = (p.cwiseAbs() - Vec3(size[0], size[1], size[2])).cwiseMax(0.0);
        return out.norm();
      }
    }
  }
  // A point of the true surface; (u, v) in [0, 1]^2 cover it.
  Vec3 surface_point(double u, double v) const {
    const double phi = 2 * kPi * u;
    switch (type) {
      case mjGEOM_SPHERE:
      case mjGEOM_ELLIPSOID: {
        const double theta = kPi * (v - 0.5);
        const Vec3 unit(std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi),
                        std::sin(theta));
        return type == mjGEOM_SPHERE ? Vec3(size[0] * unit)
                                     : Vec3(unit.cwiseProduct(Vec3(size[0], size[1], size[2])));
      }
      case mjGEOM_CAPSULE: {
        // v in [0, 1/3): lower cap, [1/3, 2/3): side, [2/3, 1]: upper cap.
        const double r = size[0], h = size[1];
        if (v >= 1.0 / 3 && v < 2.0 / 3) {
          return Vec3(r * std::cos(phi), r * std::sin(phi), h * (6 * v - 3));
        }
        const bool upper = v >= 2.0 / 3;
        const double theta = upper ? (3 * v - 2) * kPi / 2 : -(1 - 3 * v) * kPi / 2;
        return Vec3(r * std::cos(theta) * std::cos(phi), r * std::cos(theta) * std::sin(phi),
                    r * std::sin(theta) + (upper ? h : -h));
      }
      case mjGEOM_CYLINDER: {
        const double r = size[0], h = size[1];
        if (v < 0.25) return Vec3(4 * v * r * std::cos(phi), 4 * v * r * std::sin(phi), -h);
        if (v > 0.75)
          return Vec3(4 * (1 - v) * r * std::cos(phi), 4 * (1 - v) * r * std::sin(phi), h);
        return Vec3(r * std::cos(phi), r * std::sin(phi), h * (4 * v - 2));
      }
      default: {  // box: one of 6 faces by u, a point on it by (u, v)
        const int face = std::min(5, static_cast<int>(6 * u));
        const double s = 12 * u - 2 * face - 1;  // [-1, 1]
        const double t = 2 * v - 1;
        Vec3 q;
        q[face / 2] = face % 2 ? 1 : -1;
        q[(face / 2 + 1) % 3] = s;
        q[(face / 2 + 2) % 3] = t;
        return q.cwiseProduct(Vec3(size[0], size[1], size[2]));
      }
    }
  }
};

// gtest prints a parameter with this (the test names stay indices).
void PrintTo(const Shape& s, std::ostream* os) { *os << s.name(); }

Shape shape(int type, double a, double b = 0, double c = 0) {
  Shape s;
  s.type = type;
  s.size[0] = a;
  s.size[1] = b;
  s.size[2] = c;
  return s;
}

std::vector<Shape> test_shapes() {
  return {shape(mjGEOM_SPHERE, 0.004),
          shape(mjGEOM_SPHERE, 0.02),
          shape(mjGEOM_SPHERE, 0.5),
          shape(mjGEOM_CAPSULE, 0.008, 0.02),
          shape(mjGEOM_CAPSULE, 0.05, 0.002),
          shape(mjGEOM_CYLINDER, 0.01, 0.03),
          shape(mjGEOM_CYLINDER, 0.2, 0.005),
          shape(mjGEOM_ELLIPSOID, 0.01, 0.02, 0.005),
          shape(mjGEOM_ELLIPSOID, 0.3, 0.1, 0.2),
          shape(mjGEOM_BOX, 0.008, 0.008, 0.02),
          shape(mjGEOM_BOX, 0.3, 0.01, 0.1)};
}

// Outward unit normals and a vertex of each face.
struct Planes {
  std::vector<Vec3> normal;
  std::vector<Vec3> point;
};
Planes face_planes(const TriangleMesh& m) {
  Planes p;
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    const Triangle t = m.triangle(f);
    p.normal.push_back((t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]).normalized());
    p.point.push_back(t.v[0]);
  }
  return p;
}

// The largest signed distance of x beyond the faces' planes: <= 0 means x is in the solid of a
// convex mesh.
double outside_by(const Planes& p, const Vec3& x) {
  double worst = -1e300;
  for (std::size_t f = 0; f < p.normal.size(); ++f) {
    worst = std::max(worst, p.normal[f].dot(x - p.point[f]));
  }
  return worst;
}

class Tessellation : public ::testing::TestWithParam<Shape> {};

// Closed and consistently oriented: every directed edge once, its reverse once; positive volume.
TEST_P(Tessellation, IsClosedOutwardAndConvex) {
  const Shape& s = GetParam();
  const TriangleMesh m = tessellate_primitive(s.type, s.size);
  const std::size_t expected = s.type == mjGEOM_BOX        ? 12u
                               : s.type == mjGEOM_CYLINDER ? 4u * kTessAround
                                                           : 2u * kTessAround * (kTessProfile - 1);
  EXPECT_EQ(m.faces.size(), expected) << s.name();
  std::map<std::pair<int, int>, int> edges;
  for (const auto& f : m.faces) {
    for (int k = 0; k < 3; ++k) ++edges[{f[k], f[(k + 1) % 3]}];
  }
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 1) << s.name();
    const auto back = edges.find({e.second, e.first});
    ASSERT_NE(back, edges.end()) << s.name() << ": open edge";
    EXPECT_EQ(back->second, 1) << s.name();
  }
  EXPECT_GT(testing::signed_volume6(m), 0.0) << s.name();
  // Convex: every vertex on the inner side of every face's plane (to rounding).
  const Planes p = face_planes(m);
  const double scale = std::max({s.size[0], s.size[1], s.size[2]});
  for (const Vec3& v : m.vertices) EXPECT_LE(outside_by(p, v), 1e-14 * scale) << s.name();
}

// Sampled points of the true surface never lie outside the tessellation's solid (tolerance 0):
// a uniform grid, random points, and the points where facets touch the true surface (mid-angles
// between ring vertices, at the profile edges' tangent latitudes).
TEST_P(Tessellation, ContainsTheTrueSurface) {
  const Shape& s = GetParam();
  const TriangleMesh m = tessellate_primitive(s.type, s.size);
  const Planes p = face_planes(m);
  std::vector<std::pair<double, double>> uv;
  for (int i = 0; i < 97; ++i) {
    for (int j = 0; j <= 60; ++j) uv.emplace_back(i / 97.0, j / 60.0);
  }
  seeded::Rng rng(7);
  for (int i = 0; i < 4000; ++i) {
    const double u = seeded::uniform01(rng);
    const double v = seeded::uniform01(rng);
    uv.emplace_back(u, v);
  }
  for (int j = 0; j < kTessAround; ++j) {
    for (int k = 0; k <= 2 * kTessProfile; ++k) {
      uv.emplace_back((j + 0.5) / kTessAround, static_cast<double>(k) / (2 * kTessProfile));
    }
  }
  double worst = -1e300;
  for (const auto& [u, v] : uv) {
    const Vec3 x = s.surface_point(u, v);
    const double out = outside_by(p, x);
    worst = std::max(worst, out);
    EXPECT_LE(out, 0.0) << s.name() << " at u " << u << " v " << v;
    if (out > 0) break;
  }
  // Boxes: the true surface is the tessellation's, points lie on facets.
  if (s.type == mjGEOM_BOX) {
    EXPECT_EQ(worst, 0.0) << s.name();
  }
}

// Every vertex lies within the documented tolerance of the true solid (the maximum over a flat
// facet of the distance to a convex solid is at a vertex), and the tolerance is nearly reached
// (at least 90 % of it; ellipsoids, whose bound uses the largest radius in every direction, at
// least 75 %); boxes: vertices exactly the corners.
TEST_P(Tessellation, DeviationIsWithinTheDocumentedTolerance) {
  const Shape& s = GetParam();
  const TriangleMesh m = tessellate_primitive(s.type, s.size);
  const double tol = tessellation_tolerance(s.type, s.size);
  double worst = 0;
  for (const Vec3& v : m.vertices) worst = std::max(worst, s.distance(v));
  EXPECT_LE(worst, tol) << s.name();
  if (s.type == mjGEOM_BOX) {
    EXPECT_EQ(tol, 0.0);
    for (const Vec3& v : m.vertices) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(std::abs(v[k]), s.size[k]);
    }
  } else {
    EXPECT_GE(worst, (s.type == mjGEOM_ELLIPSOID ? 0.75 : 0.9) * tol) << s.name();
  }
  std::printf("%-28s tolerance %.3e m, largest vertex deviation %.3e m\n", s.name().c_str(), tol,
              worst);
}

INSTANTIATE_TEST_SUITE_P(Shapes, Tessellation, ::testing::ValuesIn(test_shapes()));

TEST(Tessellation, DocumentedFactors) {
  // primitives.h: k_round - 1 = 0.0103735 and k_around - 1 = 0.0048386 at N = 32, M = 15.
  EXPECT_NEAR(tess_round_factor() - 1, 0.0103735, 5e-7);
  EXPECT_NEAR(tess_around_factor() - 1, 0.0048386, 5e-7);
}

// Contact generation sees sharp edges only on boxes and cylinder rims (primitives.h).
TEST(Tessellation, SharpEdgesOnlyOnBoxesAndCylinderRims) {
  const auto sharp_bits = [](const TriangleMesh& m) {
    std::vector<Triangle> tris;
    for (std::size_t f = 0; f < m.faces.size(); ++f) tris.push_back(m.triangle(f));
    int n = 0;
    for (std::uint8_t mask : sharp_edge_masks(tris))
      n += (mask & 1) + (mask >> 1 & 1) + (mask >> 2 & 1);
    return n;
  };
  EXPECT_EQ(sharp_bits(tessellate_sphere(0.01)), 0);
  EXPECT_EQ(sharp_bits(tessellate_capsule(0.01, 0.03)), 0);
  EXPECT_EQ(sharp_bits(tessellate_cylinder(0.01, 0.03)), 4 * kTessAround);  // 2 rims, 2 faces each
  EXPECT_EQ(sharp_bits(tessellate_box(Vec3(0.01, 0.02, 0.03))), 24);  // 12 edges, 2 faces each
}

TEST(Tessellation, RejectsNonPrimitivesAndBadSizes) {
  const mjtNum size[3] = {0.01, 0.02, 0.03};
  EXPECT_THROW(tessellate_primitive(mjGEOM_PLANE, size), std::invalid_argument);
  EXPECT_THROW(tessellate_primitive(mjGEOM_MESH, size), std::invalid_argument);
  const mjtNum zero[3] = {0, 0.02, 0.03};
  EXPECT_THROW(tessellate_primitive(mjGEOM_SPHERE, zero), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Served primitive pairs in MuJoCo.

int geom_id(const mjModel* m, const char* name) { return mj_name2id(m, mjOBJ_GEOM, name); }

// Places the free body of geom `g` at `pos` with orientation `quat`.
void place(const mjModel* m, mjData* d, int g, const Vec3& pos, const double* quat = nullptr) {
  double* q = d->qpos + m->jnt_qposadr[m->body_jntadr[m->geom_bodyid[g]]];
  for (int k = 0; k < 3; ++k) q[k] = pos[k];
  const double identity[4] = {1, 0, 0, 0};
  for (int k = 0; k < 4; ++k) q[3 + k] = (quat ? quat : identity)[k];
}

// A sphere (tessellated) against a mesh cube, and a sphere against a capsule (both tessellated),
// at random positions with the sphere's centre outside the other solid: when the true surfaces
// meet graspcd reports contact; when they are farther apart than the tessellations'
// tolerances, it reports none.
TEST(ServedPrimitives, TessellatedPairsNeverMissAContactAndAddNoneBeyondTheTolerance) {
  TempDir dir;
  const ModelPtr m = load_scene(dir, R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <option gravity="0 0 0"/>
  <asset><mesh name="cube" file="cube.obj"/></asset>
  <worldbody>
    <geom name="cube" type="mesh" mesh="cube"/>
    <geom name="capsule" type="capsule" size="0.02 0.03" pos="0.5 0 0" contype="2" conaffinity="2"/>
    <body name="b1"><freejoint/><geom name="ball" type="sphere" size="0.01" contype="1" conaffinity="1"/></body>
    <body name="b2"><freejoint/><geom name="ball2" type="sphere" size="0.007" contype="2" conaffinity="2"/></body>
  </worldbody>
</mujoco>)",
                                {{"cube", testing::make_box_mesh(0.03, 0.03, 0.03)}});
  ASSERT_TRUE(m);
  const int cube = geom_id(m.get(), "cube"), capsule = geom_id(m.get(), "capsule");
  const int ball = geom_id(m.get(), "ball"), ball2 = geom_id(m.get(), "ball2");
  ScopedInstall scope;
  RegistryConfig config;
  config.patterns = {{"ball", "cube"}, {"ball2", "capsule"}};
  Registry registry(m.get(), config);
  const Attachment attached = attach(registry);
  EXPECT_EQ(registry.tree_count(), 4u);  // cube mesh, two sphere sizes, the capsule
  EXPECT_EQ(registry.primitive_tree_count(), 3u);
  const double tol_ball = tessellation_tolerance(mjGEOM_SPHERE, m->geom_size + 3 * ball);
  const double tol_ball2 = tessellation_tolerance(mjGEOM_SPHERE, m->geom_size + 3 * ball2);
  const double tol_capsule = tessellation_tolerance(mjGEOM_CAPSULE, m->geom_size + 3 * capsule);
  ASSERT_GT(tol_ball, 0.0);

  seeded::Rng rng(2024);
  const DataPtr d(mj_makeData(m.get()));
  int touch[2] = {0, 0}, apart[2] = {0, 0}, between[2] = {0, 0};
  for (int i = 0; i < 400; ++i) {
    // The ball around the cube, centre outside it.
    const Vec3 p1 = seeded::uniform_vec3(rng, -0.045, 0.045);
    if (p1.cwiseAbs().maxCoeff() <= 0.03) continue;
    // The small ball around the capsule (axis z at x = 0.5), centre outside it.
    const Vec3 p2 =
        seeded::uniform_in_box(rng, Vec3(-0.035, -0.035, -0.06), Vec3(0.035, 0.035, 0.06));
    const double axis_gap = (p2 - Vec3(0, 0, std::clamp(p2[2], -0.03, 0.03))).norm();
    if (axis_gap <= 0.02) continue;
    mj_resetData(m.get(), d.get());
    place(m.get(), d.get(), ball, p1);
    place(m.get(), d.get(), ball2, p2 + Vec3(0.5, 0, 0));
    mj_forward(m.get(), d.get());
    const double gap1 = (p1.cwiseAbs() - Vec3(0.03, 0.03, 0.03)).cwiseMax(0.0).norm() - 0.01;
    const double gap2 = axis_gap - 0.02 - 0.007;
    const bool ours1 = !contacts_between(d.get(), ball, cube).empty();
    const bool ours2 = !contacts_between(d.get(), ball2, capsule).empty();
    for (int k = 0; k < 2; ++k) {
      const double gap = k == 0 ? gap1 : gap2;
      const double allowance = k == 0 ? tol_ball : tol_ball2 + tol_capsule;
      const bool ours = k == 0 ? ours1 : ours2;
      if (gap <= 0) {
        EXPECT_TRUE(ours) << "pair " << k << " pose " << i << ": true surfaces meet, gap " << gap;
        ++touch[k];
      } else if (gap > allowance) {
        EXPECT_FALSE(ours) << "pair " << k << " pose " << i << ": apart by " << gap;
        ++apart[k];
      } else {
        ++between[k];
      }
    }
  }
  for (int k = 0; k < 2; ++k) {
    EXPECT_GE(touch[k], 20) << k;
    EXPECT_GE(apart[k], 20) << k;
  }
  EXPECT_GT(registry.stats().counters.tri_tests, 0u);
  EXPECT_EQ(registry.stats().box_box_calls, 0u);
  std::printf(
      "sphere/cube: %d touching, %d apart, %d within the tolerance; sphere/capsule: %d, %d, %d\n",
      touch[0], apart[0], between[0], touch[1], apart[1], between[1]);
}

// The solver can use contacts of tessellated primitives: a capsule lying on its side and an
// upright cylinder, dropped onto a fixed mesh slab, rest on it at their radius / half-height above
// its top (within the tolerance plus MuJoCo's soft-contact penetration).
TEST(ServedPrimitives, CapsuleAndCylinderRestOnAMeshSlab) {
  TempDir dir;
  const ModelPtr m = load_scene(dir, R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <option timestep="0.002"/>
  <asset><mesh name="slab" file="slab.obj"/></asset>
  <worldbody>
    <geom name="slab" type="mesh" mesh="slab"/>
    <body name="cap" pos="-0.05 0 0.06" euler="0 90 0"><freejoint/>
      <geom name="cap" type="capsule" size="0.01 0.02"/></body>
    <body name="cyl" pos="0.05 0 0.06"><freejoint/>
      <geom name="cyl" type="cylinder" size="0.012 0.015"/></body>
  </worldbody>
</mujoco>)",
                                {{"slab", testing::make_box_mesh(0.1, 0.1, 0.01)}});
  ASSERT_TRUE(m);
  ScopedInstall scope;
  RegistryConfig config;
  config.patterns = {{"slab", "cap"}, {"slab", "cyl"}};
  Registry registry(m.get(), config);
  const Attachment attached = attach(registry);
  const DataPtr d(mj_makeData(m.get()));
  while (d->time < 1.0) mj_step(m.get(), d.get());
  const int cap = mj_name2id(m.get(), mjOBJ_BODY, "cap");
  const int cyl = mj_name2id(m.get(), mjOBJ_BODY, "cyl");
  const double z_cap = d->xpos[3 * cap + 2], z_cyl = d->xpos[3 * cyl + 2];
  std::printf("capsule rests at z %.5f (true 0.02), cylinder at %.5f (true 0.025)\n", z_cap, z_cyl);
  EXPECT_NEAR(z_cap, 0.02, 0.001);
  EXPECT_NEAR(z_cyl, 0.025, 0.001);
  for (int b : {cap, cyl}) {
    const double* v = d->cvel + 6 * b;
    EXPECT_LT(Vec3(v[3], v[4], v[5]).norm(), 0.01);
  }
  EXPECT_GT(registry.stats().contacts, 0u);
}

// A stand-in for MuJoCo's box-box function that counts its calls and forwards them.
struct BoxBoxLog {
  static mjfCollision real;
  static int calls;
  static int collide(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2,
                     mjtNum margin) {
    ++calls;
    return real(m, d, con, g1, g2, margin);
  }
};
mjfCollision BoxBoxLog::real = nullptr;
int BoxBoxLog::calls = 0;

void expect_same_contacts(const std::vector<mjContact>& x, const std::vector<mjContact>& y) {
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const mjContact& a = x[i];
    const mjContact& b = y[i];
    EXPECT_EQ(a.geom1, b.geom1);
    EXPECT_EQ(a.geom2, b.geom2);
    EXPECT_EQ(a.dist, b.dist);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.pos[k], b.pos[k]);
    for (int k = 0; k < 9; ++k) EXPECT_EQ(a.frame[k], b.frame[k]);
  }
}

// Box-box pairs: the detector decides, MuJoCo's box-box routine makes the contacts. At random
// poses the contacts are MuJoCo's native ones bit for bit, no tree exists, no triangle is tested,
// and MuJoCo's routine runs only where the detector could not prove the boxes disjoint.
TEST(ServedPrimitives, BoxBoxPairsAreExactWithoutTriangles) {
  TempDir dir;
  const ModelPtr m = load_scene(dir, R"(
<mujoco>
  <size nconmax="200" njmax="800"/>
  <option gravity="0 0 0"/>
  <worldbody>
    <body name="a"><freejoint/><geom name="a" type="box" size="0.03 0.01 0.02"/></body>
    <body name="b"><freejoint/><geom name="b" type="box" size="0.008 0.025 0.015"/></body>
  </worldbody>
</mujoco>)",
                                {});
  ASSERT_TRUE(m);
  const int a = geom_id(m.get(), "a"), b = geom_id(m.get(), "b");
  seeded::Rng rng(99);
  std::vector<std::pair<Vec3, std::array<double, 4>>> poses;
  for (int i = 0; i < 300; ++i) {
    std::array<double, 4> quat{seeded::uniform(rng, -1, 1), seeded::uniform(rng, -1, 1),
                               seeded::uniform(rng, -1, 1), seeded::uniform(rng, -1, 1)};
    mju_normalize4(quat.data());
    const Vec3 position = seeded::uniform_vec3(rng, -0.06, 0.06);
    poses.emplace_back(position, quat);
  }
  const DataPtr d(mj_makeData(m.get()));
  const auto contacts_at = [&](std::size_t i) {
    mj_resetData(m.get(), d.get());
    place(m.get(), d.get(), b, poses[i].first, poses[i].second.data());
    mj_forward(m.get(), d.get());
    return std::vector<mjContact>(d->contact, d->contact + d->ncon);
  };
  std::vector<std::vector<mjContact>> native;
  for (std::size_t i = 0; i < poses.size(); ++i) native.push_back(contacts_at(i));
  const mjfCollision saved = mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_BOX];
  BoxBoxLog::real = saved;
  mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_BOX] = &BoxBoxLog::collide;
  int with_contact = 0, proven_disjoint = 0;
  BridgeStats total;
  {
    ScopedInstall scope;
    RegistryConfig config;
    config.patterns = {{"a", "b"}};
    Registry registry(m.get(), config);
    const Attachment attached = attach(registry);
    ASSERT_EQ(registry.pairs().size(), 1u);
    EXPECT_EQ(registry.pairs()[0].path, PairPath::kBoxBox);
    EXPECT_EQ(registry.tree_count(), 0u);
    EXPECT_EQ(registry.geom_tree(a), nullptr);
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const int log_before = BoxBoxLog::calls;
      const BridgeStats before = registry.stats();
      const std::vector<mjContact> ours = contacts_at(i);
      SCOPED_TRACE("pose " + std::to_string(i));
      expect_same_contacts(ours, native[i]);
      const std::uint64_t served = registry.stats().box_box_calls - before.box_box_calls;
      const int mujoco_calls = BoxBoxLog::calls - log_before;
      EXPECT_LE(mujoco_calls, static_cast<int>(served));
      if (served > 0 && mujoco_calls == 0) {
        ++proven_disjoint;
        EXPECT_TRUE(native[i].empty());
      }
      with_contact += !ours.empty();
    }
    total = registry.stats();
    EXPECT_EQ(registry.tree_count(), 0u);
  }
  mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_BOX] = saved;
  EXPECT_EQ(total.counters.tri_tests, 0u);
  EXPECT_EQ(total.calls, total.box_box_calls);
  EXPECT_EQ(total.counters.box_tests, total.box_box_calls);
  EXPECT_GE(with_contact, 30);
  EXPECT_GE(proven_disjoint, 10);
  std::printf("box-box: %llu served calls, %d with contact, %d proven disjoint by the detector\n",
              static_cast<unsigned long long>(total.box_box_calls), with_contact, proven_disjoint);
}

// ---------------------------------------------------------------------------------------------
// The box hand (mjcf/hand_boxes.xml): every finger segment a box, the object three boxes.

const std::string kMjcf = GRASPCD_MJCF_DIR;

// Closing every finger hinge from 0 in steps of 0.02 rad until finger-object contacts appear:
// contacts come, only box-box pairs are served, no tree is built and no triangle tested; the
// contacts are MuJoCo's own at every step.
TEST(BoxHand, ClosingTouchesWithoutTrianglesOrTrees) {
  char error[1024] = "";
  const ModelPtr m(mj_loadXML((kMjcf + "/hand_boxes.xml").c_str(), nullptr, error, sizeof(error)));
  ASSERT_TRUE(m) << error;
  const std::string config_path = kMjcf + "/hand_boxes.pairs.json";
  const DataPtr native(mj_makeData(m.get()));
  const DataPtr ours(mj_makeData(m.get()));
  const auto close_to = [&](mjData* d, double angle) {
    mj_resetData(m.get(), d);
    for (const std::string& s : grasp::finger_segment_names()) {
      d->qpos[m->jnt_qposadr[mj_name2id(m.get(), mjOBJ_JOINT, s.c_str())]] = angle;
    }
    mj_forward(m.get(), d);
  };
  std::set<int> object, fingers;
  const int object_body = mj_name2id(m.get(), mjOBJ_BODY, "object");
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] == object_body) object.insert(g);
  }
  for (const std::string& s : grasp::finger_segment_names())
    fingers.insert(geom_id(m.get(), s.c_str()));
  ASSERT_EQ(object.size(), 3u);
  ASSERT_EQ(fingers.size(), 12u);
  const auto finger_object_contacts = [&](const mjData* d) {
    int n = 0;
    for (int i = 0; i < d->ncon; ++i) {
      const mjContact& c = d->contact[i];
      n += (object.count(c.geom1) && fingers.count(c.geom2)) ||
           (object.count(c.geom2) && fingers.count(c.geom1));
    }
    return n;
  };

  ScopedInstall scope;
  Registry registry(m.get(), load_registry_config(config_path), config_path);
  EXPECT_EQ(registry.pairs().size(), 36u);  // 12 segments x 3 object boxes
  for (const ServedPair& p : registry.pairs()) EXPECT_EQ(p.path, PairPath::kBoxBox);
  EXPECT_EQ(registry.tree_count(), 0u);
  double angle = 0;
  int contacts = 0;
  for (; angle < 1.6 && contacts == 0; angle += 0.02) {
    close_to(native.get(), angle);  // natively (registry not attached yet)
    Attachment attached = attach(registry);
    close_to(ours.get(), angle);
    attached.release();
    SCOPED_TRACE("angle " + std::to_string(angle));
    expect_same_contacts(std::vector<mjContact>(ours->contact, ours->contact + ours->ncon),
                         std::vector<mjContact>(native->contact, native->contact + native->ncon));
    contacts = finger_object_contacts(ours.get());
  }
  const BridgeStats& st = registry.stats();
  std::printf(
      "box hand: finger contact at %.2f rad (%d contacts); %llu served calls, %llu box tests, %llu "
      "triangle tests, %zu trees\n",
      angle - 0.02, contacts, static_cast<unsigned long long>(st.calls),
      static_cast<unsigned long long>(st.counters.box_tests),
      static_cast<unsigned long long>(st.counters.tri_tests), registry.tree_count());
  EXPECT_GT(contacts, 0);
  EXPECT_GT(angle, 0.1);  // open at the start
  EXPECT_GT(st.counters.box_tests, 0u);
  EXPECT_EQ(st.calls, st.box_box_calls);
  EXPECT_GT(st.contacts, 0u);
  EXPECT_EQ(st.counters.tri_tests, 0u);
  EXPECT_EQ(st.counters.tri_pairs, 0u);
  EXPECT_EQ(registry.tree_count(), 0u);
}

// The grasp (grasp/grasp.h) on the box hand: with graspcd the box-box contacts are MuJoCo's
// own, so the run is the native run: the same first-contact steps and the same object heights;
// the object is lifted and held both ways, and every closing step ran box tests, no triangle.
TEST(BoxHand, GraspLiftsAndHoldsLikeTheNativeRun) {
  const std::string scene = kMjcf + "/hand_boxes.xml";
  grasp::GraspOptions options;
  const grasp::GraspResult ours = grasp::run_grasp(scene, options);
  options.native = true;
  const grasp::GraspResult native = grasp::run_grasp(scene, options);
  for (const grasp::GraspResult* r : {&ours, &native}) {
    std::printf("hand_boxes %-6s: %zu grasp steps, first contact", r->method.c_str(),
                r->steps.size());
    for (int k : r->first_contact) std::printf(" %d", k);
    std::printf("; z %.4f -> %.4f (hold min %.4f, drift %.4f), held %d\n", r->object_z_initial,
                r->object_z_final, r->hold_min_z, r->hold_drift, r->held ? 1 : 0);
  }
  EXPECT_TRUE(ours.gripped);
  EXPECT_TRUE(ours.held);
  EXPECT_TRUE(native.held);
  EXPECT_GT(ours.object_z_final, ours.object_z_initial + 0.03);
  EXPECT_EQ(ours.first_contact, native.first_contact);
  EXPECT_EQ(ours.steps.size(), native.steps.size());
  EXPECT_EQ(ours.object_z_final, native.object_z_final);
  std::uint64_t box_tests = 0;
  for (const grasp::GraspStepRecord& s : ours.steps) {
    EXPECT_EQ(s.triangle_tests, 0u) << "step " << s.step;
    box_tests += s.box_tests;
  }
  EXPECT_GT(box_tests, 0u);
  EXPECT_GT(ours.detection_ns_close, 0u);
}

}  // namespace
}  // namespace graspcd::mujoco::primitives_test
