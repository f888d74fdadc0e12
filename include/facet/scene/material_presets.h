#pragma once
// The thesis' table of base reflectance F0 (linear, at normal incidence; values as in
// Hoffman's "Physics and Math of Shading", SIGGRAPH 2013 course) as named material
// presets that override a model's materials.
#include <optional>
#include <string>
#include <vector>

#include <facet/scene/scene.h>

namespace facet {

struct MaterialPreset {
    std::string name;
    glm::vec3 f0{0.04f};
    bool metal = false;
};

const std::vector<MaterialPreset>& material_presets();
std::optional<MaterialPreset> find_material_preset(const std::string& name);
// "water, plastic-low, ..." for help texts and error messages.
std::string material_preset_names();

// Metals take F0 as base colour with metalness 1; dielectrics keep their albedo and
// textures, lose any metalness and take F0 as their dielectric reflectance. Roughness,
// normal maps, occlusion and emission are left as they are. "lambert" switches the
// specular lobe off (specular_factor 0).
void apply_material_preset(Material& material, const MaterialPreset& preset);
void apply_material_preset(Scene& scene, const MaterialPreset& preset);

}  // namespace facet
