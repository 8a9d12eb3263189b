// The served paths of the MuJoCo layer (collision_served.h): the tree query with its contacts, and
// the exact box-box path.
#include "graspcd/mujoco/collision_served.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "graspcd/core/clock.h"
#include "graspcd/core/contact.h"
#include "graspcd/core/tree_query.h"
#include "graspcd/mujoco/collision_pose.h"

namespace graspcd::mujoco {

void write_contact(const TriContact& c, const Mat3& R1, const Vec3& p1, mjContact& out) {
  const Vec3 pos = R1 * c.pos + p1;
  const Vec3 n = (R1 * c.normal).normalized();
  Vec3 axis = Vec3::Zero();
  axis[static_cast<Eigen::Index>(std::abs(n[0]) <= std::abs(n[1])
                                     ? (std::abs(n[0]) <= std::abs(n[2]) ? 0 : 2)
                                     : (std::abs(n[1]) <= std::abs(n[2]) ? 1 : 2))] = 1;
  const Vec3 t1 = n.cross(axis).normalized();
  const Vec3 t2 = n.cross(t1);
  out.dist = -c.depth;
  for (int k = 0; k < 3; ++k) {
    out.pos[k] = pos[k];
    out.frame[k] = n[k];
    out.frame[3 + k] = t1[k];
    out.frame[6 + k] = t2[k];
  }
}

namespace {

// Writes `contacts` (geom1's frame) into `con` in the world frame, at most mjMAXCONPAIR; returns
// how many.
int write_contacts(const std::vector<TriContact>& contacts, const mjData* d, int g1,
                   mjContact* con) {
  const Mat3 R1 = from_row_major(d->geom_xmat + 9 * g1);
  const Vec3 p1 = geom_position(d, g1);
  int n = 0;
  for (const TriContact& c : contacts) {
    if (n == mjMAXCONPAIR) break;
    write_contact(c, R1, p1, con[n++]);
  }
  return n;
}

// The separate containment check of a tree-path pair whose surfaces did not intersect: only closed
// solids contain, and only when the root boxes overlap can one lie inside the other. Sets the
// state's flag and counts it (the time from `queried`).
void check_containment(const MeshTree& t1, const MeshTree& t2, const Pose& pose,
                       Clock::time_point queried, Registry::DataPairState& state,
                       BridgeStats& stats) {
  if (!t1.closedness.closed() && !t2.closedness.closed()) return;
  if (sat_separating_axis(t1.tree.root().box, transform(pose, t2.tree.root().box)) != kSatNoAxis) {
    return;
  }
  const MeshContainment c = mesh_containment(t1.tree, t1.closedness, pose, t2.tree, t2.closedness,
                                             /*surfaces_intersect=*/false);
  state.contained = c.a_inside_b || c.b_inside_a;
  stats.contained += state.contained;
  stats.containment_ns += elapsed_ns(queried, Clock::now());
}

// One candidate per intersecting triangle pair, in geom1's frame, in sorted pair order (the
// manifold is then the same whatever order the query found them in), and the welded vertex ids
// of both faces of each.
void collect_candidates(std::vector<TrianglePair>& tri_pairs, const MeshTree& t1,
                        const MeshTree& t2, const Pose& pose, double max_depth,
                        std::vector<TriContact>& candidates, std::vector<FaceVertexIds>& vertices_a,
                        std::vector<FaceVertexIds>& vertices_b) {
  std::sort(tri_pairs.begin(), tri_pairs.end());
  const double tn = pose.t.norm();
  const Vec3 fallback = tn > 0 ? Vec3(pose.t / tn) : Vec3(Vec3::UnitZ());
  candidates.clear();
  vertices_a.clear();
  vertices_b.clear();
  for (const TrianglePair& tp : tri_pairs) {
    const Triangle& a = t1.face(tp.a);
    // Placed as the query placed it for its triangle test (posed_triangle: apply_pose's doubles,
    // by the AVX2 kernel where it is on).
    const Triangle b = detail::posed_triangle(pose, t2.face(tp.b));
    candidates.push_back(
        triangle_pair_contact(a, b, max_depth, fallback, t1.sharp(tp.a), t2.sharp(tp.b)));
    vertices_a.push_back(t1.vertices(tp.a));
    vertices_b.push_back(t2.vertices(tp.b));
  }
}

// Tree path: tree query (paper sections 2-6 through core's Detector, all contacts), one candidate
// contact per intersecting triangle pair (contact.h, after Bullet's GImpact clip method), in the
// sorted order of the pairs, reduced to the pair's manifold (contact.h: patches, at most
// max_patch_contacts points each and max_contacts in all), written in the world frame. With
// "contact_reuse" (pair_config.h), the pair's last contacts on this mjData, refreshed, while it
// moved less than that (contact.h, ReusedContacts).
int collide_trees(Registry& registry, const ServedPair& served, Registry::DataPairState& state,
                  const mjData* d, mjContact* con, int g1, int g2) {
  thread_local std::vector<TrianglePair> tri_pairs;
  thread_local std::vector<TriContact> candidates;
  thread_local std::vector<FaceVertexIds> vertices_a, vertices_b;
  thread_local ContactManifold manifold;  // its buffers kept from call to call
  const MeshTree* t1 = registry.geom_tree(g1);
  const MeshTree* t2 = registry.geom_tree(g2);
  BridgeStats& stats = registry.stats();
  if (!t1 || !t2) return 0;

  // The tree query with geom2 placed in geom1's frame.
  const Pose pose = relative_pose(d, g1, g2);
  const Clock::time_point start = Clock::now();
  const double reuse = registry.config().contact_reuse;
  const bool front_list = registry.config().front_list;
  ReusedContacts* kept = reuse > 0 ? &state.reused : nullptr;
  if (kept && kept->refresh(pose, t1->radius, t2->radius, reuse, candidates)) {
    const double max_depth = registry.config().max_depth;
    // The cap of the exact path, where it applies before the reduction: times each contact's gain.
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      candidates[i].depth = std::min(candidates[i].depth, max_depth * kept->gains()[i]);
    }
    const int n = write_contacts(candidates, d, g1, con);
    state.contained = false;
    ++stats.reused;
    stats.contacts += static_cast<std::uint64_t>(n);
    stats.contact_ns += elapsed_ns(start, Clock::now());
    return n;
  }
  tri_pairs.clear();
  if (front_list) {
    QueryFront& front = state.front;
    state.detector.collide_coherent(t1->tree, t2->tree, pose, stats.counters, &tri_pairs, front);
    stats.front_restarts += front.restarted;
  } else {
    state.detector.collide(t1->tree, t2->tree, pose, QueryMode::kAllContacts, stats.counters,
                           &tri_pairs);
  }
  const Clock::time_point queried = Clock::now();
  stats.detection_ns += elapsed_ns(start, queried);
  state.contained = false;
  if (tri_pairs.empty()) {
    if (kept) kept->clear();
    check_containment(*t1, *t2, pose, queried, state, stats);
    return 0;
  }

