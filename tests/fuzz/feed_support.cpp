#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "feed.h"

namespace facet::fuzz {

namespace {

namespace fs = std::filesystem;

constexpr const char* kPrefix = "facet-fuzz-";

// Directories of earlier runs that crashed (libFuzzer leaves with _Exit, skipping atexit):
// removed once their process is gone, so that /dev/shm does not fill up over many runs.
void remove_stale_dirs(const fs::path& parent) {
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(parent, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(kPrefix, 0) != 0) continue;
        const std::string pid = name.substr(std::string(kPrefix).size());
        if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) continue;
        if (!fs::exists(fs::path("/proc") / pid, ec)) fs::remove_all(entry.path(), ec);
    }
}

std::string make_work_dir() {
    std::error_code ec;
    fs::path parent = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
    remove_stale_dirs(parent);
    fs::path dir = parent / (kPrefix + std::to_string(::getpid()));
    fs::create_directories(dir, ec);
    if (ec) {
        std::fprintf(stderr, "fuzz: cannot create %s: %s\n", dir.c_str(), ec.message().c_str());
        std::abort();
    }
    std::atexit([] {
        std::error_code ignored;
        fs::remove_all(work_dir(), ignored);
    });
    return dir.string();
}

}  // namespace

const std::string& work_dir() {
    // Never destroyed: the atexit handler above runs after static destructors would.
    static const std::string& dir = *new std::string(make_work_dir());
    return dir;
}

std::string write_input(Bytes input, const std::string& name) {
    const std::string path = (fs::path(work_dir()) / name).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(input.data()), std::streamsize(input.size()));
    out.close();
    if (!out) {
        std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
        std::abort();
    }
    return path;
}

void expect_names_file(const Error& error, const std::string& path) {
    const std::string prefix = path + ": ";
    FACET_FUZZ_EXPECT(error.message.rfind(prefix, 0) == 0 && error.message.size() > prefix.size(),
                      "the error does not name the file and a reason: '" + error.message + "'");
}

}  // namespace facet::fuzz
