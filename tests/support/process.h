#pragma once
// Running the programs from tests: exit status and everything they printed.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace facet::test {

struct Ran {
    int status = -1;     // exit status; -1 when the program did not exit normally
    std::string output;  // stdout and stderr together
};

inline Ran run_command(const std::string& command) {
    Ran r;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
    const int raw = pclose(pipe);
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return r;
}

}  // namespace facet::test
