// The true meshes' penetration over a grasp run, whatever geometry the run collides (graspcd's
// contacts, MuJoCo's convex hulls with --native, convex pieces with --decomposed): how deep the
// object went into a hand geom or its support, or one of them into the object, as the true
// surfaces say.
//
// What is measured, on the run's start state and once per grasp step after it (every
// physics_steps_per_grasp_step-th state, in every phase; the caller, motion_watch.h, says when):
// for each object geom and each geom outside the object's body tree that the contype/conaffinity
// filter lets collide with it (as the start check, start_check.h, sees the scene; for a decomposed
// scene the true object model, decomposed_pieces.h), when their bounding spheres (geom_rbound)
// overlap:
//  - a closed mesh or primitive against another: the deepest probe of each inside the other's
//    solid, by the exact inside test and the distance to the surface of core/penetration.h
//    (deepest_point_inside), both ways. Probes are a geom's vertices and points along its edges
//    at most kTrueProbeSpacing apart (MuJoCo's float vertices in the geom frame; primitives: the
//    MuJoCo layer's tessellations, primitives.h). A vertex measure can underestimate the true depth
//    (penetration.h); it never invents one.
//  - a geom whose mesh is not closed has no inside: only the other's inside is tested (its own
//    probes in the other's solid), and the result says so (TruePenetration::partial); two open
//    meshes are not measured at all (TruePenetration::unmeasured).
//  - a plane: the depth of the object's lowest probe below it (its solid is the half-space under
//    it). Height fields are not measured (unmeasured).
// A sample per grasp step: an object thrown faster than a thin support's thickness per grasp step
// can pass through it between two samples and leave only a shallow depth; the ejection verdict
// (grasp.h) catches such a run. A plane has no thickness to pass: the depth below it stays.
// A pair that moved too little since its last measure to pass the deepest of its side found so
// far is not measured again (a depth moves no more than the probes do), and in a pair measured
// only the probes that could lie deeper than that are tested (a probe inside a solid lies no
// deeper than it lies inside the solid's bounding box): the maxima, their step and geom are those
// of measuring every probe of every pair at every grasp step. The surfaces come from a
// SurfaceCache (surface_cache.h), each built the first time a pair needs it.
// Each measured geom is the hand's (any body but the world and the support's body tree) or the
// support's (the world body: a floor; the support body tree of a driven hand). The deepest over
// the run, its grasp step, time, phase and geom, and the deepest per side.
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <vector>

#include "graspcd/grasp/surface_cache.h"

namespace graspcd::grasp {

// The most two probes along an edge lie apart, m.
inline constexpr double kTrueProbeSpacing = 1e-3;

struct TruePenetration {
  double max = 0;          // the deepest over the run, m (0: none found in `measures` grasp steps)
  long step = -1;          // its sample, counted over the whole run from 1 (the start); -1: none
  double time = 0;         // its simulated time, s
  std::string phase;       // its phase ("the start", "the closing", "the squeeze", "the settling",
                           // "the lift", "the hold")
  std::string geom;        // the geom the object went into or that went into it ("" when none)
  std::string side;        // "hand" or "support" ("" when none)
  double hand_max = 0;     // the deepest against hand geoms, m
  double support_max = 0;  // the deepest against the support (a floor, a table), m
  long measures = 0;       // states measured
  int pairs = 0;           // (object geom, other geom) pairs watched, at least one side tested
  // What is measured only one way: "geom 'bowl' (the object) is not closed: only the other
  // geoms' insides are tested, with its probes" (one line per open geom).
  std::vector<std::string> partial;
  // What is not measured: two open meshes, a height field (one line each).
  std::vector<std::string> unmeasured;
};

class TruePenetrationWatch {
 public:
  // `truth`: the model whose geoms are the true surfaces and whose collision bits say which pairs
  // are watched (the run's model, or for a decomposed scene its true_object_model: same geom
  // ids). `object_body`: the object's body (its body tree is the object); `support_root`: the
  // root of the support's body tree, -1 for none (the world body is always the support).
  // `surfaces`: the surfaces of `truth`'s geoms, kept by the caller across runs (null: the watch
  // keeps its own).
  TruePenetrationWatch(const mjModel* truth, int object_body, int support_root,
                       SurfaceCache* surfaces = nullptr);
  ~TruePenetrationWatch();
  TruePenetrationWatch(const TruePenetrationWatch&) = delete;
  TruePenetrationWatch& operator=(const TruePenetrationWatch&) = delete;

  // Measures the state `d` (of the run's model: geom placements by the same ids), the run's
  // sample `step`, at simulated time `time`, in `phase`.
  void measure(const mjData* d, long step, double time, const std::string& phase);
  const TruePenetration& result() const { return result_; }

 private:
  struct Pair;
  std::unique_ptr<SurfaceCache> own_surfaces_;
  SurfaceCache* surfaces_;
  std::vector<Pair> pairs_;
  const mjModel* truth_;
  TruePenetration result_;
};

}  // namespace graspcd::grasp
