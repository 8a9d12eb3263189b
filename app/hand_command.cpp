// graspcd hand check TEMPLATE.xml | HAND.xml --drive FILE: what a template hand, or a hand file
// with its drive, lacks to take a user's object (grasp/hand_check.h), each missing piece with how
// to add it.

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "command.h"
#include "graspcd/grasp/hand_check.h"
#include "graspcd/version/envelope.h"
#include "object_placement.h"

namespace graspcd::cli {

namespace {

struct HandCliOptions {
  std::string hand;
  std::string drive;
  bool json = false;
};

// "FILE:LINE" (or "FILE" for the whole file) of a missing piece.
std::string where(const grasp::MissingPiece& p) {
  return p.line > 0 ? p.file + ":" + std::to_string(p.line) : p.file;
}

// `given`: HAND as the user gave it (a built-in template's name, or a file).
void print_text(const grasp::HandCheck& c, const std::string& given) {
  for (const grasp::MissingPiece& p : c.missing) {
    std::cout << "missing: " << where(p) << ": " << p.what << "\n  add: " << p.how << '\n';
  }
  for (const std::string& n : c.notes) std::cout << "note: " << n << '\n';
  if (c.complete()) {
    std::cout << c.scene << ": complete (" << c.summary << "); try: graspcd grasp --object MESH "
              << "--hand " << given << (c.wrapped ? " --drive " + c.pairs : "") << '\n';
  } else {
    std::cout << c.scene << ": " << c.missing.size()
              << (c.missing.size() == 1 ? " piece" : " pieces")
              << " missing (docs/hands.md builds a template step by step)\n";
  }
}

nlohmann::json check_json(const grasp::HandCheck& c) {
  nlohmann::json missing = nlohmann::json::array();
  for (const grasp::MissingPiece& p : c.missing) {
    missing.push_back({{"file", p.file}, {"line", p.line}, {"what", p.what}, {"how", p.how}});
  }
  return {{"scene", c.scene},   {"pairs", c.pairs}, {"complete", c.complete()},
          {"missing", missing}, {"notes", c.notes}, {"summary", c.summary}};
}

void run_hand_check(const HandCliOptions& o, int* exit_code) {
  const grasp::HandTemplate hand = o.drive.empty() ? hand_template(o.hand, "hand check")
                                                   : hand_with_drive(o.hand, o.drive, "hand check");
  const grasp::HandCheck c = grasp::check_hand(hand);
  if (o.json) {
    nlohmann::json doc = check_json(c);
    add_envelope(doc);
    std::cout << doc.dump(2) << '\n';
  } else {
    print_text(c, o.hand);
  }
  *exit_code = c.complete() ? 0 : 1;
}

}  // namespace

Command add_hand_command(CLI::App& parent) {
  auto o = std::make_shared<HandCliOptions>();
  CLI::App* app = parent.add_subcommand(
      "hand", "A hand of your own: check a template hand, or a hand file with its drive");
  app->require_subcommand(1);
  CLI::App* check = app->add_subcommand(
      "check", "Say what a template (or a hand file with --drive) lacks, and how to add it");
  check
      ->add_option("HAND", o->hand,
                   "A template scene (its HAND.pairs.json beside it), a built-in template's "
                   "name (project, robotiq, shadow, allegro), or with --drive a hand file")
      ->required();
  check->add_option("--drive", o->drive,
                    "HAND is a hand file (a Menagerie-style MJCF of the hand alone) and this its "
                    "drive (JSON: \"mount\" and \"grasp\"; docs/hands.md)");
  check->add_flag("--json", o->json, "Print one JSON document instead of text");
  check->footer(wrap_help(
      "Checks, in the order a run meets them: the drive file (with --drive: its \"mount\" and "
      "\"grasp\", then the scene graspcd writes around the hand); the template contract "
      "(docs/design.md, 'Object scenes': <mujoco>, no <keyframe>, a <body name=\"object\"> in "
      "<worldbody> with a free joint and one mesh geom, that geom's <mesh> asset, a non-zero "
      "gravity); the pair config beside it (found, its fields, its \"grasp\" section, or the "
      "project's hand without one); then, with a 2 cm cube placed as 'grasp --object' places a "
      "mesh, that the scene loads in MuJoCo, that every pair pattern selects collidable geoms "
      "of a served type and one pair serves the object, that the \"grasp\" section's bodies, "
      "actuators and touch patterns exist, and that the object collides with its support.\n"
      "Output: per missing piece two lines, 'missing: FILE[:LINE]: what' and '  add: how'; "
      "'note: ...' for optional pieces (graspcd_support, graspcd_fit); last 'HAND: N pieces "
      "missing' or 'HAND: complete (...)' with the grasp command to try. --json: one document "
      "(scene, pairs, complete, missing: [{file, line, what, how}], notes, summary). Exit code "
      "0 complete, 1 pieces missing, 2 a file that cannot be read (not XML, missing) or a hand "
      "file MuJoCo cannot load.\n"
      "Examples:\n"
      "  graspcd hand check mjcf/real_allegro_brick.xml\n"
      "  graspcd hand check ../shared/models/hands/wonik_allegro/scene_right.xml\n"
      "  graspcd hand check ../shared/models/hands/wonik_allegro/right_hand.xml --drive "
      "mjcf/allegro_right_hand.drive.json"));
  auto exit_code = std::make_shared<int>(0);
  return Command{app, [o, exit_code] { run_hand_check(*o, exit_code.get()); }, exit_code};
}

}  // namespace graspcd::cli
