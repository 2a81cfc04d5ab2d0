// SIGINT and SIGTERM during `vkray bench`: instead of ending the process at once, which would lose
// every figure measured so far, the signal asks the run to stop at its next step; the runner then
// saves the finished scenes as an incomplete report (bench_runner.h) and fails. A second signal
// ends the process as the default action does, removing any output being written.
#pragma once

namespace vkray::bench {

// Catches SIGINT and SIGTERM while it lives; restores the previous handlers when it ends.
class StopOnSignals {
public:
    StopOnSignals();
    ~StopOnSignals();
    StopOnSignals(const StopOnSignals&) = delete;
    StopOnSignals& operator=(const StopOnSignals&) = delete;
};

// Throws vkray::Error "interrupted by SIGTERM" once such a signal was caught; the runner calls it
// between steps.
void throwIfStopRequested();

}  // namespace vkray::bench
