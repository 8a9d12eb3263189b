// The race's judge (docs/design.md "The race"): each contact a grasp hands to MuJoCo's
// solver, whatever made it (graspcd's manifold, MuJoCo on the hull, MuJoCo on convex pieces),
// judged against the true meshes by the exact module at the same poses.
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace graspcd::study {

struct ContactJudgeSummary {
  int steps = 0;                 // closing grasp steps judged
  std::uint64_t contacts = 0;    // hand-object contacts judged (both geoms meshes)
  std::uint64_t phantom = 0;     // contacts whose point lies > kPhantomDistance from a true surface
  std::uint64_t missed = 0;      // (hand geom, step) where CGAL says the true meshes intersect and
                                 // the configuration gave that geom no contact with the object
  std::uint64_t truth_hits = 0;  // (hand geom, step) where CGAL says they intersect
  // phantom and missed per hand geom (by name; absent: none).
  std::map<std::string, std::uint64_t> phantom_by_geom, missed_by_geom;
  // Per hand geom (by name), the first closing grasp step at which CGAL says its true mesh meets
  // the object's (absent: never).
  std::map<std::string, int> cgal_first_contact;
  std::map<std::string, int> cgal_first_contact_body;  // the same per hand body (by name)
};

// A contact point farther than this from either true surface is a phantom (metres).
constexpr double kPhantomDistance = 1e-3;

// Built on the model a grasp runs (after mj_loadXML, before the grasp), it is then called after
// each closing grasp step (GraspOptions::on_grasp_step).
//  - The object: the body named `object_body` (and its subtree). Its true surfaces are its mesh
//    geoms but the pieces of a decomposition (grasp::is_piece: grasp --decomposed keeps the
//    original geom, without collision, beside its pieces, named or not).
//  - The hand: every mesh or primitive geom that can collide (contype or conaffinity non-zero)
//    outside the object's subtree, the world body and the body named `support_body` ("": none);
//    a primitive's true surface is mujoco::tessellate_primitive's (a box exactly, curved ones
//    circumscribed within mujoco::tessellation_tolerance, far below the 1 mm of a phantom).
//  - The support: the body the object stands on (the drive config's "support", drive_config.h),
//    whose contact with the object MuJoCo makes natively in every configuration. Its own geoms
//    are neither judged nor counted as missed; its subtree's are (a hand carried by the body the
//    object stands on stays judged).
//  - At each step: every contact between an object geom and a hand geom is judged by the
//    distance of its point (MuJoCo's contact pos) to the hand geom's true surface and to the
//    nearest true object surface (exact::SurfaceDistance, CGAL's AABB tree, in each geom's frame
//    from MuJoCo's float vertices); and every (hand geom, true object geom) pair is decided by
//    exact::mesh_mesh_pairs (first contact) on the geom-frame triangles posed by
//    mujoco::relative_pose. A hand geom whose true mesh meets the object's with no contact with
//    any object geom at that step is a missed contact.
// Not judged: whether the true meshes are more than 1 mm apart when a contact's point is within
// 1 mm of both surfaces (the meshes are then within 2 mm).
class ContactJudge {
 public:
  // Throws std::invalid_argument for an object or support body the model does not have, a
  // support that is the object or inside it, or an object without a mesh geom.
  // `inflation` (m): the object's surface as the judged simulator collides it lies this far
  // outside the true mesh (a rigid flex's radius): a contact is phantom only beyond
  // kPhantomDistance plus it.
  ContactJudge(const mjModel* m, const std::string& object_body = "object",
               const std::string& support_body = "", double inflation = 0);
  ~ContactJudge();
  ContactJudge(const ContactJudge&) = delete;
  ContactJudge& operator=(const ContactJudge&) = delete;

  void judge_step(const mjModel* m, const mjData* d, int step);
  // The same with the step's contacts given apart from d (a run record's, placed at d's state).
  void judge_step(const mjModel* m, const mjData* d, int step, const mjContact* contacts, int n);
  const ContactJudgeSummary& summary() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The summary as `grasp --judge --json` and `graspcd judge --json` give it ("judge"): the counts,
// per geom, the contact error per closing step, CGAL's first contacts and the phantom distance
// used.
nlohmann::json contact_judge_json(const ContactJudgeSummary& summary, double inflation = 0);

}  // namespace graspcd::study
