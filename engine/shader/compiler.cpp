#include <facet/shader/compiler.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <set>

#include <facet/core/hash.h>
#include <facet/core/log.h>
#include "shader/glslang_frontend.h"

namespace facet {

namespace {

// On-disk entry: a small header so a truncated or foreign file is recognised and
// recompiled instead of reaching the driver. An entry is served only when its length is
// exactly the header's word count and the words hash to the header's checksum; anything
// else (a writer killed halfway, a full disk, another program's file) is one warning, a
// compile, and a rewrite. Entries appear by rename, so a reader never sees one growing;
// a writer killed outright leaves at most "KEY.spv.partial-PID-N" beside them.
struct DiskHeader {
    char magic[4] = {'F', 'S', 'P', 'V'};
    uint32_t word_count = 0;
    uint64_t key = 0;
    uint64_t words_hash = 0;
};

uint64_t hash_words(const std::vector<uint32_t>& words) {
    return Hash64().add(words.data(), words.size() * sizeof(uint32_t)).value();
}

std::string disk_path(const std::string& dir, uint64_t key) {
    Hash64 h;
    h.state = key;
    return dir + "/" + h.hex() + ".spv";
}

std::optional<std::vector<uint32_t>> read_disk(const std::string& path, uint64_t key) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    DiskHeader header;
    std::vector<uint32_t> words;
    if (in.read(reinterpret_cast<char*>(&header), sizeof header) && std::string(header.magic, 4) == "FSPV" &&
        header.key == key && header.word_count > 0 && header.word_count < (64u << 20)) {
        words.resize(header.word_count);
        if (in.read(reinterpret_cast<char*>(words.data()), words.size() * 4) && in.peek() == EOF &&
            hash_words(words) == header.words_hash && words[0] == 0x07230203u)
            return words;
    }
    log(LogLevel::warning, path + ": shader cache entry is damaged; compiling again");
    return std::nullopt;
}

void write_disk(const std::string& dir, uint64_t key, const std::vector<uint32_t>& words) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    const std::string path = disk_path(dir, key);
    // Unique per process and call, so concurrent writers of one key never share a file.
    static std::atomic<uint32_t> counter{0};
    const std::string temp = path + ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    DiskHeader header;
    header.word_count = static_cast<uint32_t>(words.size());
    header.key = key;
    header.words_hash = hash_words(words);
    {
        std::ofstream out(temp, std::ios::binary);
        out.write(reinterpret_cast<const char*>(&header), sizeof header);
        out.write(reinterpret_cast<const char*>(words.data()), words.size() * 4);
        out.close();  // the last bytes reach the file here, and may fail here (disk full)
        if (!out) {
            std::filesystem::remove(temp, ec);
            static std::atomic<bool> warned{false};
            if (!warned.exchange(true))
                log(LogLevel::warning, dir + ": cannot write to the shader cache; shaders are compiled on every run");
            return;
        }
    }
    std::filesystem::rename(temp, path, ec);
    if (ec) std::filesystem::remove(temp, ec);
}

// Keeps the cache directory within `max_bytes` (ShaderCompilerOptions::disk_cache_max_bytes):
// the oldest entries by modification time (reads refresh it) go first, down to 3/4 of the
// bound so that a full cache is not scanned at every compile. Another process may remove or
// add entries meanwhile: every failure here is ignored (a missing entry is compiled again).
void bound_disk_cache(const std::string& dir, uint64_t max_bytes) {
    if (max_bytes == 0) return;
    namespace fs = std::filesystem;
    struct Entry {
        fs::path path;
        fs::file_time_type time;
        uint64_t bytes;
    };
    std::vector<Entry> entries;
    uint64_t total = 0;
    std::error_code ec;
    const auto now = fs::file_time_type::clock::now();
    for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
        std::error_code e;
        if (!it->is_regular_file(e)) continue;
        const std::string name = it->path().filename().string();
        const auto time = it->last_write_time(e);
        if (e) continue;
        if (name.find(".spv.partial-") != std::string::npos) {
            if (now - time > std::chrono::hours(1)) fs::remove(it->path(), e);  // a killed writer's
            continue;
        }
        if (name.size() != 20 || name.substr(16) != ".spv") continue;  // only our entries
        const uint64_t bytes = it->file_size(e);
        if (e) continue;
        entries.push_back({it->path(), time, bytes});
        total += bytes;
    }
    if (total <= max_bytes) return;
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.time < b.time; });
    size_t removed = 0;
    for (const Entry& e : entries) {
        if (total <= max_bytes / 4 * 3) break;
        std::error_code rc;
        if (fs::remove(e.path, rc)) ++removed;
        total -= e.bytes;
    }
    log(LogLevel::debug, dir + ": shader cache over " + std::to_string(max_bytes >> 10) + " KiB: removed " +
                             std::to_string(removed) + " least recently used entries");
}

