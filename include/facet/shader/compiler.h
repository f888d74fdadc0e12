#pragma once
// GLSL -> SPIR-V at run time with the glslang library (Vulkan 1.3 client, SPIR-V 1.5 so
// that host devices without maintenance4 accept it), then SPIRV-Tools' performance passes
// (what the defines leave unreachable goes before a driver sees it; every binding,
// specialization constant and interface variable stays) unless debug_info is set.
// #include "x.glsl" resolves against the including file's folder, then shaders/;
// errors read `file:line: error: message` followed by the offending source line.
// Results are cached in memory (and optionally on disk) by a hash of the source, the
// files its #include lines name and the defines, so an edited include changes the key. Each result carries the shader's
// interface (bindings, push-constant size, workgroup size) read from its SPIR-V.
#include <cstdint>
#include <map>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <facet/core/result.h>
#include <facet/shader/reflection.h>
#include <facet/shader/shader_library.h>

namespace facet {

enum class ShaderStage { vertex, fragment, compute };

struct ShaderDefine {
    std::string name;
    std::string value;
};

struct Spirv {
    std::vector<uint32_t> words;
    uint64_t key = 0;             // cache key: sources (with includes) + defines + stage + options
    ShaderReflection reflection;  // what the pipeline running `words` must provide
};

struct ShaderCompilerOptions {
    std::string source_dir;      // empty: the embedded sources only
    std::string disk_cache_dir;  // empty: no on-disk cache
    // The on-disk cache's bound: after a compile adds an entry, the least recently used
    // entries (a read refreshes an entry's time) go until the cache holds at most 3/4 of
    // it, and writers' leftovers older than an hour (a killed process's .partial files)
    // go too. An entry is about 10-20 KiB; 0: no bound.
    uint64_t disk_cache_max_bytes = 64ull << 20;
    bool debug_info = false;     // keep debug information in the SPIR-V, unoptimised
    // Share results with every other compiler of the process that shares too (looked up after
    // this compiler's own memory, before its disk cache): a host's render sessions, each with its own
    // compiler and no cache directory, compile a shader once per process. At most 32 MiB,
    // emptied when full. Off only where a test counts one compiler's compiles.
    bool share_in_process = true;
};

class ShaderCompiler {
public:
    explicit ShaderCompiler(ShaderCompilerOptions options = {});

    // `name` is a path relative to shaders/, e.g. "ibl/procedural_sky.comp".
    Result<Spirv> compile(ShaderStage stage, std::string_view name,
                          std::span<const ShaderDefine> defines = {});
    // Source given as text; `name` is used in messages and for resolving #include.
    Result<Spirv> compile_source(ShaderStage stage, std::string_view name, std::string_view text,
                                 std::span<const ShaderDefine> defines = {});

    struct Stats {
        uint32_t memory_hits = 0, disk_hits = 0, process_hits = 0, compiles = 0;
    };
    Stats stats() const;
    const ShaderLibrary& library() const { return library_; }

private:
    ShaderCompilerOptions options_;
    ShaderLibrary library_;
    mutable std::mutex mutex_;
    std::map<uint64_t, std::vector<uint32_t>> memory_cache_;
    Stats stats_;
};

const char* stage_name(ShaderStage stage);

}  // namespace facet
