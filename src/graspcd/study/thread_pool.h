// The study's replays in parallel: a fixed number of threads, each taking the next job when it is
// free. Each replay's clock measures its own thread's queries (replay.h), so the jobs run one per
// thread, never interleaved on one.
#pragma once

#include <cstddef>
#include <functional>

namespace graspcd::study {

// Runs job(i) for i in [0, count) on `workers` threads, each taking the next job when it is free,
// in the order given. The first exception a job throws is rethrown after every worker stopped.
void run_parallel(std::size_t count, int workers, const std::function<void(std::size_t)>& job);

}  // namespace graspcd::study
