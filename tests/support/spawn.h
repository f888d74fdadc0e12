#pragma once
// A program started in the background for tests that signal it at a chosen moment:
// posix_spawn with stdout and stderr on one pipe, read as the program writes, so a test
// can wait for a line of progress and then send SIGINT or SIGTERM.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace facet::test {

class Spawned {
public:
    // `env` entries ("NAME=value") are added to this process's environment.
    explicit Spawned(const std::vector<std::string>& argv, const std::vector<std::string>& env = {}) {
        int fds[2];
        if (::pipe2(fds, O_CLOEXEC) != 0) return;
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
        posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
        std::vector<std::string> environment(env);
        for (char** e = environ; *e; ++e) environment.push_back(*e);
        std::vector<char*> args, envp;
        for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        for (const std::string& e : environment) envp.push_back(const_cast<char*>(e.c_str()));
        args.push_back(nullptr);
        envp.push_back(nullptr);
        if (posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), envp.data()) != 0) pid_ = -1;
        posix_spawn_file_actions_destroy(&actions);
        ::close(fds[1]);
        out_ = fds[0];
    }
    ~Spawned() {
        if (running()) {
            ::kill(pid_, SIGKILL);
            int raw;
            ::waitpid(pid_, &raw, 0);
        }
        if (out_ >= 0) ::close(out_);
    }
    Spawned(const Spawned&) = delete;
    Spawned& operator=(const Spawned&) = delete;

    bool started() const { return pid_ > 0; }
    const std::string& output() const { return output_; }

    // Reads until `text` has appeared in the output; false when the program closed its
    // output or the time ran out first.
    bool wait_for(const std::string& text, double timeout_s = 60) {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (output_.find(text) == std::string::npos) {
            const auto left = std::chrono::duration<double, std::milli>(end - std::chrono::steady_clock::now());
            if (left.count() <= 0 || !read_some(int(left.count()) + 1)) return output_.find(text) != std::string::npos;
        }
        return true;
    }

    void signal(int sig) const {
        if (running()) ::kill(pid_, sig);
    }

    struct Ended {
        bool exited = false;  // exited normally, with `status`
        int status = -1;
        int signal = 0;       // else: the signal that ended it (0: still running after the timeout)
    };
    // Reads the rest of the output and reaps the program; SIGKILL after `timeout_s`.
    Ended wait(double timeout_s = 60) {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (std::chrono::steady_clock::now() < end && read_some(100)) {
        }
        Ended e;
        if (!running()) return ended_;
        int raw = 0;
        while (std::chrono::steady_clock::now() < end) {
            if (::waitpid(pid_, &raw, WNOHANG) == pid_) {
                reaped_ = true;
                e.exited = WIFEXITED(raw);
                e.status = e.exited ? WEXITSTATUS(raw) : -1;
                e.signal = WIFSIGNALED(raw) ? WTERMSIG(raw) : 0;
                ended_ = e;
                return e;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return e;  // still running: the destructor kills it
    }

private:
    bool running() const { return pid_ > 0 && !reaped_; }
    // One read of at most what is there; false at the end of the output.
    bool read_some(int timeout_ms) {
        if (out_ < 0) return false;
        pollfd p{out_, POLLIN, 0};
        if (::poll(&p, 1, timeout_ms) <= 0) return true;  // nothing yet (or EINTR)
        char buf[4096];
        const ssize_t n = ::read(out_, buf, sizeof buf);
        if (n <= 0) return false;
        output_.append(buf, size_t(n));
        return true;
    }

    pid_t pid_ = -1;
    int out_ = -1;
    bool reaped_ = false;
    Ended ended_;
    std::string output_;
};

}  // namespace facet::test
