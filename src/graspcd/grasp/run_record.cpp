#include "graspcd/grasp/run_record.h"

#include <cmath>
#include <cstdio>
#include <utility>

#include "graspcd/grasp/six_directions.h"
#include "graspcd/io/input_error.h"

namespace graspcd::grasp {

namespace {

using json = nlohmann::json;

// The record's phases in order: start, close, squeeze, settle, lift, hold, the six directions.
constexpr int kHoldOrder = 5;
constexpr int kPhaseCount = 12;

// The phase of order k.
std::pair<RunPhase, int> phase_of_order(int k) {
  if (k > kHoldOrder) return {RunPhase::kDirection, k - kHoldOrder - 1};
  return {static_cast<RunPhase>(k), -1};
}

std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

json six_directions_json() {
  return {{"duration", kSixDirectionsDuration},
          {"distance", kSixDirectionsDistance},
          {"frame", "hand"}};
}

}  // namespace

RunRecordWriter::RunRecordWriter(const std::string& path, const RunHeader& header,
                                 std::vector<int> geom_ids)
    : header_(header), geom_ids_(std::move(geom_ids)), file_(path) {
  out_.open(file_.write_path(), std::ios::binary | std::ios::trunc);
  if (!out_) throw io::InputError(path, 0, "cannot write the run record");
  json h = {{"format", kRunRecordFormat},
            {"version", kRunRecordVersion},
            {"scene", header.scene},
            {"simulator", header.simulator},
            {"configuration", header.configuration},
            {"timestep", header.timestep},
            {"nq", header.nq},
            {"nv", header.nv},
            {"object", header.object},
            {"hand", header.hand},
            {"support", header.support},
            {"contacts", header.contacts},
            {"inflation", header.inflation},
            {"max_steps", header.max_steps}};
  if (header.noslip_iterations) h["noslip_iterations"] = *header.noslip_iterations;
  if (header.multiccd) h["multiccd"] = *header.multiccd;
  if (header.six_directions) h["six_directions"] = six_directions_json();
  line(h.dump());
}

RunRecordWriter::~RunRecordWriter() = default;

void RunRecordWriter::line(const std::string& text) { out_ << text << '\n'; }

void RunRecordWriter::start(const mjModel* m, const mjData* d) {
  line(json{{"t", d->time},
            {"phase", "start"},
            {"qpos", std::vector<double>(d->qpos, d->qpos + m->nq)},
            {"qvel", std::vector<double>(d->qvel, d->qvel + m->nv)}}
           .dump());
}

void RunRecordWriter::step(const mjModel* m, const mjData* d, RunPhase phase, int grasp_step,
                           int direction, int object) {
  json j = {{"t", d->time}, {"phase", phase_record_name(phase, direction)}};
  if (phase == RunPhase::kClose) j["grasp_step"] = grasp_step;
  j["qpos"] = std::vector<double>(d->qpos, d->qpos + m->nq);
  j["qvel"] = std::vector<double>(d->qvel, d->qvel + m->nv);
  if (header_.contacts) {
    const int root = m->body_rootid[object];
    const auto id = [this](int g) {
      return geom_ids_.empty() ? g : geom_ids_[static_cast<std::size_t>(g)];
    };
    const auto side = [&](int g) {
      const char* body = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[g]);
      return json{{"body", body != nullptr ? body : ""}, {"geom", id(g)}};
    };
    json contacts = json::array();
    for (int i = 0; i < d->ncon; ++i) {
      const mjContact& c = d->contact[i];
      if (m->body_rootid[m->geom_bodyid[c.geom1]] != root &&
          m->body_rootid[m->geom_bodyid[c.geom2]] != root) {
        continue;
      }
      contacts.push_back({{"a", side(c.geom1)},
                          {"b", side(c.geom2)},
                          {"pos", {c.pos[0], c.pos[1], c.pos[2]}},
                          {"normal", {c.frame[0], c.frame[1], c.frame[2]}},
                          {"dist", c.dist}});
    }
    j["contacts"] = std::move(contacts);
  }
  line(j.dump());
}

void RunRecordWriter::end(const RunEnd& end) {
  if (ended_) return;
  ended_ = true;
  json e = {{"status", end.status}};
  if (!end.closing.empty()) e["closing"] = end.closing;
  if (!end.message.empty()) e["message"] = end.message;
  line(json{{"end", e}}.dump());
  out_.close();
  if (!out_) throw io::InputError(file_.write_path(), 0, "cannot write the run record");
  file_.commit();
}

