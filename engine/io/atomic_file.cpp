#include <facet/io/atomic_file.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace facet {

namespace fs = std::filesystem;

std::string temporary_path(const std::string& path, const char* kind) {
    const fs::path target(path);
    // Built with += : GCC 12 warns falsely on "literal" + std::string (PR 105651).
    std::string name = ".";
    name += target.stem().string();
    name += ".";
    name += kind;
    name += "-";
    name += std::to_string(::getpid());
    name += target.extension().string();
    return (target.parent_path() / name).string();
}

Status write_atomically(const std::string& path, const std::function<Status(const std::string&)>& write) {
    const fs::path target(path);
    const fs::path temp(temporary_path(path));
    auto discard = [&] {
        std::error_code ignored;
        fs::remove(temp, ignored);
    };
    Status status = Ok{};
    try {
        status = write(temp.string());
    } catch (...) {
        discard();
        throw;
    }
    if (!status) {
        discard();
        return status;
    }
    std::error_code ec;
    fs::rename(temp, target, ec);
    if (ec) {
        discard();
        return Error{path + ": cannot move the finished file into place: " + ec.message()};
    }
    return Ok{};
}

Status write_binary_file(const std::string& path, std::span<const uint8_t> bytes) {
    return write_atomically(path, [&](const std::string& temp) -> Status {
        std::ofstream out(temp, std::ios::binary);
        if (!out) return Error{path + ": cannot open for writing: " + std::error_code(errno, std::generic_category()).message()};
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        out.close();
        if (!out) return Error{path + ": write failed (disk full?)"};
        return Ok{};
    });
}

Status write_text_file(const std::string& path, const std::string& text) {
    return write_binary_file(path, {reinterpret_cast<const uint8_t*>(text.data()), text.size()});
}

Status ensure_directory(const std::string& dir) {
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
        return Error{dir + ": exists and is not a directory"};
    fs::create_directories(dir, ec);
    if (ec) return Error{dir + ": cannot create the directory: " + ec.message()};
    if (::access(dir.c_str(), W_OK) != 0) return Error{dir + ": the directory is not writable"};
    return Ok{};
}

}  // namespace facet
