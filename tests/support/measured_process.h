#pragma once
// Running a program from a test and measuring it: exit status, output and the peak
// resident memory of the program (through the small facet_peak_rss helper, whose path
// the build passes as FACET_PEAK_RSS_PATH; see tests/support/peak_rss_main.cpp).
#include <unistd.h>

#include <fstream>
#include <string>

#include "support/process.h"

namespace facet::test {

struct Measured {
    int status = -1;       // exit status; -1 when the program did not exit normally
    std::string output;    // stdout and stderr together
    long peak_rss_kb = 0;  // the program's peak resident set size
    double peak_rss_mib() const { return peak_rss_kb / 1024.0; }
};

inline std::string shell_quoted(const std::string& text) {
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

inline Measured run_measured(const std::string& command) {
    static int calls = 0;
    const std::string peak_file = "/tmp/facet_peak_rss_" + std::to_string(::getpid()) + "_" + std::to_string(++calls);
    Ran ran = run_command(std::string(FACET_PEAK_RSS_PATH) + " " + peak_file + " sh -c " + shell_quoted(command));
    Measured m{ran.status, ran.output};
    std::ifstream(peak_file) >> m.peak_rss_kb;
    std::remove(peak_file.c_str());
    return m;
}

}  // namespace facet::test