  collect_candidates(tri_pairs, *t1, *t2, pose, registry.config().max_depth, candidates, vertices_a,
                     vertices_b);

  // The manifold: a few points per patch, the pair's budget in all; the triangles' shared
  // vertices by the ids welded once per tree (geom_trees.cpp), as build_contact_manifold would weld
  // geom1's faces and geom2's in its own frame.
  build_contact_manifold_into(candidates, vertices_a, vertices_b, served.manifold, manifold);
  if (candidates.size() > static_cast<std::size_t>(served.manifold.max_per_pair)) {
    ++stats.capped_pairs;
  }
  stats.candidates += candidates.size();
  stats.patches += manifold.patches.size();
  const int n = write_contacts(manifold.contacts, d, g1, con);
  if (kept) kept->store(pose, manifold.contacts, manifold.contact_gain);
  stats.contacts += static_cast<std::uint64_t>(n);
  stats.contact_ns += elapsed_ns(queried, Clock::now());
  return n;
}

// Box-box path: the pair's box separator (core/separators.h: SAT after Gottschalk, Lin, Manocha
// 1996, or the paper's perceptron / Neuro-SAT, each exact in its "disjoint" answer) on the two
// geoms' boxes, geom2 placed in geom1's frame; when it cannot prove them disjoint, MuJoCo's own
// box-box routine (mjc_BoxBox of engine_collision_box.c, the saved original entry) makes the
// contacts with margin 0, and only touching or penetrating ones (dist <= 0) are kept.
int collide_box_box(Registry& registry, const ServedPair& served, Registry::DataPairState& state,
                    const mjData* d, mjContact* con, int g1, int g2, mjfCollision box_box) {
  const mjModel* m = registry.model();
  BridgeStats& stats = registry.stats();
  ++stats.box_box_calls;
  const Pose pose = relative_pose(d, g1, g2);
  Obb a;
  a.half = Vec3(m->geom_size[3 * g1], m->geom_size[3 * g1 + 1], m->geom_size[3 * g1 + 2]);
  Obb b_local;
  b_local.half = Vec3(m->geom_size[3 * g2], m->geom_size[3 * g2 + 1], m->geom_size[3 * g2 + 2]);
  const Clock::time_point start = Clock::now();
  const bool disjoint = state.detector.box_disjoint(a, transform(pose, b_local), stats.counters);
  const Clock::time_point tested = Clock::now();
  stats.detection_ns += elapsed_ns(start, tested);
  if (disjoint) return 0;

  if (!box_box) return 0;
  const int found = box_box(m, d, con, g1, g2, 0);
  int n = 0;
  for (int i = 0; i < found && n < mjMAXCONPAIR; ++i) {
    if (con[i].dist > 0) continue;
    if (n != i) con[n] = con[i];
    ++n;
  }
  // The pair's budget (MuJoCo's box-box makes at most 8): the deepest, in MuJoCo's order.
  const int budget = served.manifold.max_per_pair;
  if (n > budget) {
    std::stable_sort(con, con + n,
                     [](const mjContact& x, const mjContact& y) { return x.dist < y.dist; });
    n = budget;
  }
  stats.contacts += static_cast<std::uint64_t>(n);
  stats.contact_ns += elapsed_ns(tested, Clock::now());
  return n;
}

}  // namespace

int collide_served_pair(Registry& registry, int pair_index, const mjData* d, mjContact* con, int g1,
                        int g2, mjfCollision box_box) {
  const ServedPair& served = registry.pair(pair_index);
  Registry::DataPairState& state = registry.pair_state(d, pair_index);
  BridgeStats& stats = registry.stats();
  ++stats.calls;
  // A NaN or infinite placement: no query on a meaningless pose, no contacts, counted.
  if (bad_geom_placement(d, g1) || bad_geom_placement(d, g2)) {
    ++stats.nonfinite_skips;
    state.contained = false;
    return 0;
  }
  return served.path == PairPath::kBoxBox
             ? collide_box_box(registry, served, state, d, con, g1, g2, box_box)
             : collide_trees(registry, served, state, d, con, g1, g2);
}

}  // namespace graspcd::mujoco
