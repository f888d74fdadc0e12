#include "scene/gltf_materials.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <string>

#include "scene/gltf_errors.h"
#include "scene/gltf_material_extensions.h"

namespace facet::gltf_detail {

TextureRef texture_ref(const tinygltf::Model& model, int texture, int tex_coord, const tinygltf::ExtensionMap& extensions,
                       const std::string& where, const char* slot) {
    TextureRef ref;
    if (texture == -1) return ref;
    std::string name = where + ": " + slot;
    if (!in_range(texture, model.textures.size()))
        fail(name + " texture " + std::to_string(texture) + " out of range (" + std::to_string(model.textures.size()) +
             " textures)");
    // Vertices carry two uv sets; no sample model uses a third.
    if (tex_coord != 0 && tex_coord != 1)
        fail(name + " uses TEXCOORD_" + std::to_string(tex_coord) + "; only TEXCOORD_0 and TEXCOORD_1 are supported");
    const tinygltf::Texture& t = model.textures[size_t(texture)];
    if (!in_range(t.source, model.images.size()))
        fail(name + ": texture " + std::to_string(texture) + " image " + std::to_string(t.source) + " out of range");
    if (t.sampler != -1 && !in_range(t.sampler, model.samplers.size()))
        fail(name + ": texture " + std::to_string(texture) + " sampler " + std::to_string(t.sampler) + " out of range");
    ref.image = t.source;
    ref.sampler = t.sampler;
    ref.uv_set = uint32_t(tex_coord);
    read_texture_transform(extensions, name, ref);
    return ref;
}

namespace {

uint32_t wrap_mode(int gl_wrap, const std::string& where) {
    switch (gl_wrap) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return 0;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return 1;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return 2;
    default: fail(where + ": unknown wrap mode " + std::to_string(gl_wrap));
    }
}


}  // namespace

Material convert_material(const tinygltf::Model& model, size_t index) {
    const tinygltf::Material& m = model.materials[index];
    std::string where = label("material", index, m.name);
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    Material out;
    out.name = m.name;
    if (pbr.baseColorFactor.size() != 4) fail(where + ": baseColorFactor must have 4 numbers");
    out.base_color = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2],
                               pbr.baseColorFactor[3]);
    out.metallic = float(pbr.metallicFactor);
    out.roughness = float(pbr.roughnessFactor);
    if (m.emissiveFactor.size() == 3) {
        out.emissive = glm::vec3(m.emissiveFactor[0], m.emissiveFactor[1], m.emissiveFactor[2]);
    } else if (!m.emissiveFactor.empty()) {
        fail(where + ": emissiveFactor must have 3 numbers");
    }
    auto strength = m.extensions.find("KHR_materials_emissive_strength");
    if (strength != m.extensions.end() && strength->second.IsObject()) {
        const tinygltf::Value& value = strength->second.Get("emissiveStrength");
        if (value.IsNumber()) out.emissive *= float(value.GetNumberAsDouble());
    }
    read_dielectric_extensions(model, m, where, out);
    read_clearcoat(model, m, where, out);
    read_iridescence(model, m, where, out);
    read_anisotropy(model, m, where, out);
    read_sheen(model, m, where, out);
    read_transmission(model, m, where, out);
    out.normal_scale = float(m.normalTexture.scale);
    out.occlusion_strength = float(m.occlusionTexture.strength);
    if (m.alphaMode == "OPAQUE") {
        out.alpha_mode = AlphaMode::opaque;
    } else if (m.alphaMode == "MASK") {
        out.alpha_mode = AlphaMode::mask;
    } else if (m.alphaMode == "BLEND") {
        out.alpha_mode = AlphaMode::blend;
    } else {
        fail(where + ": unknown alphaMode '" + m.alphaMode + "'");
    }
    out.alpha_cutoff = float(m.alphaCutoff);
    out.double_sided = m.doubleSided;
    // Finite JSON numbers can still overflow as floats (1e39), or in the emissive product.
    const float factors[] = {out.base_color.r, out.base_color.g, out.base_color.b, out.base_color.a, out.metallic,
                             out.roughness, out.emissive.r, out.emissive.g, out.emissive.b, out.normal_scale,
                             out.occlusion_strength, out.alpha_cutoff};
    if (!std::all_of(std::begin(factors), std::end(factors), [](float v) { return std::isfinite(v); }))
        fail(where + ": a factor is not finite (too large for floats)");
    out.base_color_texture = texture_ref(model, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                         pbr.baseColorTexture.extensions, where, "baseColorTexture");
    out.metallic_roughness_texture =
        texture_ref(model, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                    pbr.metallicRoughnessTexture.extensions, where, "metallicRoughnessTexture");
    out.normal_texture = texture_ref(model, m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions,
                                     where, "normalTexture");
    out.occlusion_texture = texture_ref(model, m.occlusionTexture.index, m.occlusionTexture.texCoord,
                                        m.occlusionTexture.extensions, where, "occlusionTexture");
    out.emissive_texture = texture_ref(model, m.emissiveTexture.index, m.emissiveTexture.texCoord,
                                       m.emissiveTexture.extensions, where, "emissiveTexture");
    read_unlit(m, out);  // last: it clears what the others read
    return out;
}

TextureSampler convert_sampler(const tinygltf::Sampler& s, size_t index) {
    std::string where = label("sampler", index, s.name);
    TextureSampler out;
    if (s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) {
        out.mag_linear = false;
    } else if (s.magFilter != -1 && s.magFilter != TINYGLTF_TEXTURE_FILTER_LINEAR) {
        fail(where + ": unknown magFilter " + std::to_string(s.magFilter));
    }
    switch (s.minFilter) {
    case -1: break;  // unspecified: the renderer's choice, trilinear
    case TINYGLTF_TEXTURE_FILTER_NEAREST: out.min_linear = false; out.use_mips = false; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR: out.use_mips = false; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: out.min_linear = false; out.mip_linear = false; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: out.mip_linear = false; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: out.min_linear = false; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: break;
    default: fail(where + ": unknown minFilter " + std::to_string(s.minFilter));
    }
    out.wrap_u = wrap_mode(s.wrapS, where);
    out.wrap_v = wrap_mode(s.wrapT, where);
    return out;
}

}  // namespace facet::gltf_detail
