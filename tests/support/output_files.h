#pragma once
// What interruption tests look at in a folder: every file with its bytes (hidden
// temporaries too), outputs compared with a run's timings left out, and the shader
// cache's entries checked against the format of engine/shader/compiler.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <facet/core/hash.h>

namespace facet::test {

namespace fs = std::filesystem;

inline std::string file_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

// Every file of `dir` (not in subfolders) -> its bytes; empty when `dir` does not exist.
inline std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> files;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (!it->is_directory()) files[it->path().filename().string()] = file_bytes(it->path());
    return files;
}

inline std::vector<std::string> names(const std::map<std::string, std::string>& files) {
    std::vector<std::string> out;
    for (const auto& [name, bytes] : files) out.push_back(name);
    return out;
}

// Hidden names: the temporaries of io/atomic_file.h (".NAME.partial-PID.EXT").
inline std::vector<std::string> temporaries_in(const fs::path& dir) {
    std::vector<std::string> out;
    for (const std::string& name : names(snapshot(dir)))
        if (name[0] == '.' || name.find(".partial-") != std::string::npos) out.push_back(name);
    return out;
}

// JSON without what differs between two equal runs: wall and GPU times.
inline std::string without_times(const std::string& json) {
    std::istringstream in(json);
    std::string line, out;
    int skipping = 0;  // depth inside a "gpu_time_ms": { ... } object
    while (std::getline(in, line)) {
        if (skipping) {
            if (line.find('{') != std::string::npos) ++skipping;
            if (line.find('}') != std::string::npos) --skipping;
            continue;
        }
        if (line.find("\"gpu_time_ms\": {") != std::string::npos) {
            skipping = 1;
            continue;
        }
        if (line.find("time_ms") == std::string::npos) out += line + "\n";
    }
    return out;
}

// Same files, byte for byte (JSON: but for times).
inline void expect_same_outputs(const fs::path& want_dir, const fs::path& got_dir) {
    const auto want = snapshot(want_dir), got = snapshot(got_dir);
    EXPECT_EQ(names(got), names(want)) << got_dir;
    for (const auto& [name, bytes] : want) {
        auto it = got.find(name);
        if (it == got.end()) continue;
        if (fs::path(name).extension() == ".json") EXPECT_EQ(without_times(it->second), without_times(bytes)) << name;
        else EXPECT_TRUE(it->second == bytes) << name << " differs from an uninterrupted run's";
    }
}

// Every entry of a shader cache whole and under its key's name: a 24-byte header
// ("FSPV", word count, key, FNV-1a of the words), exactly that many SPIR-V words.
inline ::testing::AssertionResult shader_cache_is_valid(const fs::path& dir, size_t* entries = nullptr) {
    size_t count = 0;
    for (const auto& [name, bytes] : snapshot(dir)) {
        if (fs::path(name).extension() != ".spv" || name.size() != 20)
            return ::testing::AssertionFailure() << dir << ": unexpected file " << name;
        struct Header {
            char magic[4];
            uint32_t word_count;
            uint64_t key, words_hash;
        } h;
        if (bytes.size() < sizeof h) return ::testing::AssertionFailure() << name << ": shorter than its header";
        std::memcpy(&h, bytes.data(), sizeof h);
        if (std::string(h.magic, 4) != "FSPV") return ::testing::AssertionFailure() << name << ": bad magic";
        if (bytes.size() != sizeof h + size_t(h.word_count) * 4)
            return ::testing::AssertionFailure() << name << ": " << bytes.size() << " bytes, the header says "
                                                 << sizeof h + size_t(h.word_count) * 4;
        Hash64 words, key;
        words.add(bytes.data() + sizeof h, bytes.size() - sizeof h);
        key.state = h.key;
        if (words.value() != h.words_hash) return ::testing::AssertionFailure() << name << ": checksum mismatch";
        if (key.hex() + ".spv" != name) return ::testing::AssertionFailure() << name << ": key " << key.hex();
        uint32_t spirv_magic = 0;
        std::memcpy(&spirv_magic, bytes.data() + sizeof h, 4);
        if (spirv_magic != 0x07230203u) return ::testing::AssertionFailure() << name << ": not SPIR-V";
        ++count;
    }
    if (entries) *entries = count;
    return ::testing::AssertionSuccess();
}

struct TempDir {
    fs::path path;
    explicit TempDir(const std::string& name)
        : path(fs::temp_directory_path() / ("facet_" + name + "_" + std::to_string(::getpid()))) {
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    fs::path operator/(const std::string& name) const { return path / name; }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

}  // namespace facet::test