RunRecordReader::RunRecordReader(const std::string& path, const mjModel* m,
                                 const std::string& object, const std::string& hand,
                                 const std::string& support)
    : path_(path), in_(path, std::ios::binary), m_(m) {
  if (!in_) throw io::InputError(path, 0, "cannot open the run record");
  std::string text;
  if (!std::getline(in_, text)) refuse("empty: no header");
  line_ = 1;
  json h;
  try {
    h = json::parse(text);
  } catch (const json::parse_error& e) {
    refuse(std::string("bad JSON: ") + e.what());
  }
  if (!h.is_object()) refuse("the header is not a JSON object");
  check_finite(h);
  const json& format = key(h, "format");
  if (!format.is_string() || format.get<std::string>() != kRunRecordFormat) {
    refuse(std::string("\"format\" is not \"") + kRunRecordFormat + "\"");
  }
  const json& version = key(h, "version");
  if (!version.is_number_integer() || version.get<long>() != kRunRecordVersion) {
    refuse("\"version\" " + version.dump() + " is not " + std::to_string(kRunRecordVersion));
  }
  const auto text_of = [&](const char* name) {
    const json& v = key(h, name);
    if (!v.is_string()) refuse(std::string("\"") + name + "\" is not a string");
    return v.get<std::string>();
  };
  const auto integer = [&](const char* name) {
    const json& v = key(h, name);
    if (!v.is_number_integer()) refuse(std::string("\"") + name + "\" is not an integer");
    return v.get<long>();
  };
  header_.scene = text_of("scene");
  header_.simulator = text_of("simulator");
  header_.configuration = text_of("configuration");
  header_.timestep = number(h, "timestep");
  if (header_.timestep <= 0) refuse("\"timestep\" is not positive");
  const long nq = integer("nq");
  const long nv = integer("nv");
  if (nq != m->nq || nv != m->nv) {
    refuse("nq = " + std::to_string(nq) + ", nv = " + std::to_string(nv) +
           "; the scene has nq = " + std::to_string(m->nq) + ", nv = " + std::to_string(m->nv));
  }
  header_.nq = m->nq;
  header_.nv = m->nv;
  header_.object = text_of("object");
  header_.hand = text_of("hand");
  header_.support = text_of("support");
  const std::pair<const char*, const std::string*> bodies[] = {
      {"object", &object}, {"hand", &hand}, {"support", &support}};
  const std::string* named[] = {&header_.object, &header_.hand, &header_.support};
  for (std::size_t i = 0; i < 3; ++i) {
    body(*named[i], bodies[i].first);
    if (*named[i] != *bodies[i].second) {
      refuse(std::string("\"") + bodies[i].first + "\" is '" + *named[i] + "'; the scene's is '" +
             *bodies[i].second + "'");
    }
  }
  object_ = body(header_.object, "object");
  const json& contacts = key(h, "contacts");
  if (!contacts.is_boolean()) refuse("\"contacts\" is not true or false");
  header_.contacts = contacts.get<bool>();
  if (h.contains("inflation")) {
    header_.inflation = number(h, "inflation");
    if (header_.inflation < 0) refuse("\"inflation\" is negative");
  }
  if (h.contains("noslip_iterations")) {
    header_.noslip_iterations = static_cast<int>(integer("noslip_iterations"));
  }
  if (h.contains("multiccd")) {
    if (!h["multiccd"].is_boolean()) refuse("\"multiccd\" is not true or false");
    header_.multiccd = h["multiccd"].get<bool>();
  }
  header_.max_steps = static_cast<int>(integer("max_steps"));
  if (header_.max_steps < 1) refuse("\"max_steps\" is less than 1");
  if (h.contains("six_directions")) {
    const json& six = h["six_directions"];
    const json ours = six_directions_json();
    if (!six.is_object() || !six.contains("duration") || !six.contains("distance") ||
        !six.contains("frame") || six["duration"] != ours["duration"] ||
        six["distance"] != ours["distance"] || six["frame"] != ours["frame"]) {
      refuse("\"six_directions\" is " + six.dump() + "; the judge's is " + ours.dump());
    }
    header_.six_directions = true;
  }
  // A flex side (geom -1) is the object: its first geom with a surface.
  const int root = m->body_rootid[object_];
  for (int g = 0; g < m->ngeom && flex_geom_ < 0; ++g) {
    if (m->body_rootid[m->geom_bodyid[g]] == root &&
        (m->geom_type[g] == mjGEOM_MESH || m->geom_type[g] == mjGEOM_BOX ||
         m->geom_type[g] == mjGEOM_SPHERE || m->geom_type[g] == mjGEOM_CAPSULE ||
         m->geom_type[g] == mjGEOM_CYLINDER || m->geom_type[g] == mjGEOM_ELLIPSOID)) {
      flex_geom_ = g;
    }
  }
}

