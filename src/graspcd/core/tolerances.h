// Every tolerance of the geometry core, named once, with its unit, its value and what breaks if it
// changes. Nothing else in src/graspcd/core may introduce a numeric tolerance of its own.
#pragma once

namespace graspcd::tol {

// Unit roundoff of IEEE double (round to nearest): u = 2^-53. Dimensionless. The error bounds of
// the floating-point filters are multiples of it.
inline constexpr double kUnitRoundoff = 0x1p-53;

// Exact predicates (predicates.h) evaluate determinants with expansion arithmetic; they stay exact
// as long as no intermediate product underflows or overflows. That holds for every input coordinate
// x with x == 0 or kMinCoordinate <= |x| <= kMaxCoordinate (metres). The text parsers reject values
// outside this range as bad input, so no answer is ever silently inexact.
inline constexpr double kMaxCoordinate = 1e50;
inline constexpr double kMinCoordinate = 1e-50;

// A rotation (box axes, pose) whose R^T R differs from the identity by more than this, entrywise,
// is bad input. Dimensionless. Fitted boxes are orthonormal to ~1e-15.
inline constexpr double kOrthonormalTol = 1e-9;

// SAT (sat.h) declares "separated" only when the gap on an axis L exceeds (L unnormalised: for the
// cross-product axes |L| = sin of the edges' angle <= 1, so in metres the slack can be up to
// slack / |L|)
//   slack = kSatRelativeSlack * (sum of both boxes' half-extents + |cB - cA|_1)
//         + kSatRoundoffFactor * (|cA|_1 + |cB|_1)                              (metres)
// The first term covers axes that are up to kOrthonormalTol away from orthonormal and near-parallel
// edge pairs, whose cross-product axis is ~0 (Gottschalk's "epsilon added to |R|", made relative
// to the boxes' size and distance so that it means the same at every scale). The second covers the
// rounding of the box centres far from the origin. Smaller values risk a false "separated" (a
// missed collision); larger ones only add false "may overlap" answers, which the tree resolves.
inline constexpr double kSatRelativeSlack = 1e-8;
inline constexpr double kSatRoundoffFactor = 16 * kUnitRoundoff;

// The tree query with SAT (tree_query.h) carries B's node frame in A's node frame down both trees
// (RAPID style): each step multiplies by a stored child-in-parent frame, so R and T gather
// rounding from every level. Its slack at a node pair is
//   kSatRelativeSlack * (sum of both boxes' half-extents + 2 |T|_1)
//   + kSatCarriedRoundoffFactor * (depth_A + depth_B + 2) * S                   (metres),
// with S = 2 (|cA_root|_1 + sum hA_root + |cB_root|_1 + sum hB_root) in A's frame, a bound on the
// size of every node centre, extent and centre distance in either tree (a node's centre lies
// within sqrt(3) of its triangles' farthest vertex, which lies in the root box). 2 |T|_1 bounds
// the |cB - cA|_1 of the direct test (|d|_1 <= sqrt(3) |d|_2 = sqrt(3) |T|_2). One carried step
// (a 3x3 product and a difference, the stored frame itself rounded) moves T by at most about
// 16 u S and R's entries by about 8 u, so the second term covers every level four times over,
// including the direct test's rounding of the root frame; R's drift moves B's corners by
// depth * 8 u * sum hB, far inside the first term. Smaller risks a false "separated"; larger only
// sends node pairs closer than ~1e-12 S further down the tree.
inline constexpr double kSatCarriedRoundoffFactor = 64 * kUnitRoundoff;

// The tree query's front (tree_query.h, collide_coherent) is followed while B moved little
// relative to A since it was recorded: a rotation of at most kFrontMaxRotation (radians) and a
// shift of B's root box centre of at most kFrontMaxShift times the root box's diagonal. Past
// either, the descent starts from the roots again. Speed only: every front gives the same answer.
// Larger values follow stale fronts (many node pairs deep in the trees that one test higher up
// would have settled); smaller ones give up the front at a grasp's ordinary motions (a finger at 2
// rad/s turns 0.004 rad per 2 ms step).
inline constexpr double kFrontMaxRotation = 0.1;
inline constexpr double kFrontMaxShift = 0.1;
// Every kFrontPullUpPeriod-th restarted query pulls its front up where node pairs moved apart
// (tree_query.h, pull_up_front): each attempt costs a box test whether or not it succeeds, so a
// front is not pulled up at every step. Speed only: every 32nd restart, chosen by the instructions
// of whole grasps against 4, 16, 64 and never (docs/performance.md, "Fronts across steps").
inline constexpr unsigned kFrontPullUpPeriod = 32;
// front_motion (tree_query.h) bounds how far B's boxes moved between two poses; the bound is
// computed in doubles from a few products and sums (rounding well below 1e-15 relative), so it is
// enlarged by kFrontMotionRelative times itself plus kFrontMotionRelative times the magnitudes
// that entered it (metres). Smaller risks keeping a front pair that now overlaps untested (a
// missed collision); larger only tests front pairs a little earlier. Dimensionless.
inline constexpr double kFrontMotionRelative = 1e-9;

// An OBB fit pads each half-extent by this fraction of the largest |coordinate| of the fitted
// points (metres per metre), so that every vertex lies inside the box although the projections that
// size it are rounded. Smaller: a vertex may poke out by an ulp; larger: looser boxes.
inline constexpr double kObbFitPad = 64 * kUnitRoundoff;

// The absolute epsilon of Moller's reference code (1997), on unnormalised plane distances (m^3).
// Used only by the deliberately naive variant kept for the study: at grasp scale it answers
// "intersect" for many disjoint pairs.
inline constexpr double kNaiveMollerEpsilon = 1e-6;

// The perceptron (perceptron.h) proves two boxes disjoint only when its plane w.x + d clears
// every corner by more than the corners' positional uncertainty times |w|_1 plus the rounding of
// w.x + d. The positional uncertainty of a corner is
//   kPerceptronCornerFactor * (|cA|_1 + |cB|_1 + sum of both boxes' half-extents)   (metres),
// which covers the rounding of the corners themselves, of the pose that placed the box, and of the
// OBB fit's own pad (tolerances of the same order as the SAT's roundoff term). Smaller risks a
// plane that separates the computed corners but not the true boxes; larger only sends more node
// pairs down the tree.
inline constexpr double kPerceptronCornerFactor = 16 * kUnitRoundoff;

// Default pass caps (docs/design.md, "Semantics"): the paper's triangle hand used 1,500 (section
// 11), its box hand 10,000 (section 9); Neuro-SAT switches to SAT after 300 passes (section 10).
inline constexpr int kPerceptronDefaultCap = 1500;
inline constexpr int kNeuroSatDefaultSwitch = 300;

// --- Contact geometry (contact.h: triangle_contact.h, mesh_features.h, contact_manifold.h):
// contacts for the solver, not collision answers. None of these changes whether two meshes
// intersect; they shape the contacts handed to MuJoCo.

// Edges sharper than this dihedral angle (radians between the two faces' normals) are feature
// edges. 30 degrees: a box's edges (90) are, a sphere or cylinder tessellated with 12 or more
// segments around (<= 30) is not. Smaller: edges of smooth tessellated surfaces give edge-edge
// directions of no meaning; larger: the edges of a box or a C-block no longer do.
inline constexpr double kSharpEdgeAngle = 0.5235987755982988;

// Edge pairs whose directions are parallel to within this sine have no cross-product axis
// (dimensionless). Smaller admits axes whose direction is rounding noise; larger only skips a
// candidate direction (the face normals remain).
inline constexpr double kContactParallelEdgeSine = 1e-9;

// An edge axis (unit) whose dot product with n_a - n_b is at most this in magnitude lies nearly in
// both faces (dimensionless): the face normals do not decide its sign and the smaller of the two
// sides does. Smaller lets a tilt of no meaning pick a sign (at 1e-6 a pad's edge 0.23 degrees off
// a voxel cup's measured 10 mm instead of 0.09 mm and kicked the held cup: docs/performance.md,
// "Holds"); larger leaves more axes to the two-sided rule, which holds while the penetration is
// under half the triangles' overlap.
inline constexpr double kContactSignCosine = 0.1;

// Penetration depths handed to the solver are clipped to this by default (metres; a pair config's
// "max_depth" overrides it): a triangle pair far inside the other geom says little about the local
// penetration, and MuJoCo's soft contacts keep true penetrations at millimetres. Larger: a deep
// triangle pair can fling the object; smaller: the solver may not push out a real penetration.
inline constexpr double kContactMaxDepth = 0.01;

// Contact manifold (contact_manifold.h, build_contact_manifold). A patch grows from its deepest
// contact through contacts whose triangles touch (share a vertex on either geom) and whose normal
// is within this angle of the seed's: 35 degrees (cosine, dimensionless). Smaller splits one curved
// contact region (a finger on a cup of radius 3.5 cm spans about 16 degrees) into several patches,
// each spending the pair's budget on its own deepest point; larger merges the two walls of a
// corner (90 degrees) or the two faces of a pinched wall (180) into one patch with a meaningless
// mean normal.
inline constexpr double kPatchNormalCosine = 0.8191520442889918;

// Contacts handed to the solver per patch and per geom pair by default (a pair config's
// "max_patch_contacts" and "max_contacts" override them). Four points span a patch's support
// polygon (Jolt keeps four per manifold: "no more than 4 are needed for a stable solution"); eight
// per pair leave room for two to eight patches (a pinch, a corner) while keeping MuJoCo's
// contact and constraint buffers (nconmax, njmax) far from full. More: the solver sees redundant,
// nearly parallel constraints (slower, less stable); fewer: a patch can rock on its points.
inline constexpr int kManifoldPatchContacts = 4;
inline constexpr int kManifoldPairContacts = 8;

// The force reduction's reference (contact_manifold.h, "Force reduction"; ManifoldOptions::
// reference_per_pair): the points per pair of the support reduction whose summed depth and centre
// of pressure per patch its fewer points keep. The support reduction's default budget, kept apart
// from kManifoldPairContacts so that lowering that budget leaves the reference where it was
// measured. Larger: a patch's force summed over more (deeper and shallower) support points.
inline constexpr int kManifoldReferencePairContacts = 8;

// When a patch's next point would enlarge the convex hull of the points chosen so far by less
// than this fraction of the squared extent of the patch (dimensionless), the points are taken as
// collinear and the next is the one farthest from the chosen instead. Smaller lets rounding noise
// across a straight contact line pick a point near the chosen ones; larger gives up real but thin
// support polygons.
inline constexpr double kManifoldFlatArea = 1e-9;

}  // namespace graspcd::tol
