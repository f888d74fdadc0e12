#pragma once
// The shaders/ directory as compiled into the library (cmake/EmbedShaders.cmake).
#include <cstddef>

namespace facet::embedded {

struct Shader {
    const char* name;  // path relative to shaders/, e.g. "ibl/equirect.glsl"
    const char* text;  // not NUL-terminated at `size`; use size
    std::size_t size;
};

extern const Shader shaders[];
extern const std::size_t shader_count;

}  // namespace facet::embedded
