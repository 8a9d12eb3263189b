#include "graspcd/version/envelope.h"

#include "graspcd/version/provenance.h"

namespace graspcd {

nlohmann::json provenance_json() {
  const Provenance& p = provenance();
  return {{"version", p.version}, {"commit", p.commit}, {"dirty", p.dirty}};
}

nlohmann::json warnings_json(const std::vector<Warning>& list) {
  nlohmann::json out = nlohmann::json::array();
  for (const Warning& w : list) {
    out.push_back(
        {{"source", w.source}, {"code", w.code}, {"message", w.message}, {"count", w.count}});
  }
  return out;
}

void add_envelope(nlohmann::json& document) {
  document["graspcd"] = provenance_json();
  document["warnings"] = warnings_json(warnings().list());
}

}  // namespace graspcd
