// What a run of `graspcd study` (study.h) is asked to do: the options that the study and each of
// its experiments (Table 1, the box hand, the sweep) read.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace graspcd::study {

class MeshScene;  // recording.h
class Querier;    // replay.h

// A replay method from outside the study's own detectors: a peer library (FCL, in the graspcd
// executable: graspcd/peer/fcl_querier.h). It is one more row of Table 1, after the detector
// methods, replayed and checked against CGAL like them. The study library links no peer; the
// caller hands these in.
struct PeerMethod {
  std::string name;                                                // its row name, "fcl-obb"
  std::function<std::unique_ptr<Querier>(const MeshScene&)> make;  // its querier on a scene
};

struct Shard {
  int index = 0;  // 0 .. count-1
  int count = 1;
};

struct StudyOptions {
  std::string out_dir = "report/out";
  std::string mjcf_dir;  // the scenes (default: graspcd::mjcf_dir())
  bool quick = false;    // example 1, fewer methods and sweep points: the smoke test
  int repeats = 5;       // timed replays per method (medians of these)
  // Timed replays of Table 1's perceptron methods that run to the cap of 1,500 passes
  // (perceptron, perceptron-warm, perceptron-scaled), at most `repeats`: they are most of a
  // study's time.
  int perceptron_repeats = 2;
  int max_steps = 400;  // closing grasp steps at most
  // Replays run this many at a time, one thread each (0: one per core). Each replay's clock
  // measures its own thread's queries; the box hand of Figures 13-15 always runs alone.
  int jobs = 0;
  bool table = true;  // Table 1 and Figures 13-15
  bool sweep = true;  // the error sweep
  // The sweep on all three examples with every knob value (a cluster job, see --shard); by
  // default it runs on example 1 with the standard values.
  bool full_sweep = false;
  std::optional<Shard> shard;     // only this shard of the sweep (implies table = false)
  std::vector<PeerMethod> peers;  // Table 1's peer rows, in this order after the detectors
};

}  // namespace graspcd::study
