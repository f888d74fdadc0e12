#pragma once
// The programs' on-disk SPIR-V cache (shader/compiler.h): on by default, so that a later
// run skips glslang. --shader-cache DIR chooses the directory, --no-shader-cache turns it
// off (both: a usage error); without either, FACET_SHADER_CACHE, else the user's cache
// directory: $XDG_CACHE_HOME/facet/shaders, else ~/.cache/facet/shaders. An entry is used
// only when it is whole and matches its key (length and content checksum); a damaged
// one (a killed writer, a full disk) is reported as a warning, compiled again and
// rewritten; a directory that cannot be written is a warning, and every shader compiled.
#include <string>

#include "cli.h"

namespace facet {

void add_shader_cache_option(cli::Parser& parser);
// The cache directory chosen as above; empty: none (--no-shader-cache, or no HOME).
// Throws std::invalid_argument for both flags or an empty DIR.
std::string shader_cache_dir(const cli::Parsed& parsed);
// The directory of a cache's pair of options: --OPTION DIR, none with --NO-OPTION,
// `fallback` without either. Throws std::invalid_argument for both or an empty DIR.
std::string cache_dir_option(const cli::Parsed& parsed, const std::string& option, const std::string& no_option,
                             const std::string& fallback);
// The user's cache directory NAME: $XDG_CACHE_HOME/facet/NAME, else ~/.cache/facet/NAME;
// empty without either (nowhere to keep anything).
std::string user_cache_dir(const char* name);
// FACET_SHADER_DIR: read shaders from this directory instead of the embedded copies
// (the library reads no environment variable; ShaderCompilerOptions::source_dir).
// Empty: unset.
std::string shader_dir_from_environment();

}  // namespace facet
