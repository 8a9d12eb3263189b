#include "graspcd/grasp/grasp_output.h"

#include <iomanip>
#include <sstream>

#include "graspcd/grasp/verdicts.h"

namespace graspcd::grasp {

namespace {

using json = nlohmann::json;

std::string segments_text(const GraspResult& g, const GraspStepRecord& r) {
  std::string out;
  for (std::size_t s = 0; s < r.touching.size(); ++s) {
    if (!r.touching[s]) continue;
    if (!out.empty()) out += ',';
    out += g.segments[s];
  }
  return out.empty() ? "-" : out;
}

// "# object FILE at scale S (given|fitted) ... in the HAND template": the first line of the text.
std::string object_line(const ObjectRunDescription& o) {
  std::ostringstream out;
  out << "# object " << o.file << " at scale " << std::setprecision(6) << o.scene.scale
      << (o.scene.fitted ? " (fitted)" : " (given)") << ", " << std::setprecision(3)
      << o.scene.size[0] << " x " << o.scene.size[1] << " x " << o.scene.size[2] << " m, in the "
      << o.hand << " template";
  if (o.scene.support_raised > 0) {
    out << ", on its support raised " << std::setprecision(3) << 1000 * o.scene.support_raised
        << " mm to the hand's reach";
  }
  return out.str();
}

// The true meshes' penetration (true_penetration.h) as a phrase of the verdict line: "true
// meshes: deepest penetration 0.412 mm (geom 'left_pad', hand, grasp step 57, t = 0.570 s, in the
// closing), hand 0.412 mm, support 0.101 mm, over 640 grasp steps; partial: ...; not measured:
// ...".
std::string true_penetration_text(const TruePenetration& p) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << "true meshes: deepest penetration " << p.max * 1e3
      << " mm";
  if (p.step > 0) {
    out << " (" << p.geom << ", " << p.side << ", grasp step " << p.step << ", t = " << p.time
        << " s, in " << p.phase << ")";
  }
  out << ", hand " << p.hand_max * 1e3 << " mm, support " << p.support_max * 1e3 << " mm, over "
      << p.measures << " grasp steps (" << p.pairs << " geom pairs)";
  for (const std::string& line : p.partial) out << "; partial: " << line;
  for (const std::string& line : p.unmeasured) out << "; not measured: " << line;
  return out.str();
}

// "steps": one object per closing grasp step.
json steps_json(const GraspResult& r) {
  json steps = json::array();
  for (const GraspStepRecord& s : r.steps) {
    json segments = json::array();
    for (std::size_t i = 0; i < s.touching.size(); ++i) {
      if (s.touching[i]) segments.push_back(r.segments[i]);
    }
    steps.push_back({{"step", s.step},
                     {"contacts", s.contacts},
                     {"detection_ns", s.detection_ns},
                     {"box_tests", s.box_tests},
                     {"front_skips", s.front_skips},
                     {"triangle_tests", s.triangle_tests},
                     {"served_calls", s.served_calls},
                     {"contained", s.contained},
                     {"nonfinite_skips", s.nonfinite_skips},
                     {"object_z", s.object_z},
                     {"segments", segments}});
  }
  return steps;
}

// "first_contact": segment -> grasp step, or null.
json first_contact_json(const GraspResult& r) {
  json first = json::object();
  for (std::size_t i = 0; i < r.first_contact.size(); ++i) {
    first[r.segments[i]] = r.first_contact[i] > 0 ? json(r.first_contact[i]) : json();
  }
  return first;
}

// `value` when the deepest penetration was found at some step, else null.
template <typename T>
json when_found(const TruePenetration& p, const T& value) {
  return p.step > 0 ? json(value) : json();
}

json true_penetration_json(const TruePenetration& p) {
  return {{"max", p.max},
          {"step", when_found(p, p.step)},
          {"time", when_found(p, p.time)},
          {"phase", when_found(p, p.phase)},
          {"geom", when_found(p, p.geom)},
          {"side", when_found(p, p.side)},
          {"hand_max", p.hand_max},
          {"support_max", p.support_max},
          {"measures", p.measures},
          {"pairs", p.pairs},
          {"probe_spacing", kTrueProbeSpacing},
          {"partial", p.partial},
          {"unmeasured", p.unmeasured}};
}

// The run's cost and MuJoCo's side of it.
json run_json(const GraspResult& r) {
  return {{"noslip_iterations", r.noslip_iterations},
          {"multiccd", r.multiccd},
          {"detection_ns_close", r.detection_ns_close},
          {"detection_ns_total", r.detection_ns_total},
          {"physics_steps", r.physics_steps},
          {"sim_time", r.sim_time},
          {"timestep", r.timestep},
          {"physics_steps_per_grasp_step", r.physics_steps_per_grasp_step},
          {"ms_per_physics_step", r.step_wall_ms},
          {"cpu_ms_per_physics_step", r.step_cpu_ms},
          {"max_contacts", r.max_contacts},
          {"mean_contacts", r.mean_contacts},
          {"max_pair_contacts", r.max_pair_contacts},
          {"rest",
           {{"max_speed", r.rest_max_speed},
            {"max_penetration", r.rest_max_penetration},
            {"energy_early", r.rest_energy_early},
            {"energy_late", r.rest_energy_late}}},
          {"contact_buffer_full", r.contact_buffer_full},
          {"constraint_buffer_full", r.constraint_buffer_full},
          {"contained_calls", r.contained_calls},
          {"nonfinite_skips", r.nonfinite_skips},
          {"reused_calls", r.reused_calls}};
}

json object_json(const ObjectRunDescription& object) {
  const ObjectScene& o = object.scene;
  return {{"file", object.file},
          {"hand", object.hand},
          {"scale", o.scale},
          {"fitted", o.fitted},
          {"size", o.size},
          {"pos", o.pos},
          {"quat", o.quat},
          {"support_raised", o.support_raised},
          {"scene", object.kept ? json(o.scene) : json()}};
}

}  // namespace

