#pragma once
// Where shader sources come from: a directory on disk when one is given (edit and
// reload; the programs map FACET_SHADER_DIR and --shader-dir onto it), else the copies
// embedded at build time. Thread safety: load() may be called from several threads.
#include <optional>
#include <string>
#include <string_view>

namespace facet {

class ShaderLibrary {
public:
    // `source_dir` empty: the embedded copies only. A file missing there falls back to
    // the embedded copy.
    explicit ShaderLibrary(std::string source_dir = {});

    // The text of `name` (a path relative to shaders/), or nothing.
    std::optional<std::string> load(std::string_view name) const;

    struct Source {
        std::string name;  // relative to shaders/
        std::string text;
    };
    // What `#include "header"` in `includer` reads: the file beside the includer, else the
    // one at the shaders/ root; `#include <header>` (local false): the root's only.
    std::optional<Source> find_include(std::string_view header, std::string_view includer, bool local) const;
    const std::string& source_dir() const { return source_dir_; }

private:
    std::string source_dir_;
};

// "a/b/../c.glsl" -> "a/c.glsl"; leading "./" dropped. Empty when it leaves the root.
std::string normalize_shader_path(std::string_view path);

}  // namespace facet
