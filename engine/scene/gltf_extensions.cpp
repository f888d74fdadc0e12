#include "scene/gltf_extensions.h"

#include <facet/scene/gltf_loader.h>

#include <algorithm>

#include "scene/gltf_decompress.h"
#include "scene/gltf_decompress_draco.h"
#include "scene/gltf_decompress_meshopt.h"
#include "scene/gltf_errors.h"

namespace facet::gltf_detail {

const std::vector<std::string_view>& supported_extensions() {
    // Add an extension here when the loader reads it (and say so in the README).
    static const std::vector<std::string_view> names = [] {
        std::vector<std::string_view> list = {
            "EXT_meshopt_compression",          // gltf_decompress_meshopt.cpp
            "EXT_texture_webp",                 // below; decoded by OpenImageIO (io/texture_decode.cpp)
            "KHR_draco_mesh_compression",       // gltf_decompress_draco.cpp
            "KHR_lights_punctual",              // gltf_nodes.cpp
            "KHR_materials_anisotropy",         // gltf_material_extensions.cpp; drawn by forward.frag (FACET_ANISOTROPY)
            "KHR_materials_clearcoat",          // gltf_material_extensions.cpp; drawn by forward.frag (CLEARCOAT)
            "KHR_materials_emissive_strength",  // gltf_materials.cpp
            "KHR_materials_ior",                // gltf_material_extensions.cpp
            "KHR_materials_iridescence",        // gltf_material_extensions.cpp; drawn by forward.frag (FACET_IRIDESCENCE)
            "KHR_materials_sheen",              // gltf_material_extensions.cpp; drawn by forward.frag (FACET_SHEEN)
            "KHR_materials_specular",           // gltf_material_extensions.cpp; drawn by forward.frag
            "KHR_materials_transmission",       // gltf_material_extensions.cpp; drawn by forward.frag (FACET_TRANSMISSION)
            "KHR_materials_unlit",              // gltf_material_extensions.cpp; drawn by forward.frag (UNLIT)
            "KHR_materials_volume",             // gltf_material_extensions.cpp; drawn by forward.frag (FACET_TRANSMISSION)
            "KHR_mesh_quantization",            // gltf_attributes.cpp: every component type, normalized or not
            "KHR_texture_transform",            // gltf_material_extensions.cpp; drawn by forward_pass.cpp
        };
        std::sort(list.begin(), list.end());
        return list;
    }();
    return names;
}

bool is_supported_extension(std::string_view name) {
    const auto& names = supported_extensions();
    return std::binary_search(names.begin(), names.end(), name);
}

namespace {

// Each name once, in the file's order (a list may repeat a name).
std::vector<std::string> unsupported(const std::vector<std::string>& listed) {
    std::vector<std::string> out;
    for (const std::string& name : listed)
        if (!is_supported_extension(name) && std::find(out.begin(), out.end(), name) == out.end())
            out.push_back(name);
    return out;
}

std::string join(const std::vector<std::string>& names) {
    std::string text;
    for (size_t i = 0; i < names.size(); ++i) text += (i == 0 ? "" : ", ") + names[i];
    return text;
}

}  // namespace

void check_required_extensions(const tinygltf::Model& model) {
    const std::vector<std::string> missing = unsupported(model.extensionsRequired);
    if (missing.size() == 1) fail("requires unsupported extension " + missing[0]);
    if (missing.size() > 1)
        fail("requires " + std::to_string(missing.size()) + " unsupported extensions: " + join(missing));
}

std::vector<std::string> ignored_extension_warnings(const tinygltf::Model& model) {
    std::vector<std::string> warnings;
    for (const std::string& name : unsupported(model.extensionsUsed))
        warnings.push_back("extension " + name + " is used by the file but not implemented: ignored");
    return warnings;
}

void use_webp_sources(tinygltf::Model& model) {
    for (size_t i = 0; i < model.textures.size(); ++i) {
        tinygltf::Texture& texture = model.textures[i];
        const std::string where = "texture " + std::to_string(i) + " (EXT_texture_webp)";
        const tinygltf::Value* webp = extension_object(texture.extensions, "EXT_texture_webp", where);
        if (!webp) continue;
        const uint64_t source = field_uint(*webp, "source", where);
        if (source >= model.images.size()) fail(where + ": source " + std::to_string(source) + " out of range");
        texture.source = int(source);  // the WebP image replaces the fallback (PNG or JPEG), if any
        texture.extensions.erase("EXT_texture_webp");
    }
}

void apply_extensions(tinygltf::Model& model) {
    check_required_extensions(model);
    decompress_meshopt(model);
    decompress_draco(model);
    use_webp_sources(model);
}

}  // namespace facet::gltf_detail

namespace facet {

std::vector<std::string> gltf_supported_extensions() {
    const auto& names = gltf_detail::supported_extensions();
    return {names.begin(), names.end()};
}

}  // namespace facet
