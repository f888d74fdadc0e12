#pragma once
// A private Xvfb server for one test process (xvfb-run's own clean-up races with quick
// programs and then exits 5). Started on a free display number, stopped on destruction.
#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>

namespace facet::test {

class Xvfb {
public:
    Xvfb() {
        for (int attempt = 0; attempt < 50 && display_.empty(); ++attempt) {
            const int n = 100 + int((::getpid() + attempt * 7919) % 800);
            if (std::filesystem::exists("/tmp/.X" + std::to_string(n) + "-lock")) continue;
            const std::string pid_file = "/tmp/facet-xvfb-" + std::to_string(::getpid()) + ".pid";
            const std::string command = "Xvfb :" + std::to_string(n) +
                                        " -screen 0 640x480x24 -nolisten tcp >/dev/null 2>&1 & echo $! > " + pid_file;
            if (std::system(command.c_str()) != 0) continue;
            FILE* f = std::fopen(pid_file.c_str(), "r");
            if (f) {
                if (std::fscanf(f, "%d", &pid_) != 1) pid_ = 0;
                std::fclose(f);
            }
            std::filesystem::remove(pid_file);
            // Ready when its socket exists (a few hundred ms at most).
            const std::string socket = "/tmp/.X11-unix/X" + std::to_string(n);
            for (int i = 0; i < 200 && !std::filesystem::exists(socket); ++i)
                std::this_thread::sleep_for(std::chrono::milliseconds(25));
            if (std::filesystem::exists(socket)) display_ = ":" + std::to_string(n);
            else stop();
        }
    }
    ~Xvfb() { stop(); }
    Xvfb(const Xvfb&) = delete;
    Xvfb& operator=(const Xvfb&) = delete;

    // "DISPLAY=:N " to put before a command; empty when no server could start.
    std::string env() const { return display_.empty() ? std::string() : "DISPLAY=" + display_ + " "; }
    bool running() const { return !display_.empty(); }

private:
    void stop() {
        if (pid_ > 0) {
            ::kill(pid_t(pid_), SIGTERM);
            pid_ = 0;
        }
    }
    int pid_ = 0;
    std::string display_;
};

}  // namespace facet::test
