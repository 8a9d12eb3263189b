// `graspcd validate --objects DIR`: a set of objects checked against CGAL, one row per
// object. Every OBJ and STL file under DIR (searched recursively, the extension in any case,
// sorted by its path relative to DIR) goes through the `grasp --object` run (grasp/object_run.h):
// placed in the template hand's scene with the same placement options (--fit, --scale, --up,
// --yaw), its start state checked, then validate_scene() (validate.h) runs the grasp and checks
// every registered pair through the closing and the squeeze (validate.h's default phases).
//
// A row: the object's scale and size, the closing grasp steps checked, those at which CGAL found
// some pair intersecting (steps with contact), CGAL's hits (pair checks that intersect, summed
// over the pairs and steps; the same for every method), per method its missed and false
// collisions (and triangle pairs), and the grasp's verdict (gripped, held, the reason). An object
// that cannot be checked (a bad mesh, a start state that is not valid) is a row `refused` with
// the one-line error naming its file, and a warning (`object_refused`); the other objects go on.
//
// Scale-out: a shard i/N takes every N-th object from the i-th (as `study --shard`); the
// document names the whole set, the settings and the shard, so merge_object_shards() can check
// that its shards are one split of one set, each present once.
#pragma once

#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "graspcd/grasp/hand_templates.h"
#include "graspcd/grasp/object_scene.h"
#include "graspcd/study/study.h"
#include "graspcd/study/validate.h"

namespace graspcd::study {

struct ObjectSetOptions {
  std::string dir;           // searched recursively
  grasp::HandTemplate hand;  // the template (grasp/hand_templates.h)
  // scale, fit, up, yaw_degrees, pose: the same for every object (file is ignored).
  grasp::ObjectPlacement placement;
  int max_steps = 400;  // most closing grasp steps per object
  // The first disagreement of each (method, pair, object) is written into OUT/<object path
  // without its extension>/ (validate.h); empty: nothing is written.
  std::string out_dir;
  std::optional<Shard> shard;                   // only this shard of the set
  std::function<void(const std::string&)> log;  // progress, one line per object
  // Called after each object with the document so far (its rows up to this one, no verdicts
  // yet) and the object's row, e.g. to print the row at once (object_set_row).
  std::function<void(const nlohmann::json& doc, const nlohmann::json& row)> on_row;
};

// The mesh files under `dir` (every extension io::load_mesh reads), relative to it ('/'
// separated), sorted: every entry of such a name that is not a folder, so that a FIFO or a device
// gets its row, refused. Symbolic links are followed only where they lead to a place under
// `dir`, and each folder is read once (by device and inode), so that a link loop (`up -> ..`) or
// a link out of `dir` adds nothing; a link of a mesh's name that is not followed is named in the
// warning `object_skipped`. Throws io::InputError naming `dir` when it is not a folder or holds
// no such file.
std::vector<std::string> find_object_files(const std::string& dir);

// Validates the objects of the set (of the shard) with every tester. The document: objects_dir,
// hand, template, settings (scale, fit, up, yaw, pose, max_steps, methods), objects (the whole
// set, relative paths), shard {index, count}, rows (this shard's objects in set order: object,
// status "checked" or "refused", error, scale, fitted, size, steps, steps_with_contact, states and
// states_with_contact (every phase checked: the closing's grasp steps and the squeeze's),
// cgal_hits, gripped, held, reason, methods: method, checks, agree, missed, false_contacts,
// missed_tri_pairs, false_tri_pairs), missed_any and false_any (some method missed a collision
// or a triangle pair, or gave a false one, on some object), refused (the objects refused). No
// envelope (the caller adds it when it writes the document). Throws std::invalid_argument for a bad
// `up` (a usage error).
nlohmann::json validate_object_set(const ObjectSetOptions& options,
                                   const std::vector<TesterSpec>& testers);

// Joins shard documents (files written from validate_object_set, each with its envelope) into
// one document of the whole set, rows in set order, its verdicts (missed_any, false_any,
// refused) counted again over them. Throws std::runtime_error naming the file
// (not a shard, another set or settings, another split, a shard given twice) or naming the
// missing shard and its objects.
nlohmann::json merge_object_shards(const std::vector<std::string>& files);

// The set's table (`validate --objects` without --json): a header, one row per object, the
// refusals, the result.
std::string object_set_text(const nlohmann::json& doc);
// The same in three parts, for a table printed as its rows come: the header and the column
// names (from the document's set, settings and shard; no rows needed), one row, and the
// refusals and the result (from the finished document).
std::string object_set_head(const nlohmann::json& doc);
std::string object_set_row(const nlohmann::json& doc, const nlohmann::json& row);
std::string object_set_tail(const nlohmann::json& doc);

// The document with its envelope as OUT/objects.json, or OUT/objects.shard-i-of-N.json for a
// shard. Throws io::InputError naming the folder or file that cannot be written.
void write_object_set(const std::string& out_dir, nlohmann::json doc);

}  // namespace graspcd::study
