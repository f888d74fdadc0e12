#pragma once
// The glslang call behind ShaderCompiler: compilation to SPIR-V, with glslang's log turned into `file:line: error:` messages.
#include <string>
#include <string_view>
#include <vector>

#include <facet/core/result.h>
#include <facet/shader/compiler.h>
#include <facet/shader/shader_library.h>

namespace facet::glslang_frontend {

struct Input {
    ShaderStage stage;
    std::string name;
    std::string text;
    std::string preamble;  // #defines
    bool debug_info = false;
};

// What else decides the SPIR-V for a given source: the glslang version and the targets.
// Part of every cache key, so an upgrade or a new target never serves old entries.
const std::string& toolchain_tag();

Result<std::vector<uint32_t>> compile(const ShaderLibrary& library, const Input& input);

// glslang's info log as `file:line: error: message` lines, each followed by the source
// line it points at (found through the library, or `main_text` for the main file).
std::string format_log(std::string_view log, const ShaderLibrary& library, const std::string& main_name,
                       const std::string& main_text);

}  // namespace facet::glslang_frontend