Result<Spirv> with_reflection(std::vector<uint32_t> words, uint64_t key, std::string_view name) {
    auto reflection = reflect_spirv(words, name);
    if (!reflection) return reflection.error();
    return Spirv{std::move(words), key, std::move(reflection).value()};
}

// The `#include` lines of `text` (#include "x" or <x>, spaces allowed around the #).
template <typename F>
void for_each_include(std::string_view text, F&& visit) {
    auto skip_space = [&](size_t i, size_t end) {
        while (i < end && (text[i] == ' ' || text[i] == '\t')) ++i;
        return i;
    };
    for (size_t pos = 0; pos < text.size();) {
        size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        size_t i = skip_space(pos, end);
        pos = end + 1;
        if (i >= end || text[i] != '#') continue;
        i = skip_space(i + 1, end);
        if (text.compare(i, 7, "include") != 0) continue;
        i = skip_space(i + 7, end);
        if (i >= end || (text[i] != '"' && text[i] != '<')) continue;
        const char close = text[i] == '"' ? '"' : '>';
        const size_t stop = text.find(close, i + 1);
        if (stop == std::string_view::npos || stop > end) continue;
        visit(text.substr(i + 1, stop - i - 1), close == '"');
    }
}

// Every file a source may read, each once, by name and text: what its #include lines
// name, followed through the library as glslang's includer does. Lines in comments and
// inactive branches count too, so the key may change when the SPIR-V would not, never
// the other way round. Costs no glslang: a cache hit never starts it (its built-in
// declarations alone take ~60 ms to parse on a first preprocess).
void add_sources(const ShaderLibrary& library, std::string_view name, std::string_view text, Hash64& hash,
                 std::set<std::string>& seen) {
    for_each_include(text, [&](std::string_view header, bool local) {
        auto found = library.find_include(header, name, local);
        if (!found) {
            hash.add("missing ").add(header);  // glslang reports it when it compiles
            return;
        }
        if (!seen.insert(found->name).second) return;
        const uint64_t size = found->text.size();
        hash.add(found->name).add(&size, sizeof size).add(found->text);
        add_sources(library, found->name, found->text, hash, seen);
    });
}

}  // namespace

namespace {

// What every sharing compiler of the process has compiled (ShaderCompilerOptions::
// share_in_process). The keys hash the sources with their includes, the defines, the stage
// and the toolchain, so any compiler's entry serves any other.
struct ProcessCache {
    std::mutex mutex;
    std::map<uint64_t, std::vector<uint32_t>> entries;
    size_t bytes = 0;
};
constexpr size_t kProcessCacheBytes = 32u << 20;

ProcessCache& process_cache() {
    static ProcessCache cache;
    return cache;
}

std::optional<std::vector<uint32_t>> process_cache_find(uint64_t key) {
    ProcessCache& cache = process_cache();
    std::lock_guard lock(cache.mutex);
    auto it = cache.entries.find(key);
    if (it == cache.entries.end()) return std::nullopt;
    return it->second;
}

void process_cache_add(uint64_t key, const std::vector<uint32_t>& words) {
    ProcessCache& cache = process_cache();
    std::lock_guard lock(cache.mutex);
    const size_t bytes = words.size() * sizeof(uint32_t);
    if (cache.entries.count(key)) return;
    if (cache.bytes + bytes > kProcessCacheBytes) {  // far more variants than a scene needs: start again
        cache.entries.clear();
        cache.bytes = 0;
    }
    cache.entries.emplace(key, words);
    cache.bytes += bytes;
}

}  // namespace

