#include <facet/scene/material_presets.h>

namespace facet {

const std::vector<MaterialPreset>& material_presets() {
    static const std::vector<MaterialPreset> presets = {
        {"water", glm::vec3(0.02f), false},
        {"plastic-low", glm::vec3(0.03f), false},
        {"plastic-high", glm::vec3(0.05f), false},
        {"glass", glm::vec3(0.08f), false},  // high-index glass / ruby
        {"diamond", glm::vec3(0.17f), false},
        {"iron", {0.56f, 0.57f, 0.58f}, true},
        {"copper", {0.95f, 0.64f, 0.54f}, true},
        {"gold", {1.00f, 0.71f, 0.29f}, true},
        {"aluminium", {0.91f, 0.92f, 0.92f}, true},
        {"silver", {0.95f, 0.93f, 0.88f}, true},
        {"lambert", glm::vec3(0.0f), false},
    };
    return presets;
}

std::optional<MaterialPreset> find_material_preset(const std::string& name) {
    for (const MaterialPreset& p : material_presets())
        if (p.name == name) return p;
    if (name == "aluminum") return find_material_preset("aluminium");
    return std::nullopt;
}

std::string material_preset_names() {
    std::string names;
    for (const MaterialPreset& p : material_presets()) names += (names.empty() ? "" : ", ") + p.name;
    return names;
}

void apply_material_preset(Material& m, const MaterialPreset& preset) {
    m.name = preset.name;
    if (preset.metal) {
        m.base_color = glm::vec4(preset.f0, m.base_color.a);
        m.base_color_texture = {};
        m.metallic = 1.0f;
    } else {
        m.metallic = 0.0f;
        m.dielectric_f0 = preset.f0.x;
    }
    // A metallic-roughness texture still multiplies the metalness (glTF: factor x B),
    // so a metal preset on a textured model stays a metal only where B is 1.
    m.specular_factor = preset.name == "lambert" ? 0.0f : 1.0f;
}

void apply_material_preset(Scene& scene, const MaterialPreset& preset) {
    for (Material& m : scene.materials) apply_material_preset(m, preset);
}

}  // namespace facet