void RunRecordReader::refuse(const std::string& what) const {
  throw io::InputError(path_, static_cast<std::size_t>(line_), what);
}

void RunRecordReader::check_finite(const json& value) const {
  if (value.is_number_float() && !std::isfinite(value.get<double>())) {
    refuse("a number that is not finite");
  }
  if (value.is_structured()) {
    for (const json& v : value) check_finite(v);
  }
}

const json& RunRecordReader::key(const json& object, const char* name) const {
  const auto it = object.find(name);
  if (it == object.end()) refuse(std::string("no \"") + name + "\"");
  return *it;
}

double RunRecordReader::number(const json& object, const char* name) const {
  const json& v = key(object, name);
  if (!v.is_number()) refuse(std::string("\"") + name + "\" is not a number");
  return v.get<double>();
}

std::vector<double> RunRecordReader::numbers(const json& object, const char* name,
                                             std::size_t count) const {
  const json& v = key(object, name);
  if (!v.is_array()) refuse(std::string("\"") + name + "\" is not an array");
  if (v.size() != count) {
    const std::string n(name);
    refuse("\"" + n + "\" has " + std::to_string(v.size()) + " numbers; " +
           (n == "qpos"   ? "the scene has nq = "
            : n == "qvel" ? "the scene has nv = "
                          : "it needs ") +
           std::to_string(count));
  }
  std::vector<double> out;
  out.reserve(count);
  for (const json& x : v) {
    if (!x.is_number()) refuse(std::string("\"") + name + "\" holds something not a number");
    out.push_back(x.get<double>());
  }
  return out;
}

int RunRecordReader::body(const std::string& name, const char* what) const {
  const int id = name == "world" ? 0 : mj_name2id(m_, mjOBJ_BODY, name.c_str());
  if (id < 0) refuse(std::string(what) + " body '" + name + "': the scene has no such body");
  return id;
}

int RunRecordReader::side(const json& contact, const char* name) const {
  const json& s = key(contact, name);
  if (!s.is_object()) refuse(std::string("a contact's \"") + name + "\" is not an object");
  const json& b = key(s, "body");
  if (!b.is_string()) refuse(std::string("a contact's \"") + name + "\" body is not a string");
  const std::string body_name = b.get<std::string>();
  const int id = body(body_name, "a contact's");
  const json& g = key(s, "geom");
  if (!g.is_number_integer())
    refuse(std::string("a contact's \"") + name + "\" geom is not an integer");
  const long geom = g.get<long>();
  if (geom == -1) {
    if (flex_geom_ < 0) refuse("a contact's geom -1 (a flex), but the object has no geom");
    if (m_->body_rootid[id] != m_->body_rootid[object_]) {
      refuse("a contact's geom -1 (a flex) on body '" + body_name + "', which is not the object");
    }
    return flex_geom_;
  }
  if (geom < 0 || geom >= m_->ngeom) {
    refuse("a contact's geom " + std::to_string(geom) + " is out of range (the scene has " +
           std::to_string(m_->ngeom) + " geoms)");
  }
  if (m_->geom_bodyid[geom] != id) {
    refuse("a contact's geom " + std::to_string(geom) + " does not belong to body '" + body_name +
           "'");
  }
  return static_cast<int>(geom);
}

RecordContact RunRecordReader::contact(const json& value) const {
  if (!value.is_object()) refuse("a contact is not an object");
  RecordContact c;
  c.geom1 = side(value, "a");
  c.geom2 = side(value, "b");
  const std::vector<double> pos = numbers(value, "pos", 3);
  const std::vector<double> normal = numbers(value, "normal", 3);
  for (std::size_t k = 0; k < 3; ++k) {
    c.pos[k] = pos[k];
    c.normal[k] = normal[k];
  }
  c.dist = number(value, "dist");
  return c;
}

