#include <facet/shader/shader_library.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "shader/embedded_shaders.h"

namespace facet {

ShaderLibrary::ShaderLibrary(std::string source_dir) : source_dir_(std::move(source_dir)) {}

std::optional<std::string> ShaderLibrary::load(std::string_view name) const {
    const std::string path = normalize_shader_path(name);
    if (path.empty()) return std::nullopt;
    if (!source_dir_.empty()) {
        std::ifstream in(source_dir_ + "/" + path, std::ios::binary);
        if (in) {
            std::ostringstream text;
            text << in.rdbuf();
            return text.str();
        }
    }
    for (std::size_t i = 0; i < embedded::shader_count; ++i)
        if (path == embedded::shaders[i].name)
            return std::string(embedded::shaders[i].text, embedded::shaders[i].size);
    return std::nullopt;
}

std::optional<ShaderLibrary::Source> ShaderLibrary::find_include(std::string_view header, std::string_view includer,
                                                                bool local) const {
    auto find = [&](std::string name) -> std::optional<Source> {
        if (name.empty()) return std::nullopt;
        auto text = load(name);
        if (!text) return std::nullopt;
        return Source{std::move(name), std::move(*text)};
    };
    if (local) {
        const size_t slash = includer.rfind('/');
        const std::string_view folder = slash == std::string_view::npos ? "" : includer.substr(0, slash + 1);
        if (auto found = find(normalize_shader_path(std::string(folder) + std::string(header)))) return found;
    }
    return find(normalize_shader_path(header));
}

std::string normalize_shader_path(std::string_view path) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (start <= path.size()) {
        std::size_t end = path.find('/', start);
        if (end == std::string_view::npos) end = path.size();
        std::string part(path.substr(start, end - start));
        if (part == "..") {
            if (parts.empty()) return {};
            parts.pop_back();
        } else if (!part.empty() && part != ".") {
            parts.push_back(part);
        }
        start = end + 1;
    }
    std::string out;
    for (const std::string& p : parts) out += (out.empty() ? "" : "/") + p;
    return out;
}

}  // namespace facet
