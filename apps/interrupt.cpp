#include "interrupt.h"

#include <pthread.h>
#include <signal.h>
#include <time.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <facet/io/output_set.h>

namespace facet {

namespace {

std::atomic<int> g_signal{0};
// While a commit renames files, a second signal (on another thread: this one blocks them)
// is parked here and raised when the renames are done.
std::atomic<bool> g_committing{false};
std::atomic<int> g_deferred{0};
const char* g_program = "facet";

static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "the handler may only touch lock-free atomics");

// signal() and raise() are async-signal-safe.
void die_by(int sig) {
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

extern "C" void on_signal(int sig) {
    int none = 0;
    if (g_signal.compare_exchange_strong(none, sig)) return;
    // A second signal: the user insists.
    if (g_committing.load()) {
        g_deferred.store(sig);
        // Still committing: the commit raises it at its end (commit_outputs). Otherwise the
        // commit ended between the two loads and may have missed the store.
        if (g_committing.load()) return;
    }
    die_by(sig);
}

sigset_t interrupt_signals() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    return set;
}

// SIGINT and SIGTERM blocked on this thread (sigprocmask; pthread_sigmask is its name in
// a process with threads, which lavapipe starts) and a second signal elsewhere deferred.
class CommitSection {
public:
    CommitSection() {
        const sigset_t set = interrupt_signals();
        pthread_sigmask(SIG_BLOCK, &set, &saved_);
        g_committing.store(true);
    }
    ~CommitSection() {
        g_committing.store(false);
        if (int sig = g_deferred.exchange(0)) die_by(sig);
        // A signal that arrived meanwhile is delivered here: the first is recorded, a
        // second kills.
        pthread_sigmask(SIG_SETMASK, &saved_, nullptr);
    }
    CommitSection(const CommitSection&) = delete;
    CommitSection& operator=(const CommitSection&) = delete;

private:
    sigset_t saved_;
};

}  // namespace

void install_interrupt_handlers(const char* program) {
    g_program = program;
    struct sigaction action {};
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    // Restarted system calls: a signal must not turn a file write into an EINTR failure.
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

int interrupt_signal() { return g_signal.load(); }

void check_interrupt() {
    if (int sig = g_signal.load()) throw Interrupted{sig};
}

const char* signal_name(int signal) {
    switch (signal) {
        case SIGINT: return "SIGINT";
        case SIGTERM: return "SIGTERM";
        default: return "a signal";
    }
}

Status commit_outputs(OutputSet& outputs) {
    pause_for_test("commit");
    CommitSection section;
    check_interrupt();
    return outputs.commit();
}

void pause_for_test(const char* point) {
    static const std::string wanted = [] {
        const char* env = std::getenv("FACET_TEST_PAUSE_AT");
        return env ? "," + std::string(env) + "," : std::string();
    }();
    if (wanted.find("," + std::string(point) + ",") == std::string::npos) return;
    std::fprintf(stderr, "%s: test hook: paused at %s\n", g_program, point);
    // "stopping" already had its signal and waits for a second one, which kills.
    const bool stopping = std::strcmp(point, "stopping") == 0;
    for (int i = 0; i < 6000 && (stopping || interrupt_signal() == 0); ++i) {
        const timespec ten_ms{0, 10'000'000};
        nanosleep(&ten_ms, nullptr);
    }
}

int report_interrupted(const Interrupted& interrupted, const char* consequence) {
    std::fprintf(stderr, "%s: interrupted by %s; %s\n", g_program, signal_name(interrupted.signal), consequence);
    pause_for_test("stopping");
    return 128 + interrupted.signal;
}

}  // namespace facet