const char* stage_name(ShaderStage stage) {
    switch (stage) {
        case ShaderStage::vertex: return "vertex";
        case ShaderStage::fragment: return "fragment";
        case ShaderStage::compute: return "compute";
    }
    return "?";
}

ShaderCompiler::ShaderCompiler(ShaderCompilerOptions options)
    : options_(std::move(options)), library_(options_.source_dir) {}

Result<Spirv> ShaderCompiler::compile(ShaderStage stage, std::string_view name,
                                      std::span<const ShaderDefine> defines) {
    auto text = library_.load(name);
    if (!text)
        return Error{std::string(name) + ": no such shader (looked in " +
                     (library_.source_dir().empty() ? "" : library_.source_dir() + " and ") +
                     "the embedded shaders/)"};
    return compile_source(stage, name, *text, defines);
}

Result<Spirv> ShaderCompiler::compile_source(ShaderStage stage, std::string_view name, std::string_view text,
                                             std::span<const ShaderDefine> defines) {
    glslang_frontend::Input input{stage, std::string(name), std::string(text), {}, options_.debug_info};
    for (const ShaderDefine& d : defines) input.preamble += "#define " + d.name + " " + d.value + "\n";

    Hash64 sources;
    const uint64_t size = text.size();
    sources.add(name).add(&size, sizeof size).add(text);
    std::set<std::string> seen;
    add_sources(library_, name, text, sources, seen);
    const uint64_t key = sources.add(input.preamble)
                             .add(stage_name(stage))
                             .add(options_.debug_info ? "debug" : "release")
                             .add(glslang_frontend::toolchain_tag())
                             .add("facet " FACET_VERSION)  // another Facet may compile the same text otherwise
                             .value();
    {
        std::lock_guard lock(mutex_);
        if (auto it = memory_cache_.find(key); it != memory_cache_.end()) {
            ++stats_.memory_hits;
            return with_reflection(it->second, key, name);
        }
    }
    // Then what another compiler of the process made (no file read), then the disk.
    if (options_.share_in_process)
        if (auto words = process_cache_find(key)) {
            std::lock_guard lock(mutex_);
            ++stats_.process_hits;
            memory_cache_[key] = *words;
            return with_reflection(std::move(*words), key, name);
        }
    if (!options_.disk_cache_dir.empty()) {
        const std::string path = disk_path(options_.disk_cache_dir, key);
        if (auto words = read_disk(path, key)) {
            // Used now: the cache's bound removes the least recently used entries first.
            std::error_code ec;
            std::filesystem::last_write_time(path, std::filesystem::file_time_type::clock::now(), ec);
            if (options_.share_in_process) process_cache_add(key, *words);
            std::lock_guard lock(mutex_);
            ++stats_.disk_hits;
            memory_cache_[key] = *words;
            log(LogLevel::debug, std::string(name) + ": " + stage_name(stage) + " shader read from the shader cache");
            return with_reflection(std::move(*words), key, name);
        }
    }
    const auto start = std::chrono::steady_clock::now();
    auto words = glslang_frontend::compile(library_, input);
    if (!words) return words.error();
    // At FACET_LOG=debug one line per glslang compile: the programs' tests count them (a
    // warm cache compiles nothing).
    char took[32];
    std::snprintf(took, sizeof took, "%.1f ms",
                  std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    log(LogLevel::debug, std::string(name) + ": " + stage_name(stage) + " shader compiled by glslang in " + took);
    if (!options_.disk_cache_dir.empty()) {
        write_disk(options_.disk_cache_dir, key, *words);
        bound_disk_cache(options_.disk_cache_dir, options_.disk_cache_max_bytes);
    }
    if (options_.share_in_process) process_cache_add(key, *words);
    std::lock_guard lock(mutex_);
    ++stats_.compiles;
    memory_cache_[key] = *words;
    return with_reflection(std::move(words).value(), key, name);
}

ShaderCompiler::Stats ShaderCompiler::stats() const {
    std::lock_guard lock(mutex_);
    return stats_;
}

}  // namespace facet
