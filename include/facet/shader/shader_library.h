#pragma once
// Where shader sources come from: a directory on disk when one is given (or
// FACET_SHADER_DIR is set: edit-and-reload), else the copies embedded at build time.
#include <optional>
#include <string>
#include <string_view>

namespace facet {

class ShaderLibrary {
public:
    // `source_dir` empty: FACET_SHADER_DIR if set, else embedded only.
    explicit ShaderLibrary(std::string source_dir = {});

    // The text of `name` (a path relative to shaders/), or nothing.
    std::optional<std::string> load(std::string_view name) const;
    const std::string& source_dir() const { return source_dir_; }

private:
    std::string source_dir_;
};

// "a/b/../c.glsl" -> "a/c.glsl"; leading "./" dropped. Empty when it leaves the root.
std::string normalize_shader_path(std::string_view path);

}  // namespace facet
