// Figures 13-15 of the paper (section 10): SAT, the perceptron (cap 10,000, the paper's box hand)
// and Neuro-SAT (switch 300) replay the box hand's segments B and C against the object's boxes:
// time and perceptron passes per grasp step, and Novikoff's bound on the perceptron's updates from
// the exact gap of each box pair.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "graspcd/study/experiment.h"
#include "graspcd/study/recording.h"
#include "graspcd/study/study_options.h"

namespace graspcd::study {

// Replays the box hand's recording `o.repeats` times with each of the three methods, timed per
// grasp step and segment kind, every answer checked against CGAL's.
nlohmann::json run_box_hand(const StudyOptions& o, const Recording& rec, const Log& log);

// box_hand.csv: one row per (method, segment, grasp step).
std::string box_csv(const nlohmann::json& box);

}  // namespace graspcd::study
