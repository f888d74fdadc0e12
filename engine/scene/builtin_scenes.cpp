#include <facet/scene/builtin_scenes.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include <facet/core/hash.h>
#include <facet/core/shared_constants.h>

namespace facet {
namespace {

Material sphere_material(const std::string& name, glm::vec3 albedo, float metallic, float roughness) {
    Material m;
    m.name = name;
    m.base_color = glm::vec4(albedo, 1.0f);
    m.metallic = metallic;
    m.roughness = roughness;
    return m;
}

void add_instance(Scene& scene, uint32_t primitive, glm::vec3 at, std::string name) {
    Instance instance;
    instance.primitive = primitive;
    instance.world = glm::translate(glm::mat4(1.0f), at);
    instance.node = std::move(name);
    scene.instances.push_back(instance);
}

std::string scene_hash(const std::string& name, const std::optional<MaterialPreset>& preset, const SpheresGrid& g) {
    Hash64 h;
    h.add(name).add(preset ? preset->name : std::string("none"));
    const float values[] = {float(g.columns), float(g.rows), g.spacing, g.albedo.x, g.albedo.y, g.albedo.z};
    h.add(values, sizeof values);
    return h.hex();
}

}  // namespace

bool is_builtin_scene(const std::string& name) { return name == "builtin:sphere" || name == "builtin:spheres"; }

std::string builtin_scene_names() { return "builtin:sphere, builtin:spheres"; }

uint32_t add_sphere_primitive(Scene& scene, uint32_t material, uint32_t segments, uint32_t rings) {
    Primitive p;
    p.first_index = static_cast<uint32_t>(scene.indices.size());
    p.vertex_offset = static_cast<uint32_t>(scene.vertices.size());
    p.material = material;
    p.bounds_min = glm::vec3(-1.0f);
    p.bounds_max = glm::vec3(1.0f);
    // Rows run from the north pole (v = 0) to the south pole; the seam column is doubled
    // so that u runs 0..1 without wrapping.
    for (uint32_t r = 0; r <= rings; ++r) {
        const float theta = float(pi) * float(r) / float(rings);
        for (uint32_t s = 0; s <= segments; ++s) {
            const float phi = 2.0f * float(pi) * float(s) / float(segments);
            Vertex v;
            v.normal = glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
            v.position = v.normal;
            v.uv = glm::vec2(float(s) / float(segments), float(r) / float(rings));
            // dP/du (direction of increasing u), exact at every latitude, including the poles.
            v.tangent = glm::vec4(-std::sin(phi), 0.0f, -std::cos(phi), 1.0f);
            scene.vertices.push_back(v);
        }
    }
    const uint32_t row = segments + 1;
    for (uint32_t r = 0; r < rings; ++r)
        for (uint32_t s = 0; s < segments; ++s) {
            const uint32_t a = r * row + s, b = a + row;
            // Counter-clockwise seen from outside.
            if (r != 0) scene.indices.insert(scene.indices.end(), {a, b, a + 1});
            if (r + 1 != rings) scene.indices.insert(scene.indices.end(), {a + 1, b, b + 1});
        }
    p.vertex_count = static_cast<uint32_t>(scene.vertices.size()) - p.vertex_offset;
    p.index_count = static_cast<uint32_t>(scene.indices.size()) - p.first_index;
    // Indices are relative to the primitive's first vertex.
    for (uint32_t i = p.first_index; i < scene.indices.size(); ++i) scene.indices[i] -= p.vertex_offset;
    scene.primitives.push_back(p);
    return static_cast<uint32_t>(scene.primitives.size() - 1);
}

Result<Scene> builtin_scene(const std::string& name, const std::optional<MaterialPreset>& preset,
                            const SpheresGrid& grid) {
    Scene scene;
    scene.source = name;
    scene.content_hash = scene_hash(name, preset, grid);
    if (name == "builtin:sphere") {
        scene.materials.push_back(sphere_material("white", glm::vec3(1.0f), 0.0f, 0.5f));
        if (preset) apply_material_preset(scene.materials.back(), *preset);
        const uint32_t p = add_sphere_primitive(scene, 0);
        add_instance(scene, p, glm::vec3(0.0f), "sphere");
        scene.meshes.push_back({"sphere", {p}});
        return scene;
    }
    if (name != "builtin:spheres")
        return Error{name + ": unknown built-in scene (" + builtin_scene_names() + ")"};
    if (grid.columns < 1 || grid.rows < 1) return Error{name + ": the grid needs at least one row and column"};
    const uint32_t rows = preset ? 1 : grid.rows;
    const float x0 = -0.5f * grid.spacing * float(grid.columns - 1);
    const float y0 = -0.5f * grid.spacing * float(rows - 1);
    for (uint32_t r = 0; r < rows; ++r)
        for (uint32_t c = 0; c < grid.columns; ++c) {
            const float roughness = grid.columns > 1 ? float(c) / float(grid.columns - 1) : 0.5f;
            const float metallic = rows > 1 ? float(r) / float(rows - 1) : 0.0f;  // row 0 at the bottom
            Material m = sphere_material("", grid.albedo, metallic, roughness);
            if (preset) apply_material_preset(m, *preset);
            m.name = "roughness " + std::to_string(roughness).substr(0, 4) +
                     (preset ? " " + preset->name : " metalness " + std::to_string(metallic).substr(0, 4));
            scene.materials.push_back(m);
            const uint32_t p = add_sphere_primitive(scene, static_cast<uint32_t>(scene.materials.size() - 1));
            scene.meshes.push_back({m.name, {p}});
            add_instance(scene, p, glm::vec3(x0 + grid.spacing * float(c), y0 + grid.spacing * float(r), 0.0f),
                         m.name);
        }
    return scene;
}

}  // namespace facet
