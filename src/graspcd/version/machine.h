// The machine a measurement ran on and the build that measured it, as the study records them
// beside its timings (study.json's "machine" and "build"), and the time of day it was written.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace graspcd {

// {"cpu", "cores", "memory", "kernel", "os"} of this machine: the first "model name" of
// /proc/cpuinfo, the hardware threads, MemTotal of /proc/meminfo, uname(2), and PRETTY_NAME of
// os-release(5) ("unknown" for what cannot be read).
nlohmann::json machine_info();

// {"graspcd", "build_type", "compiler", "flags", "mujoco", "eigen", "cgal"} of this build.
nlohmann::json build_info();

// The current time in UTC, ISO 8601 to the second ("2026-01-31T12:00:00Z").
std::string now_utc();

}  // namespace graspcd
