#include "shader_cache.h"

#include <cstdlib>

namespace facet {

void add_shader_cache_option(cli::Parser& parser) {
    parser.option("--shader-cache", "DIR", "keep compiled shaders (SPIR-V) in DIR for later runs\n"
                                           "                          (default: FACET_SHADER_CACHE; none without either)");
}

std::string shader_cache_dir(const cli::Parsed& parsed) {
    if (parsed.has("--shader-cache")) {
        if (parsed.get("--shader-cache").empty()) throw std::invalid_argument("--shader-cache needs a directory");
        return parsed.get("--shader-cache");
    }
    const char* env = std::getenv("FACET_SHADER_CACHE");
    return env ? env : "";
}

std::string shader_dir_from_environment() {
    const char* env = std::getenv("FACET_SHADER_DIR");
    return env ? env : "";
}

}  // namespace facet