bool RunRecordReader::next(RecordState& out) {
  if (ended_) return false;
  std::string text;
  if (!std::getline(in_, text)) {
    ++line_;
    refuse("the record ends without its end line ({\"end\": ...}): the run was cut off");
  }
  ++line_;
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    refuse(std::string("bad JSON: ") + e.what());
  }
  if (!j.is_object()) refuse("not a JSON object");
  check_finite(j);
  if (j.contains("end")) {
    const json& e = j["end"];
    if (!e.is_object()) refuse("\"end\" is not an object");
    const json& status = key(e, "status");
    if (!status.is_string()) refuse("\"status\" is not a string");
    end_.status = status.get<std::string>();
    if (end_.status != "ok" && end_.status != "nonfinite" && end_.status != "cannot start") {
      refuse("\"status\" '" + end_.status + "' is none of ok, nonfinite, cannot start");
    }
    if (e.contains("closing") || end_.status == "ok") {
      const json& closing = key(e, "closing");
      if (!closing.is_string() ||
          (closing.get<std::string>() != "touched" && closing.get<std::string>() != "max_steps")) {
        refuse("\"closing\" is neither \"touched\" nor \"max_steps\"");
      }
      end_.closing = closing.get<std::string>();
    }
    if (e.contains("message") || end_.status == "cannot start") {
      const json& message = key(e, "message");
      if (!message.is_string()) refuse("\"message\" is not a string");
      end_.message = message.get<std::string>();
    }
    const int last = header_.six_directions ? kPhaseCount - 1 : kHoldOrder;
    if (end_.status == "ok" && order_ != last) {
      refuse("the run ended \"ok\" after phase '" +
             (order_ < 0 ? std::string("none")
                         : phase_record_name(phase_of_order(order_).first,
                                             phase_of_order(order_).second)) +
             "': it needs every phase to '" +
             phase_record_name(phase_of_order(last).first, phase_of_order(last).second) + "'");
    }
    ended_ = true;
    std::string rest;
    while (std::getline(in_, rest)) {
      ++line_;
      if (rest.find_first_not_of(" \t\r") != std::string::npos) refuse("a line after the end line");
    }
    return false;
  }
  out.line = line_;
  out.t = number(j, "t");
  const json& phase = key(j, "phase");
  if (!phase.is_string()) refuse("\"phase\" is not a string");
  const std::string name = phase.get<std::string>();
  int order = -1;
  for (int k = 0; k < kPhaseCount && order < 0; ++k) {
    const auto [p, dir] = phase_of_order(k);
    if (phase_record_name(p, dir) == name) order = k;
  }
  if (order < 0) refuse("phase '" + name + "' is not a phase of the record");
  if (order > kHoldOrder && !header_.six_directions) {
    refuse("phase '" + name + "' without \"six_directions\" in the header");
  }
  if (!started_ && order != 0) refuse("the first state is phase '" + name + "', not 'start'");
  if (started_ && (order < order_ || order > order_ + 1 || order == 0)) {
    refuse("phase '" + name + "' out of order after '" +
           phase_record_name(phase_of_order(order_).first, phase_of_order(order_).second) + "'");
  }
  std::tie(out.phase, out.direction) = phase_of_order(order);
  // Time: never back within a phase or from the start through the hold; a direction starts again
  // from the hold's end.
  if (order > kHoldOrder && order != order_) {
    if (order_ == kHoldOrder) hold_end_ = last_t_;
    if (out.t < hold_end_) {
      refuse("t = " + number_text(out.t) +
             " is before the hold's end (t = " + number_text(hold_end_) + ")");
    }
  } else if (started_ && out.t < last_t_) {
    refuse("time goes backwards: t = " + number_text(out.t) + " after t = " + number_text(last_t_));
  }
  out.grasp_step = 0;
  if (out.phase == RunPhase::kClose) {
    const json& step = key(j, "grasp_step");
    if (!step.is_number_integer()) refuse("\"grasp_step\" is not an integer");
    const long k = step.get<long>();
    const long expected_new = order_ == order ? grasp_step_ + 1 : 1;
    if (k != expected_new && !(order_ == order && k == grasp_step_)) {
      refuse("grasp step " + std::to_string(k) + " does not follow grasp step " +
             std::to_string(order_ == order ? grasp_step_ : 0));
    }
    grasp_step_ = static_cast<int>(k);
    out.grasp_step = grasp_step_;
  }
  out.qpos = numbers(j, "qpos", static_cast<std::size_t>(m_->nq));
  out.qvel = numbers(j, "qvel", static_cast<std::size_t>(m_->nv));
  out.contacts.clear();
  if (order > 0) {
    if (header_.contacts) {
      const json& contacts = key(j, "contacts");
      if (!contacts.is_array()) refuse("\"contacts\" is not an array");
      for (const json& c : contacts) out.contacts.push_back(contact(c));
    } else if (j.contains("contacts")) {
      refuse("\"contacts\" on a line, but the header says \"contacts\": false");
    }
  }
  order_ = order;
  last_t_ = out.t;
  started_ = true;
  return true;
}

}  // namespace graspcd::grasp
