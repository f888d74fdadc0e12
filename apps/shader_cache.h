#pragma once
// --shader-cache DIR for facet-bake and facet-render: the shader compiler's on-disk SPIR-V
// cache (shader/compiler.h), so a later run skips glslang. FACET_SHADER_CACHE is the
// default; with neither, there is no cache. An entry is used only when it is whole and
// matches its key (length and content checksum); a damaged one (a killed writer, a full
// disk) is reported as a warning, compiled again and rewritten.
#include <string>

#include "cli.h"

namespace facet {

void add_shader_cache_option(cli::Parser& parser);
// The cache directory chosen by --shader-cache or FACET_SHADER_CACHE; empty: none.
std::string shader_cache_dir(const cli::Parsed& parsed);

// FACET_SHADER_DIR: read shaders from this directory instead of the embedded copies
// (the library reads no environment variable; ShaderCompilerOptions::source_dir).
// Empty: unset.
std::string shader_dir_from_environment();

}  // namespace facet
