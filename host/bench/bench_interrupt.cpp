// bench_interrupt.h: the handler only records the signal (async-signal-safe); the run polls it.
#include "bench/bench_interrupt.h"

#include <csignal>
#include <string>

#include "core/error.h"
#include "core/temp_files.h"

namespace vkray::bench {
namespace {

volatile std::sig_atomic_t caught = 0;
struct sigaction previousInt, previousTerm;

// The first signal is recorded; a second one gets the handler from before the run (the output
// cleanup of core/temp_files.h, so an output being written is not left as a temporary), raised
// again once this handler returns (the signal is blocked while it runs). sigaction and raise are
// async-signal-safe.
extern "C" void recordSignal(int sig) {
    if (caught == 0) {
        caught = sig;
        return;
    }
    ::sigaction(SIGINT, &previousInt, nullptr);
    ::sigaction(SIGTERM, &previousTerm, nullptr);
    ::raise(sig);
}

}  // namespace

StopOnSignals::StopOnSignals() {
    temp_files::installInterruptCleanup();  // the handler a second signal gets
    caught = 0;
    struct sigaction action {};
    action.sa_handler = recordSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;
    // A signal the process ignores (nohup, a background job's SIGINT) stays ignored.
    sigaction(SIGINT, nullptr, &previousInt);
    sigaction(SIGTERM, nullptr, &previousTerm);
    if (previousInt.sa_handler != SIG_IGN) sigaction(SIGINT, &action, nullptr);
    if (previousTerm.sa_handler != SIG_IGN) sigaction(SIGTERM, &action, nullptr);
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
