#include "scene/gltf_material_extensions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "scene/gltf_errors.h"
#include "scene/gltf_materials.h"

namespace facet::gltf_detail {

namespace {

// The extension's object, or null when the material does not use it.
const tinygltf::Value* extension(const tinygltf::Material& m, const char* name, const std::string& where) {
    const auto found = m.extensions.find(name);
    if (found == m.extensions.end()) return nullptr;
    if (!found->second.IsObject()) fail(where + ": " + name + " must be an object");
    return &found->second;
}

// A number member: `fallback` when absent; an error naming it when not a finite number.
double number(const tinygltf::Value& object, const char* key, double fallback, const std::string& where) {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) fail(where + "." + key + " must be a finite number");
    return v.GetNumberAsDouble();
}

std::string number_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// A number member within [low, high] (`fallback` when absent): an error naming it and the
// range, described as `range` ("[0, 1]"), when outside.
double number_within(const tinygltf::Value& object, const char* key, double fallback, double low, double high,
                     const char* range, const std::string& where) {
    const double v = number(object, key, fallback, where);
    if (v < low || v > high) fail(where + "." + key + " " + number_text(v) + " is outside " + range);
    return v;
}

// `count` finite numbers of an array member into `out`; absent: `out` untouched.
void numbers(const tinygltf::Value& object, const char* key, int count, double* out, const std::string& where) {
    if (!object.Has(key)) return;
    const tinygltf::Value& a = object.Get(key);
    if (!a.IsArray() || a.ArrayLen() != size_t(count))
        fail(where + "." + key + " must have " + std::to_string(count) + " numbers");
    for (int i = 0; i < count; ++i) {
        const tinygltf::Value& v = a.Get(i);
        if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble()))
            fail(where + "." + key + " must have " + std::to_string(count) + " finite numbers");
        out[i] = v.GetNumberAsDouble();
    }
}

// A textureInfo member of an extension's object (index, texCoord, its extensions), read as
// the core textures are (gltf_materials.h); absent: no texture.
TextureRef texture_info(const tinygltf::Model& model, const tinygltf::Value& object, const char* key,
                        const std::string& where) {
    if (!object.Has(key)) return {};
    const std::string at = where + "." + key;
    const tinygltf::Value& info = object.Get(key);
    if (!info.IsObject()) fail(at + " must be an object");
    if (!info.Has("index") || !info.Get("index").IsInt()) fail(at + ".index must be an integer");
    const int index = info.Get("index").GetNumberAsInt();
    if (index < 0) fail(at + ".index " + std::to_string(index) + " is negative");
    int tex_coord = 0;
    if (info.Has("texCoord")) {
        if (!info.Get("texCoord").IsInt()) fail(at + ".texCoord must be an integer");
        tex_coord = info.Get("texCoord").GetNumberAsInt();
    }
    tinygltf::ExtensionMap extensions;
    if (info.Has("extensions")) {
        const tinygltf::Value& e = info.Get("extensions");
        if (!e.IsObject()) fail(at + ".extensions must be an object");
        for (const std::string& name : e.Keys()) extensions[name] = e.Get(name);
    }
    return texture_ref(model, index, tex_coord, extensions, where, key);
}

}  // namespace

void read_texture_transform(const tinygltf::ExtensionMap& extensions, const std::string& where, TextureRef& ref) {
    const auto found = extensions.find("KHR_texture_transform");
    if (found == extensions.end()) return;
    const std::string at = where + ": KHR_texture_transform";
    if (!found->second.IsObject()) fail(at + " must be an object");
    const tinygltf::Value& t = found->second;
    double offset[2] = {0.0, 0.0}, scale[2] = {1.0, 1.0};
    numbers(t, "offset", 2, offset, at);
    numbers(t, "scale", 2, scale, at);
    const double rotation = number(t, "rotation", 0.0, at);
    const double c = std::cos(rotation), s = std::sin(rotation);
    // translation x rotation x scale: the columns R S e0, R S e1 and the offset.
    ref.uv_transform = {float(c * scale[0]), float(s * scale[0]), float(-s * scale[1]), float(c * scale[1]),
                        float(offset[0]), float(offset[1])};
    if (t.Has("texCoord")) {
        const tinygltf::Value& v = t.Get("texCoord");
        if (!v.IsInt() || (v.GetNumberAsInt() != 0 && v.GetNumberAsInt() != 1))
            fail(at + ".texCoord must be 0 or 1 (TEXCOORD_0 or TEXCOORD_1)");
        ref.uv_set = uint32_t(v.GetNumberAsInt());
    }
}

