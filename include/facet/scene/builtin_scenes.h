#pragma once
// The built-in scenes (design.md), so the programs run with no data files:
// builtin:sphere (one unit sphere) and builtin:spheres (the thesis' comparison figure:
// roughness across, metalness down, or one row of a preset).
#include <optional>
#include <string>

#include <facet/core/result.h>
#include <facet/scene/material_presets.h>
#include <facet/scene/scene.h>

namespace facet {

struct SpheresGrid {
    uint32_t columns = 7;  // roughness c / (columns - 1), left to right
    uint32_t rows = 7;     // metalness 1 in the top row down to 0 in the bottom row
    float spacing = 2.5f;  // centre to centre, spheres of radius 1
    glm::vec3 albedo{0.5f, 0.0f, 0.0f};  // the thesis' figure
};

bool is_builtin_scene(const std::string& name);
std::string builtin_scene_names();  // "builtin:sphere, builtin:spheres"

// A preset turns the grid into one row of that material (roughness still across).
Result<Scene> builtin_scene(const std::string& name, const std::optional<MaterialPreset>& preset = std::nullopt,
                            const SpheresGrid& grid = {});

// A UV sphere (radius 1, centre 0) with analytic normals and tangents, appended to the
// scene as one primitive of `material`; returns the primitive's index.
uint32_t add_sphere_primitive(Scene& scene, uint32_t material, uint32_t segments = 64, uint32_t rings = 32);

}  // namespace facet
