#include "shader_cache.h"

#include <cstdlib>

#include <facet/cache/directory_cache.h>

namespace facet {

void add_shader_cache_option(cli::Parser& parser) {
    parser.option("--shader-cache", "DIR", "keep compiled shaders (SPIR-V) in DIR for later runs (default:\n"
                                           "                          FACET_SHADER_CACHE, else $XDG_CACHE_HOME/facet/shaders)")
        .flag("--no-shader-cache", "compile every shader; keep none");
}

std::string shader_cache_dir(const cli::Parsed& parsed) {
    if (parsed.has("--shader-cache") && parsed.has("--no-shader-cache"))
        throw std::invalid_argument("--shader-cache and --no-shader-cache exclude each other");
    if (parsed.has("--no-shader-cache")) return "";
    if (parsed.has("--shader-cache")) {
        if (parsed.get("--shader-cache").empty()) throw std::invalid_argument("--shader-cache needs a directory");
        return parsed.get("--shader-cache");
    }
    if (const char* env = std::getenv("FACET_SHADER_CACHE"); env && *env) return env;
    return user_cache_dir("shaders");
}

std::string user_cache_dir(const char* name) {
    // The library reads no environment: the program picks the folder (XDG base directories).
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* home = std::getenv("HOME");
    auto dir = default_cache_directory(xdg ? xdg : "", home ? home : "");
    return dir ? dir.value() + "/" + name : "";  // no HOME: nowhere to keep it
}

std::string shader_dir_from_environment() {
    const char* env = std::getenv("FACET_SHADER_DIR");
    return env ? env : "";
}

}  // namespace facet
