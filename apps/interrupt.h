#pragma once
// SIGINT and SIGTERM in the programs. The handler only records the signal (one atomic
// store: async-signal-safe); the work looks at it at safe points (between graph passes,
// between reference batches, in the accuracy budget's brute-force sums, between output
// files) and unwinds with Interrupted, so every owner cleans up on the way out: GPU
// objects are destroyed in order, temporaries removed (io/output_set.h). The program then
// prints "PROGRAM: interrupted by SIGINT; no output written" and exits 128 + the signal
// (130 for SIGINT, 143 for SIGTERM). A second signal while it stops restores the default
// action and re-raises it, so a user can always kill a program that is slow to stop.
#include <exception>
#include <functional>

#include "cli.h"
#include <facet/core/result.h>

namespace facet {

class OutputSet;

// Thrown at a safe point after a signal. Deliberately not a std::exception: no handler of
// ordinary errors mistakes it for one.
struct Interrupted {
    int signal = 0;
};

// Installs the handlers (SIGINT, SIGTERM); `program` prefixes the messages.
void install_interrupt_handlers(const char* program);
// The signal received (SIGINT or SIGTERM), or 0.
int interrupt_signal();
// A safe point: throws Interrupted once a signal arrived.
void check_interrupt();
const char* signal_name(int signal);

// Moves `outputs` into place as the run's last step: the final safe point, then the renames
// with SIGINT and SIGTERM blocked (sigprocmask), so a signal cannot split the set; one
// that arrives meanwhile is taken after the commit (the run has then finished: exit 0).
// A second signal from another thread during the renames waits for their end as well.
Status commit_outputs(OutputSet& outputs);

// Test hook (documented in README.md): with FACET_TEST_PAUSE_AT=NAME[,NAME...] in the
// environment the program prints "PROGRAM: test hook: paused at NAME" when it reaches the
// point NAME and waits there (up to 60 s) for a signal, so a test can interrupt it at
// exactly that point. Points: "shaders" (facet-bake, between its first shaders and the
// bake's), "bake" (facet-bake, after the first pass), "reference" (facet-render, after the
// first batch), "commit" (every temporary written, none moved yet), and "stopping" (an
// interruption has cleaned up; waits the whole time, for a second signal).
void pause_for_test(const char* point);

// Prints the message for an interruption and returns the exit status (128 + signal).
int report_interrupted(const Interrupted& interrupted, const char* consequence = "no output written");

// cli::run_program with the handlers installed and an interruption reported.
template <class Parse, class Run>
int run_interruptible(const char* program, Parse parse, Run run) {
    install_interrupt_handlers(program);
    return cli::run_program(program, parse, [&](const auto& options) -> int {
        try {
            return run(options);
        } catch (const Interrupted& interrupted) {
            return report_interrupted(interrupted);
        }
    });
}

}  // namespace facet