void read_unlit(const tinygltf::Material& m, Material& out) {
    if (m.extensions.find("KHR_materials_unlit") == m.extensions.end()) return;
    out.unlit = true;
    out.clearcoat = 0.0f;
    out.clearcoat_texture = out.clearcoat_roughness_texture = out.clearcoat_normal_texture = {};
    out.specular_texture = out.specular_color_texture = {};
    out.iridescence = 0.0f;
    out.iridescence_texture = out.iridescence_thickness_texture = {};
    out.anisotropy = 0.0f;
    out.anisotropy_texture = {};
    out.sheen_color = glm::vec3(0.0f);
    out.sheen_color_texture = out.sheen_roughness_texture = {};
    out.transmission = 0.0f;
    out.transmission_texture = {};
    out.thickness = 0.0f;
    out.thickness_texture = {};
    out.attenuation_distance = std::numeric_limits<float>::infinity();
    out.attenuation_color = glm::vec3(1.0f);
    out.emissive = glm::vec3(0.0f);
    out.emissive_texture = {};
    out.normal_texture = {};
    out.occlusion_texture = {};
    out.metallic_roughness_texture = {};
}

void read_clearcoat(const tinygltf::Model& model, const tinygltf::Material& m, const std::string& where,
                    Material& out) {
    const tinygltf::Value* coat = extension(m, "KHR_materials_clearcoat", where);
    if (!coat) return;
    const std::string at = where + ": KHR_materials_clearcoat";
    const double factor = number_within(*coat, "clearcoatFactor", 0.0, 0.0, 1.0, "[0, 1]", at);
    const double roughness = number_within(*coat, "clearcoatRoughnessFactor", 0.0, 0.0, 1.0, "[0, 1]", at);
    out.clearcoat = float(factor);
    out.clearcoat_roughness = float(roughness);
    out.clearcoat_texture = texture_info(model, *coat, "clearcoatTexture", at);
    out.clearcoat_roughness_texture = texture_info(model, *coat, "clearcoatRoughnessTexture", at);
    out.clearcoat_normal_texture = texture_info(model, *coat, "clearcoatNormalTexture", at);
    if (coat->Has("clearcoatNormalTexture")) {
        const std::string normal = at + ".clearcoatNormalTexture";
        out.clearcoat_normal_scale = float(number(coat->Get("clearcoatNormalTexture"), "scale", 1.0, normal));
    }
}

void read_iridescence(const tinygltf::Model& model, const tinygltf::Material& m, const std::string& where,
                      Material& out) {
    const tinygltf::Value* film = extension(m, "KHR_materials_iridescence", where);
    if (!film) return;
    const std::string at = where + ": KHR_materials_iridescence";
    const double factor = number_within(*film, "iridescenceFactor", 0.0, 0.0, 1.0, "[0, 1]", at);
    const double ior = number(*film, "iridescenceIor", 1.3, at);
    if (ior < 1.0) fail(at + ".iridescenceIor " + number_text(ior) + " is below 1 (an index of refraction)");
    const char* nanometres = "[0, 1e6] (nanometres)";
    const double minimum = number_within(*film, "iridescenceThicknessMinimum", 100.0, 0.0, 1e6, nanometres, at);
    const double maximum = number_within(*film, "iridescenceThicknessMaximum", 400.0, 0.0, 1e6, nanometres, at);
    out.iridescence = float(factor);
    out.iridescence_ior = float(ior);
    out.iridescence_thickness_minimum = float(minimum);
    out.iridescence_thickness_maximum = float(maximum);
    out.iridescence_texture = texture_info(model, *film, "iridescenceTexture", at);
    out.iridescence_thickness_texture = texture_info(model, *film, "iridescenceThicknessTexture", at);
}

void read_anisotropy(const tinygltf::Model& model, const tinygltf::Material& m, const std::string& where,
                     Material& out) {
    const tinygltf::Value* stretch = extension(m, "KHR_materials_anisotropy", where);
    if (!stretch) return;
    const std::string at = where + ": KHR_materials_anisotropy";
    const double strength = number_within(*stretch, "anisotropyStrength", 0.0, 0.0, 1.0, "[0, 1]", at);
    out.anisotropy = float(strength);
    out.anisotropy_rotation = float(number(*stretch, "anisotropyRotation", 0.0, at));
    out.anisotropy_texture = texture_info(model, *stretch, "anisotropyTexture", at);
}