nlohmann::json cost_json(const GraspCost& cost) {
  const auto part = [](const PartTime& t) {
    return json{{"cpu_s", t.cpu_s}, {"wall_s", t.wall_s}};
  };
  json parts = json::object();
  for (std::size_t i = 0; i < kCostParts; ++i) parts[kCostPartKeys[i]] = part(cost.parts[i]);
  const PartTime total = cost.total();
  return {{"cpu_s", total.cpu_s},
          {"wall_s", total.wall_s},
          {"before_first_step", part(cost.before_first_step())},
          {"parts", parts}};
}

std::string cost_text(const GraspCost& cost) {
  const PartTime total = cost.total();
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << "# cost " << total.cpu_s << " s CPU ("
      << total.wall_s << " s wall):";
  const char* separator = " ";
  for (std::size_t i = 0; i < kCostParts; ++i) {
    if (cost.parts[i].cpu_s <= 0 && cost.parts[i].wall_s <= 0) continue;
    std::string name = kCostPartKeys[i];
    for (char& c : name) c = c == '_' ? ' ' : c;
    out << separator << name << ' ' << cost.parts[i].cpu_s;
    separator = ", ";
  }
  out << " s CPU; " << cost.before_first_step().cpu_s << " s CPU before the first physics step\n";
  return out.str();
}

json verdict_json(const GraspResult& r) {
  json directions = json::array();
  int passed = 0;
  for (const DirectionResult& d : r.directions) {
    directions.push_back({{"direction", d.name},
                          {"touching", d.touching},
                          {"moved", d.moved},
                          {"passed", d.passed}});
    passed += d.passed ? 1 : 0;
  }
  json doc = {{"gripped", r.gripped},
              {"held", r.held},
              {"outcome", r.outcome},
              {"reason", r.reason.empty() ? json() : json(r.reason)},
              {"evidence", r.evidence},
              {"notes", r.notes},
              {"closing", r.closing},
              {"touching_at_lift", r.touching_at_lift},
              {"object_rise", r.object_rise},
              {"hand_travel", r.hand_travel},
              {"slip_time", r.slip_time >= 0 ? json(r.slip_time) : json()},
              {"pushed", r.squeeze_push},
              {"pushed_during_squeeze", r.pushed_during_squeeze},
              {"tilt_before_lift_deg", r.tilt_before_lift_deg},
              {"pushed_over", r.pushed_over},
              {"release_time", r.release_time >= 0 ? json(r.release_time) : json()},
              {"dropped_at", r.dropped_at ? json(*r.dropped_at) : json()},
              {"drop", r.drop.empty() ? json() : json(r.drop)},
              {"fell", r.fell ? json{{"t", r.fell->time}, {"speed", r.fell->speed}} : json()},
              {"object_z_initial", r.object_z_initial},
              {"object_z_gripped", r.object_z_gripped},
              {"object_z_final", r.object_z_final},
              {"lowest_z", r.lowest_z},
              {"hold_min_z", r.hold_min_z},
              {"hold_drift", r.hold_drift},
              {"grip_rise", r.grip_rise},
              {"tilt_deg", r.tilt_deg},
              {"tilt_final_deg", r.tilt_final_deg},
              {"max_speed", r.max_speed},
              {"kinetic_energy_max", r.kinetic_energy_max},
              {"ejected", r.ejected ? json{{"t", r.ejected->time},
                                           {"speed", r.ejected->speed},
                                           {"cause", r.ejected->cause},
                                           {"limit", r.ejected->limit}}
                                    : json()},
              {"support_warning", r.support_warning.empty() ? json() : json(r.support_warning)},
              {"true_penetration_max", r.true_penetration.max},
              {"true_penetration_step", when_found(r.true_penetration, r.true_penetration.step)},
              {"true_penetration", true_penetration_json(r.true_penetration)}};
  doc["six_directions"] =
      r.directions.empty()
          ? json()
          : json{{"held", passed}, {"of", r.directions.size()}, {"directions", directions}};
  return doc;
}

