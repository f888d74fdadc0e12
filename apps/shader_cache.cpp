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
    const char* env = std::getenv("FACET_SHADER_CACHE");
    return cache_dir_option(parsed, "--shader-cache", "--no-shader-cache",
                            env && *env ? std::string(env) : user_cache_dir("shaders"));
}

std::string cache_dir_option(const cli::Parsed& parsed, const std::string& option, const std::string& no_option,
                             const std::string& fallback) {
    if (parsed.has(option) && parsed.has(no_option))
        throw std::invalid_argument(option + " and " + no_option + " exclude each other");
    if (parsed.has(no_option)) return "";
    if (!parsed.has(option)) return fallback;
    if (parsed.get(option).empty()) throw std::invalid_argument(option + " needs a directory");
    return parsed.get(option);
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