void read_sheen(const tinygltf::Model& model, const tinygltf::Material& m, const std::string& where, Material& out) {
    const tinygltf::Value* sheen = extension(m, "KHR_materials_sheen", where);
    if (!sheen) return;
    const std::string at = where + ": KHR_materials_sheen";
    double colour[3] = {0.0, 0.0, 0.0};
    numbers(*sheen, "sheenColorFactor", 3, colour, at);
    for (double c : colour)
        if (c < 0.0 || c > 1.0) fail(at + ".sheenColorFactor " + number_text(c) + " is outside [0, 1]");
    out.sheen_color = glm::vec3(float(colour[0]), float(colour[1]), float(colour[2]));
    out.sheen_roughness = float(number_within(*sheen, "sheenRoughnessFactor", 0.0, 0.0, 1.0, "[0, 1]", at));
    out.sheen_color_texture = texture_info(model, *sheen, "sheenColorTexture", at);
    out.sheen_roughness_texture = texture_info(model, *sheen, "sheenRoughnessTexture", at);
}

void read_transmission(const tinygltf::Model& model, const tinygltf::Material& m, const std::string& where,
                       Material& out) {
    if (const tinygltf::Value* transmission = extension(m, "KHR_materials_transmission", where)) {
        const std::string at = where + ": KHR_materials_transmission";
        out.transmission = float(number_within(*transmission, "transmissionFactor", 0.0, 0.0, 1.0, "[0, 1]", at));
        out.transmission_texture = texture_info(model, *transmission, "transmissionTexture", at);
    }
    const tinygltf::Value* volume = extension(m, "KHR_materials_volume", where);
    if (!volume) return;
    const std::string at = where + ": KHR_materials_volume";
    // Finite doubles can still overflow as floats (1e39) or, for the distance, underflow to 0.
    const double thickness = number(*volume, "thicknessFactor", 0.0, at);
    if (thickness < 0.0) fail(at + ".thicknessFactor " + number_text(thickness) + " is negative");
    if (!std::isfinite(float(thickness)))
        fail(at + ".thicknessFactor " + number_text(thickness) + " is too large for floats");
    const double distance = number(*volume, "attenuationDistance", std::numeric_limits<double>::infinity(), at);
    if (volume->Has("attenuationDistance")) {
        if (distance <= 0.0) fail(at + ".attenuationDistance " + number_text(distance) + " is not positive");
        if (!std::isfinite(float(distance)) || float(distance) == 0.0f)
            fail(at + ".attenuationDistance " + number_text(distance) + " is outside the range of floats");
    }
    double colour[3] = {1.0, 1.0, 1.0};
    numbers(*volume, "attenuationColor", 3, colour, at);
    for (double c : colour)
        if (c < 0.0 || c > 1.0) fail(at + ".attenuationColor " + number_text(c) + " is outside [0, 1]");
    out.thickness = float(thickness);
    out.thickness_texture = texture_info(model, *volume, "thicknessTexture", at);
    out.attenuation_distance = float(distance);
    out.attenuation_color = glm::vec3(float(colour[0]), float(colour[1]), float(colour[2]));
}

void read_dielectric_extensions(const tinygltf::Model& model, const tinygltf::Material& m, const std::string& where,
                                Material& out) {
    if (const tinygltf::Value* ior_ext = extension(m, "KHR_materials_ior", where)) {
        const std::string at = where + ": KHR_materials_ior";
        const double ior = number(*ior_ext, "ior", 1.5, at);
        if (!(ior >= 1.0 || ior == 0.0))
            fail(at + ".ior " + number_text(ior) + " is neither 0 nor at least 1 (an index of refraction)");
        const double r = (ior - 1.0) / (ior + 1.0);
        out.dielectric_f0 = float(r * r);
    }
    const tinygltf::Value* spec = extension(m, "KHR_materials_specular", where);
    if (!spec) return;
    const std::string at = where + ": KHR_materials_specular";
    const double factor = number_within(*spec, "specularFactor", 1.0, 0.0, 1.0, "[0, 1]", at);
    double colour[3] = {1.0, 1.0, 1.0};
    if (spec->Has("specularColorFactor")) {
        const tinygltf::Value& c = spec->Get("specularColorFactor");
        if (!c.IsArray() || c.ArrayLen() != 3) fail(at + ".specularColorFactor must have 3 numbers");
        for (int i = 0; i < 3; ++i) {
            const tinygltf::Value& v = c.Get(i);
            if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble()) || v.GetNumberAsDouble() < 0.0)
                fail(at + ".specularColorFactor must have 3 finite numbers >= 0");
            colour[i] = v.GetNumberAsDouble();
        }
    }
    out.specular_texture = texture_info(model, *spec, "specularTexture", at);
    out.specular_color_texture = texture_info(model, *spec, "specularColorTexture", at);
    out.specular_color = glm::vec3(float(colour[0]), float(colour[1]), float(colour[2]));
    out.specular_factor = float(factor);
}

}  // namespace facet::gltf_detail