std::string verdict_text(const GraspResult& r) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(4) << "# gripped " << (r.gripped ? "yes" : "no")
      << "; held " << (r.held ? "yes" : "no");
  for (const std::string& note : r.notes) out << ", " << note;
  out << ": " << (r.held ? std::string("carried") : r.reason) << " (" << r.evidence
      << "); object z (origin) " << r.object_z_initial << " -> " << r.object_z_gripped
      << " (before the lift) -> " << r.object_z_final << " m (final), rose " << r.object_rise
      << " m of the hand's " << r.hand_travel << " m, lowest " << r.hold_min_z << " m and drift "
      << r.hold_drift << " m in the hold; grip point rose " << r.grip_rise << " m; tilt "
      << r.tilt_final_deg << " deg final, " << r.tilt_deg << " deg largest, "
      << r.tilt_before_lift_deg << " deg before the lift; fastest " << r.max_speed
      << " m/s, kinetic energy at most " << std::setprecision(6) << r.kinetic_energy_max << " J; "
      << true_penetration_text(r.true_penetration) << '\n';
  if (!r.directions.empty()) {
    int passed = 0;
    std::string lost;
    for (const DirectionResult& d : r.directions) {
      if (d.passed) {
        ++passed;
        continue;
      }
      std::ostringstream why;
      why << std::fixed << std::setprecision(1) << d.name << " (moved " << 100 * d.moved << " cm"
          << (d.touching ? "" : ", not touching") << ")";
      lost += (lost.empty() ? "" : ", ") + why.str();
    }
    out << "# six directions: held in " << passed << " of " << r.directions.size() << " directions"
        << (lost.empty() ? "" : "; lost " + lost) << '\n';
  }
  return out.str();
}

std::string grasp_text(const GraspResult& r, const ObjectRunDescription* object,
                       const DecomposedScene* decomposed, bool quiet) {
  std::ostringstream out;
  if (object) out << object_line(*object) << '\n';
  out << std::fixed;
  if (!quiet) {
    out << "step contacts detection_ns box_tests triangle_tests object_z segments\n";
    for (const GraspStepRecord& s : r.steps) {
      out << s.step << ' ' << s.contacts << ' ' << s.detection_ns << ' ' << s.box_tests << ' '
          << s.triangle_tests << ' ' << std::setprecision(6) << s.object_z << ' '
          << segments_text(r, s) << '\n';
    }
  }
  out << "# method " << r.method << "; first contact (grasp step):";
  for (std::size_t s = 0; s < r.first_contact.size(); ++s) {
    out << ' ' << r.segments[s] << '=';
    if (r.first_contact[s] > 0) {
      out << r.first_contact[s];
    } else {
      out << '-';
    }
  }
  out << '\n';
  out << verdict_text(r);
  out << "# detection ns " << r.detection_ns_close << " closing, " << r.detection_ns_total
      << " total; " << r.physics_steps << " physics steps, " << std::setprecision(2) << r.sim_time
      << " s simulated, " << std::setprecision(4) << r.step_wall_ms << " ms per physics step; "
      << r.contained_calls << " containment findings; " << r.nonfinite_skips
      << " non-finite skips; " << r.reused_calls << " reused; noslip " << r.noslip_iterations
      << " iterations; multiccd " << (r.multiccd ? "on" : "off") << '\n';
  if (decomposed) {
    out << "# decomposed: " << decomposed->replaced_geoms << " geom(s) of " << decomposed->source
        << " collide as " << decomposed->pieces << " convex pieces each (native)\n";
  }
  return out.str();
}

json grasp_json(const GraspResult& r, const ObjectRunDescription* object,
                const DecomposedScene* decomposed, const std::string& decomposed_dir) {
  json doc = {{"scene", r.scene},
              {"method", r.method},
              {"native", r.native},
              {"steps", steps_json(r)},
              {"first_contact", first_contact_json(r)}};
  doc.update(verdict_json(r));
  doc.update(run_json(r));
  doc["cost"] = cost_json(r.cost);
  if (object) doc["object"] = object_json(*object);
  if (decomposed) {
    doc["decomposed"] = {{"dir", decomposed_dir},
                         {"source", decomposed->source},
                         {"pieces", decomposed->pieces},
                         {"geoms", decomposed->replaced_geoms}};
  }
  return doc;
}

}  // namespace graspcd::grasp
