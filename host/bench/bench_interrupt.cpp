// bench_interrupt.h: the handler only records the signal (async-signal-safe); the run polls it.
#include "bench/bench_interrupt.h"

#include <csignal>
#include <string>

#include "core/error.h"

namespace vkray::bench {
namespace {

volatile std::sig_atomic_t caught = 0;
struct sigaction previousInt, previousTerm;

extern "C" void recordSignal(int sig) { caught = sig; }

}  // namespace

StopOnSignals::StopOnSignals() {
    caught = 0;
    struct sigaction action {};
    action.sa_handler = recordSignal;
    sigemptyset(&action.sa_mask);
    // SA_RESETHAND: the first signal is recorded, a second one gets the default action.
    action.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &action, &previousInt);
    sigaction(SIGTERM, &action, &previousTerm);
}

StopOnSignals::~StopOnSignals() {
    sigaction(SIGINT, &previousInt, nullptr);
    sigaction(SIGTERM, &previousTerm, nullptr);
}

void throwIfStopRequested() {
    const int sig = caught;
    if (sig == 0) return;
    throw Error(std::string("interrupted by ") + (sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal"));
}

}  // namespace vkray::bench
