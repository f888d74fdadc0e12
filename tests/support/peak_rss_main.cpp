// facet_peak_rss FILE COMMAND [ARGS...]: runs COMMAND, writes its peak resident memory in
// KiB (wait4's ru_maxrss) to FILE and exits with its status. The tests measure through
// this small process because a child's ru_maxrss starts from the memory of the process
// that forked it: forked from a test that has loaded OpenImageIO and large images, a
// program would seem to peak at the test's size.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: facet_peak_rss FILE COMMAND [ARGS...]\n");
        return 2;
    }
    const pid_t pid = fork();
    if (pid < 0) return 127;
    if (pid == 0) {
        execvp(argv[2], argv + 2);
        _exit(127);
    }
    int status = 0;
    rusage usage{};
    if (wait4(pid, &status, 0, &usage) != pid) return 127;
    if (FILE* f = std::fopen(argv[1], "w")) {
        std::fprintf(f, "%ld\n", usage.ru_maxrss);
        std::fclose(f);
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
