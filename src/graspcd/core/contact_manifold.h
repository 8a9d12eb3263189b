// The contact manifold of a geom pair.
//
// MuJoCo's solver wants few, well-spread contacts per pair with consistent normals and depths, not
// one contact per intersecting triangle pair (a fingertip in a cup wall gives dozens). The
// manifold groups a pair's triangle-pair contacts (triangle_contact.h) into patches and keeps a
// few points of each. Pure geometry, in geom1's frame.
#pragma once

#include <cstddef>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/mesh_features.h"
#include "graspcd/core/tolerances.h"
#include "graspcd/core/triangle_contact.h"

namespace graspcd {

// Chooses at most `k` of `contacts` (indices, the deepest first): the deepest contact, then
// farthest-point sampling on positions (Gonzalez 1985: each next contact maximises its distance
// to the chosen ones; ties go to the deeper one), which keeps a spread over the contact region.
// Returns all indices, deepest first, when there are at most k.
std::vector<std::size_t> select_contacts(const std::vector<TriContact>& contacts, std::size_t k);

// How a patch's points are chosen (build_contact_manifold, step 2).
enum class ManifoldReduction {
  // The support polygon: the deepest member and the hull extremes, each with the seed's normal and
  // its own depth along it (the default).
  kSupport,
  // The patch's net normal force and its moment kept (build_contact_manifold, "Moment
  // reduction"): a centre-of-pressure anchor and support extremes, all with the net normal, their
  // depths fitted so that the points' depth-weighted centre is the proxy's central-axis point.
  kMoment,
  // The support reduction's points at the reference budget, reduced to the pair's budget with the
  // same summed depth and depth-weighted centre per patch (build_contact_manifold, "Force
  // reduction").
  kForce,
};

struct ManifoldOptions {
  int max_per_patch = tol::kManifoldPatchContacts;  // points kept per patch (>= 1)
  int max_per_pair = tol::kManifoldPairContacts;    // points kept per geom pair (>= 1)
  double patch_cosine = tol::kPatchNormalCosine;    // see tolerances.h
  ManifoldReduction reduction = ManifoldReduction::kSupport;
  // The force reduction's reference: the points per pair the support reduction would keep, whose
  // summed depth and depth-weighted centre each patch's fewer points reproduce (>= 1).
  int reference_per_pair = tol::kManifoldReferencePairContacts;
};

struct ContactPatch {
  Vec3 normal = Vec3::UnitZ();       // the seed's (the deepest candidate's) normal, unit
  double depth = 0;                  // the deepest member's depth along `normal`
  double area = 0;                   // area of the kept points' convex hull across `normal`
  std::vector<std::size_t> members;  // indices into the candidates, deepest first
  // The patch's chosen points (indices), in choice order; under the moment reduction its support
  // extremes (the anchor is no candidate).
  std::vector<std::size_t> selected;
};

struct ContactManifold {
  std::vector<ContactPatch> patches;  // the deepest patch first
  // What the solver gets: at most max_per_pair points, each with its patch's normal and its depth
  // along it; the deepest point of every patch first (deepest patch first), then the patches'
  // further points, the patch of largest area first.
  std::vector<TriContact> contacts;
  // The patch (index into `patches`) each of `contacts` belongs to.
  std::vector<std::size_t> contact_patch;
  // Each of `contacts`' gain: how much its reported depth changes per unit of penetration along
  // its normal, so that a patch's summed depth follows the reference's (ReusedContacts refreshes
  // depths by it): 1, and |S| / m for the m points of a patch the force reduction reduced.
  std::vector<double> contact_gain;
};

// Builds the manifold of one geom pair from its candidates: candidate i is the contact of the
// intersecting triangles faces_a[i] (geom1) and faces_b[i] (geom2, in any one frame: only equal
// coordinates matter). Deterministic: the result depends on the candidates' order only through
// ties, so callers pass them in the sorted order of their triangle pairs. Throws
// std::invalid_argument, naming the lengths, unless faces_a and faces_b each hold one triangle per
// candidate; no candidates (and no faces) give the empty manifold.
//
// 1. Patches: the deepest unassigned candidate seeds a patch, which grows breadth-first through
//    candidates whose triangles share a vertex (exactly equal coordinates) with a member's on
//    either geom -- consecutive triangle pairs along one intersection curve share a triangle --
//    and whose normal lies within acos(patch_cosine) of the seed's. A finger pinching a wall from
//    both sides, or touching two walls of a corner, gives one patch per side; a flat face on a
//    flat face gives one.
// 2. Points of a patch (at most max_per_patch), in the patch plane (positions projected across
//    the patch normal): the deepest member; then the member farthest from it; then each next the
//    member that most enlarges the convex hull of those chosen (the support polygon), after the
//    largest-area reduction of Jolt Physics (PruneContactPoints in ManifoldBetweenTwoFaces.cpp,
//    which keeps 4); when no member enlarges it (collinear points), the one farthest from the
//    chosen. Ties go to the deeper, then the earlier candidate.
// 3. The pair's budget as described at ContactManifold::contacts.
// Each kept point keeps its position; its normal is the patch's and its depth the candidate's
// depth times the cosine between its normal and the patch's (its penetration along the patch
// normal), so the points of a patch push along one direction. What is lost: the other candidates
// (the full triangle-pair list stays with the caller: validate, meshpair and the study use it),
// and patches beyond max_per_pair (the shallowest).
//
// Moment reduction (options.reduction == kMoment; patches as in step 1). Detection has geometry,
// not forces, so each patch's normal force is given a proxy: member i (position p_i, unit normal
// n_i, depth a_i along the seed's normal, step 2's) pushes with w_i = a_i along n_i (depth-
// weighted normals; all w_i = 1 when every a_i is 0). The proxy's net force F = sum w_i n_i, its
// direction N = F / |F| (the seed's normal when |F| vanishes), its centre of pressure
// c = sum w_i p_i / sum w_i and its moment about c, M = sum w_i (p_i - c) x n_i. The patch gives
// at most max_per_patch points, every one with normal N:
//   - the anchor, at the proxy's central-axis point c* = c + N x M / |F| (the point about which
//     the proxy's moment is least: only its torsion N (N . M) remains), with depth
//     sum w_i a_i / sum w_i along N (the proxy's mean penetration);
//   - up to max_per_patch - 1 support extremes (step 2's rule: the deepest member, then the hull
//     extremes), each with its depth along N, then the least change of those depths (least
//     squares, clamped at 0) that puts the extremes' depth-weighted centre at c* across N; what
//     the clamp leaves, the anchor takes by moving across N (d * its offset from c* cancels it).
// The pair's budget: every patch's anchor first (the deepest patch first), then the patches'
// extremes, the patch of largest area first; a patch's depths are fitted to the extremes it keeps.
// The bound the tests check: taking each kept point's depth d_j as its force along its normal,
// (1) the patch's kept force sum d_j N has the proxy's direction N exactly (rounding only), and
// (2) the kept points' moment about c per unit force, sum d_j (q_j - c) x N / sum d_j, equals the
// proxy's, M / |F|, except for the torsion along N (which normals all along N cannot carry):
//     | sum d_j (q_j - c) x N / sum d_j - M / |F| | = |N . M| / |F|
//                                                  <= sum w_i |p_i - c| sin(n_i, N) / |F|,
// exactly so (rounding aside) whenever the anchor's depth is positive. On a flat patch (all n_i
// equal) both sides are 0: the kept points' depth-weighted centre is the centre of pressure. This
// follows the reduction of Newton (newton-physics, contact_reduction / the hydroelastic reduction:
// the aggregate force sum area * pressure * normal kept as the reduced normal, plus an anchor
// contact at the centre of pressure), with the largest-area support points of Jolt Physics
// (PruneContactPoints) and the minimum-moment point of a force system (Poinsot's central axis,
// as Drake's ContactResultantForceCalculator places a resultant).
//
// Force reduction (options.reduction == kForce; patches and their points as in steps 1 and 2).
// The proxy is what the support reduction hands the solver at the reference budget
// (max(options.reference_per_pair, max_per_pair) points per pair, max_per_patch per patch): a
// patch's reference set S, points q_j with depths d_j along the patch normal N, each taken as a
// spring pushing with force d_j along N (a soft contact's steady force grows with its reported
// depth). Its force is D N, D = sum_S d_j, and its centre of pressure c = sum_S d_j q_j / D, about
// which its moment is 0 (every force along N). The pair's budget (max_per_pair) is spent as step 3
// spends it, giving each patch m <= |S| points K: the first m of S in step 2's choice order (the
// deepest, the farthest, the hull extremes), and
//   - when m == |S|, exactly S (positions and depths);
//   - else depths scaled to sum D (e_k = d_k D / sum_K d_k; D / m each when sum_K d_k is 0), then
//     the least-norm change of them that keeps the sum and puts their depth-weighted centre at c
//     across N (e_k + l0 + l . o_k, o_k the offset of q_k from c across N), clamped at 0 and
//     rescaled to sum D; what the clamp or a too-small K (one point, a segment) leaves is taken
//     by moving all of K across N by the same offset t, the depth-weighted centre's from c.
// The bound the tests check, per patch with D > 0 (rounding aside): every kept normal is N;
// e_k >= 0; (1) sum_K e_k = D, the proxy's force; (2) sum_K e_k (x_k - c) x N = 0, its moment
// about c (x_k the kept positions); (3) x_k = q_k - t with t across N and |t| <= the largest
// distance between two points of S (c and the depth-weighted centre of K both lie in S's hull);
// (4) e_k <= D <= |S| max_depth when the candidates' depths are capped at max_depth (the cap
// bounds a patch's force, as under the support reduction at the reference budget, not each
// point's reported depth). A patch with D = 0 keeps its m points at depth 0. Patches beyond
// max_per_pair (the shallowest) are lost, as under step 3. This is the contact reduction of
// Newton (newton-physics, contact_reduction: the aggregate normal force of the removed contacts
// kept by the reduced set, plus a point at the centre of pressure) on the largest-area support
// points of Jolt Physics (PruneContactPoints).
ContactManifold build_contact_manifold(const std::vector<TriContact>& candidates,
                                       const std::vector<Triangle>& faces_a,
                                       const std::vector<Triangle>& faces_b,
                                       const ManifoldOptions& options = {});

// The same manifold from the candidates' triangles given as welded vertex ids (ids of one geom
// from one weld_vertex_ids call, e.g. kept with the geom's tree): what the MuJoCo layer calls, with
// no coordinates to compare per candidate. Throws std::invalid_argument, naming the lengths,
// unless vertices_a and vertices_b each hold one entry per candidate, and std::length_error for an
// id of 2^31 or more. (A name of its own: an overload would make build_contact_manifold(c, {}, {})
// ambiguous.)
ContactManifold build_contact_manifold_by_ids(const std::vector<TriContact>& candidates,
                                              const std::vector<FaceVertexIds>& vertices_a,
                                              const std::vector<FaceVertexIds>& vertices_b,
                                              const ManifoldOptions& options = {});

// build_contact_manifold_by_ids into `out`, whose contents it replaces, keeping its buffers (and
// its patches' member lists) for the next call: a caller that builds a manifold every physics step
// allocates nothing once warm. The same manifold, bit for bit, and the same exceptions (named
// build_contact_manifold_by_ids).
void build_contact_manifold_into(const std::vector<TriContact>& candidates,
                                 const std::vector<FaceVertexIds>& vertices_a,
                                 const std::vector<FaceVertexIds>& vertices_b,
                                 const ManifoldOptions& options, ContactManifold& out);

}  // namespace graspcd
