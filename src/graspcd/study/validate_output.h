// The output of `graspcd validate` (its --help says what each field means): a validation
// report (validate.h) as text and as a JSON document without its envelope.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "graspcd/study/validate.h"

namespace graspcd::study {

// A header line, one row per method and pair, each method's totals and first disagreements,
// then the contacts and the result.
std::string validation_text(const ValidationReport& report);

nlohmann::json validation_json(const ValidationReport& report);

}  // namespace graspcd::study
