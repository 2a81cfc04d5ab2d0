#include "core/temp_files.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>

namespace vkray::temp_files {
namespace {

// Fixed storage: the handler may run at any instruction, so it reads only these slots, each guarded
// by a lock-free atomic state (async-signal-safe, unlike any lock or allocation). A slot is filled
// while Filling and read by the handler only once it has claimed it, Live to Removing: other threads
// run on while one handles the signal, and a slot freed and filled again under the handler's read
// would give it a path made of two. A Removing slot is never freed (the process is ending).
// Outputs are written a few at a time, so a few dozen slots are plenty; a path longer than
// kPathBytes goes untracked.
constexpr int kSlots = 64;
constexpr size_t kPathBytes = 4096;
enum State : int { Free, Filling, Live, Removing };

struct Slot {
    std::atomic<int> state{Free};
    char path[kPathBytes];
};
Slot g_slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

void removeTrackedAndReraise(int sig) {
    const int savedErrno = errno;
    for (Slot& slot : g_slots) {
        int live = Live;
        if (slot.state.compare_exchange_strong(live, Removing, std::memory_order_acquire)) ::unlink(slot.path);
    }
    // Back to the default action and raised again: the signal is blocked while its handler runs, so
    // it is delivered as soon as the handler returns and ends the process as if never caught.
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    ::sigaction(sig, &dfl, nullptr);
    ::raise(sig);
    errno = savedErrno;
}

}  // namespace

void installInterruptCleanup() {
    struct sigaction ours {};
    ours.sa_handler = removeTrackedAndReraise;
    sigemptyset(&ours.sa_mask);
    for (int sig : kSignals) sigaddset(&ours.sa_mask, sig);  // one cleanup at a time
    for (int sig : kSignals) {
        struct sigaction current {};
        if (::sigaction(sig, nullptr, &current) != 0) continue;
        const bool isDefault = !(current.sa_flags & SA_SIGINFO) && current.sa_handler == SIG_DFL;
        if (isDefault) ::sigaction(sig, &ours, nullptr);
    }
}

int track(const char* absolutePath) {
    installInterruptCleanup();
    const size_t length = std::strlen(absolutePath);
    if (length >= kPathBytes) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = Free;
        if (!g_slots[i].state.compare_exchange_strong(expected, Filling, std::memory_order_acquire)) continue;
        std::memcpy(g_slots[i].path, absolutePath, length + 1);
        g_slots[i].state.store(Live, std::memory_order_release);
        return i;
    }
    return -1;
}

void untrack(int slot) {
    if (slot < 0 || slot >= kSlots) return;
    int live = Live;  // not Removing: the handler is reading its path
    g_slots[slot].state.compare_exchange_strong(live, Free, std::memory_order_release, std::memory_order_relaxed);
}

}  // namespace vkray::temp_files
