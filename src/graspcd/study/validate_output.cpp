#include "graspcd/study/validate_output.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "graspcd/exact/exact.h"

namespace graspcd::study {

namespace {

using json = nlohmann::json;

std::string first_text(const PairRow& r) {
  if (!r.disagreed) return "-";
  return (r.first.phase == "closing" ? "" : r.first.phase + " ") + std::to_string(r.first.step);
}

// "the closing, 183 grasp steps, each after its last physics step" and the like for a phase.
std::string phase_text(const PhaseChecks& c) {
  if (c.phase == "closing") {
    return "the closing, " + std::to_string(c.states) +
           " grasp steps, each after its last physics step";
  }
  return (c.phase == "squeeze" ? std::string("the squeeze and its settling") : "the " + c.phase) +
         ", " + std::to_string(c.states) + " states, one every " + std::to_string(c.physics_steps) +
         " physics steps";
}

// The header line (and the decomposed scene's).
void text_header(std::ostream& out, const ValidationReport& report) {
  out << "# graspcd validate " << report.scene << " (pairs " << report.config
      << "): " << report.steps << " closing grasp steps of the grasp driven by "
      << report.grasp_method << (report.gripped ? " (gripped)" : " (not gripped)")
      << "; truth: CGAL " << exact::cgal_version()
      << " on the same triangles or boxes in the same poses\n";
  out << "# checked: ";
  std::vector<std::string> unchecked = {"the closing", "the squeeze", "the lift", "the hold"};
  for (const PhaseChecks& c : report.phases) {
    out << phase_text(c) << "; ";
    unchecked.erase(std::find(unchecked.begin(), unchecked.end(), "the " + c.phase));
  }
  out << (report.cut_short
              ? "--max-steps " + std::to_string(report.max_steps) +
                    " cut the closing short (the hand had not finished closing)"
              : "the closing ended before --max-steps " + std::to_string(report.max_steps));
  for (std::size_t i = 0; i < unchecked.size(); ++i) {
    out << (i == 0 ? "; " : i + 1 == unchecked.size() ? " and " : ", ") << unchecked[i];
  }
  if (!unchecked.empty()) {
    out << (unchecked.size() == 1 ? " is" : " are")
        << " not checked (--phases all checks every phase)";
  }
  out << '\n';
  if (report.decomposed.pieces > 0) {
    out << "# decomposed: the grasp ran natively with " << report.decomposed.replaced_geoms
        << " geom(s) of " << report.decomposed.source << " colliding as "
        << report.decomposed.pieces << " convex pieces each (" << report.decomposed_dir
        << "); the pairs are checked on the true meshes\n";
  }
}

// One row per method and pair.
void pair_table(std::ostream& out, const ValidationReport& report) {
  std::size_t width = 4;
  for (const MethodTable& t : report.methods) {
    for (const PairRow& r : t.rows) width = std::max(width, r.pair.size());
  }
  out << std::left << std::setw(17) << "method" << std::setw(static_cast<int>(width) + 2) << "pair"
      << std::setw(7) << "path" << std::right << std::setw(6) << "steps" << std::setw(7) << "agree"
      << std::setw(7) << "truth" << std::setw(8) << "missed" << std::setw(7) << "false"
      << std::setw(11) << "tri_missed" << std::setw(10) << "tri_false" << std::setw(20)
      << "first_disagreement" << '\n';
  for (const MethodTable& t : report.methods) {
    for (const PairRow& r : t.rows) {
      out << std::left << std::setw(17) << t.method << std::setw(static_cast<int>(width) + 2)
          << r.pair << std::setw(7) << (r.box_box ? "boxes" : "trees") << std::right << std::setw(6)
          << r.steps << std::setw(7) << r.agree << std::setw(7) << r.truth_hits << std::setw(8)
          << r.missed << std::setw(7) << r.false_contacts << std::setw(11) << r.missed_tri_pairs
          << std::setw(10) << r.false_tri_pairs << std::setw(20) << first_text(r) << '\n';
    }
  }
}

// Per method: its totals and each pair's first disagreement.
void method_summaries(std::ostream& out, const ValidationReport& report) {
  for (const MethodTable& t : report.methods) {
    int checks = 0, agree = 0, missed = 0, false_contacts = 0;
    for (const PairRow& r : t.rows) {
      checks += r.steps;
      agree += r.agree;
      missed += r.missed;
      false_contacts += r.false_contacts;
    }
    out << "# " << t.method << ": " << checks << " checks, " << agree << " agree, " << missed
        << " missed, " << false_contacts << " false; " << std::fixed << std::setprecision(3)
        << t.seconds << " s of queries\n";
    for (const PairRow& r : t.rows) {
      if (!r.disagreed) continue;
      out << "# first disagreement of " << t.method << " on " << r.pair << ": "
          << (r.first.phase == "closing" ? "step " : r.first.phase + " physics step ")
          << r.first.step << ", CGAL " << (r.first.truth ? "intersect" : "disjoint");
      if (!r.box_box) out << " (" << r.first.truth_pairs << " triangle pairs)";
      out << ", " << t.method << ' ' << (r.first.answer ? "intersect" : "disjoint");
      if (!r.box_box) out << " (" << r.first.answer_pairs << " triangle pairs)";
      out << '\n';
      if (!r.first.command.empty()) {
        out << "#   reproduce: " << r.first.command << "   (add --exact for CGAL's answer)\n";
      } else {
        out << "#   add --out DIR to write the two meshes and the command that reproduces it\n";
      }
    }
  }
}

// A (method, pair) row.
json pair_json(const PairRow& r) {
  json row = {{"pair", r.pair},
              {"geom1", r.geom1},
              {"geom2", r.geom2},
              {"path", r.box_box ? "boxes" : "trees"},
              {"steps", r.steps},
              {"agree", r.agree},
              {"truth_hits", r.truth_hits},
              {"missed", r.missed},
              {"false_contacts", r.false_contacts},
              {"pair_mismatch", r.pair_mismatch},
              {"missed_tri_pairs", r.missed_tri_pairs},
              {"false_tri_pairs", r.false_tri_pairs},
              {"first_disagreement", nullptr}};
  if (r.disagreed) {
    row["first_disagreement"] = {{"phase", r.first.phase},
                                 {"step", r.first.step},
                                 {"truth", r.first.truth},
                                 {"answer", r.first.answer},
                                 {"truth_pairs", r.first.truth_pairs},
                                 {"answer_pairs", r.first.answer_pairs},
                                 {"files", r.first.files},
                                 {"command", r.first.command}};
  }
  return row;
}

}  // namespace

std::string validation_text(const ValidationReport& report) {
  std::ostringstream out;
  text_header(out, report);
  pair_table(out, report);
  method_summaries(out, report);
  out << "# contacts: ";
  for (std::size_t i = 0; i < report.phases.size(); ++i) {
    const PhaseChecks& c = report.phases[i];
    out << (i == 0 ? "" : ", ") << c.with_contact << " of " << c.states
        << (c.phase == "closing" ? " closing grasp steps" : " " + c.phase + " states");
  }
  out << " had a contact to check\n";
  out << "# result: " << (report.missed_any() ? "MISSED COLLISIONS" : "no missed collision")
      << (report.states_with_contact() == 0 ? " (nothing touched: nothing was checked)" : "")
      << "; CGAL " << std::fixed << std::setprecision(2) << report.exact_seconds
      << " s, the methods " << report.tester_seconds << " s\n";
  if (report.nonfinite_skips > 0) {
    out << "# non-finite skips: " << report.nonfinite_skips
        << " pair checks on a placement with NaN, inf or a number beyond 1e10 (not checked)\n";
  }
  return out.str();
}

json validation_json(const ValidationReport& report) {
  json methods = json::array();
  for (const MethodTable& t : report.methods) {
    json rows = json::array();
    for (const PairRow& r : t.rows) rows.push_back(pair_json(r));
    methods.push_back({{"method", t.method},
                       {"missed_any", t.missed_any()},
                       {"seconds", t.seconds},
                       {"pairs", rows}});
  }
  json phase_names = json::array();
  json checks = json::array();
  for (const PhaseChecks& c : report.phases) {
    phase_names.push_back(c.phase);
    checks.push_back({{"phase", c.phase},
                      {"states", c.states},
                      {"with_contact", c.with_contact},
                      {"physics_steps", c.physics_steps}});
  }
  json doc = {{"scene", report.scene},
              {"config", report.config},
              {"grasp_method", report.grasp_method},
              {"steps", report.steps},
              {"steps_with_contact", report.steps_with_contact},
              {"phases", phase_names},
              {"checks", checks},
              {"max_steps", report.max_steps},
              {"cut_short", report.cut_short},
              {"gripped", report.gripped},
              {"cgal", exact::cgal_version()},
              {"exact_seconds", report.exact_seconds},
              {"tester_seconds", report.tester_seconds},
              {"nonfinite_skips", report.nonfinite_skips},
              {"missed_any", report.missed_any()},
              {"methods", methods},
              {"decomposed", nullptr}};
  if (report.decomposed.pieces > 0) {
    doc["decomposed"] = {{"dir", report.decomposed_dir},
                         {"source", report.decomposed.source},
                         {"pieces", report.decomposed.pieces},
                         {"geoms", report.decomposed.replaced_geoms}};
  }
  return doc;
}

}  // namespace graspcd::study
