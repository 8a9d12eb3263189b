// The run record (docs/run-record.md): a grasp's states, one JSON line per physics step, written
// by `graspcd grasp --write-run` (RunRecordWriter) or any other simulator, read and checked
// against the judged scene by `graspcd judge` (RunRecordReader). State only, never verdicts.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "graspcd/grasp/motion_watch.h"
#include "graspcd/io/output_files.h"

namespace graspcd::grasp {

inline constexpr const char* kRunRecordFormat = "graspcd-run";
inline constexpr int kRunRecordVersion = 1;

// The header's fields (docs/run-record.md, "Line 1").
struct RunHeader {
  std::string scene;
  std::string simulator;
  std::string configuration;
  double timestep = 0;
  int nq = 0, nv = 0;
  std::string object, hand, support;  // body names; the support "world" for the world
  bool contacts = false;
  double inflation = 0;  // m
  std::optional<int> noslip_iterations;
  std::optional<bool> multiccd;
  int max_steps = 0;
  bool six_directions = false;  // with the parameters of six_directions.h
};

// How the run ended (docs/run-record.md, "The last line").
struct RunEnd {
  std::string closing;  // "touched", "max_steps", or "" when not said
  std::string status;   // "ok", "nonfinite", "cannot start"
  std::string message;
};

// Writes a record whole or not at all (io::AtomicFile): the header at construction, the start
// state, one line per physics step, the end line, then commit().
class RunRecordWriter {
 public:
  // `geom_ids`: the record's geom id of each of the run model's geoms (a decomposed scene's
  // pieces as the geom they replace, the others as in the scene as given); empty: the same ids.
  // Throws io::InputError naming `path` when it cannot be written.
  RunRecordWriter(const std::string& path, const RunHeader& header, std::vector<int> geom_ids = {});
  ~RunRecordWriter();
  RunRecordWriter(const RunRecordWriter&) = delete;
  RunRecordWriter& operator=(const RunRecordWriter&) = delete;

  // The start state (qpos, qvel, time of d).
  void start(const mjModel* m, const mjData* d);
  // The state after a physics step of `phase` (direction 0 .. 5 for kDirection), with the step's
  // contacts of the object's body tree (`object` its body) when the header says so.
  void step(const mjModel* m, const mjData* d, RunPhase phase, int grasp_step, int direction,
            int object);
  // The end line, then the file renamed into place.
  void end(const RunEnd& end);

 private:
  void line(const std::string& text);
  RunHeader header_;
  std::vector<int> geom_ids_;
  io::AtomicFile file_;
  std::ofstream out_;
  bool ended_ = false;
};

// A contact of a record line, its geoms as ids of the judged scene (a flex side: the object's
// first geom with a surface).
struct RecordContact {
  int geom1 = -1, geom2 = -1;
  std::array<double, 3> pos{}, normal{};
  double dist = 0;
};

// A state line of a record.
struct RecordState {
  long line = 0;  // in the file, from 1
  double t = 0;
  RunPhase phase = RunPhase::kStart;
  int direction = -1;  // 0 .. 5 for kDirection
  int grasp_step = 0;  // kClose: from 1
  std::vector<double> qpos, qvel;
  std::vector<RecordContact> contacts;
};

// Reads a record line by line, checking each against the judged scene's model `m` and the
// scene's bodies (`object`, `hand`, `support` as the scene's drive names them; support "world"
// for the world). Every malformed record is an io::InputError naming the file and its line
// (docs/run-record.md, "Refusals").
class RunRecordReader {
 public:
  // Reads and checks the header (a six_directions other than six_directions.h's is refused).
  RunRecordReader(const std::string& path, const mjModel* m, const std::string& object,
                  const std::string& hand, const std::string& support);
  const RunHeader& header() const { return header_; }
  // The next state line into `out`: true; or false after the end line (end() is then set).
  bool next(RecordState& out);
  const RunEnd& end() const { return end_; }

 private:
  [[noreturn]] void refuse(const std::string& what) const;
  void check_finite(const nlohmann::json& value) const;
  const nlohmann::json& key(const nlohmann::json& object, const char* name) const;
  double number(const nlohmann::json& object, const char* name) const;
  std::vector<double> numbers(const nlohmann::json& object, const char* name,
                              std::size_t count) const;
  RecordContact contact(const nlohmann::json& value) const;
  int side(const nlohmann::json& contact, const char* name) const;
  int body(const std::string& name, const char* what) const;

  std::string path_;
  std::ifstream in_;
  const mjModel* m_;
  RunHeader header_;
  RunEnd end_;
  long line_ = 0;
  bool ended_ = false;
  bool started_ = false;
  int object_ = -1;
  int flex_geom_ = -1;  // the geom a flex side maps to
  // Where the lines are: the last phase (and direction), grasp step and time seen, and the
  // hold's last time.
  int order_ = -1;
  int grasp_step_ = 0;
  double last_t_ = 0;
  double hold_end_ = 0;
};

}  // namespace graspcd::grasp
