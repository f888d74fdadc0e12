#include "scene/gltf_nodes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/tangents.h"

#include "scene/gltf_deform.h"
#include "scene/gltf_errors.h"

namespace facet::gltf_detail {

namespace {

glm::mat4 local_matrix(const tinygltf::Node& node, const std::string& where) {
    auto finite = [](const std::vector<double>& values) {
        return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
    };
    if (!finite(node.matrix) || !finite(node.translation) || !finite(node.rotation) || !finite(node.scale))
        fail(where + ": transform is not finite");
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) fail(where + ": matrix must have 16 numbers");
        glm::mat4 m;
        for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = float(node.matrix[size_t(i)]);  // both column-major
        return m;
    }
    glm::mat4 m(1.0f);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3) fail(where + ": translation must have 3 numbers");
        m = glm::translate(m, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) fail(where + ": rotation must have 4 numbers");
        glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]));
        float length = glm::length(q);
        if (!(length > 1e-6f)) fail(where + ": rotation is not a unit quaternion");
        m *= glm::mat4_cast(q / length);  // exporters write rounded quaternions
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3) fail(where + ": scale must have 3 numbers");
        m = glm::scale(m, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    }
    return m;
}

// Children in range, one parent each and no cycles; returns each node's parent (-1 for roots).
std::vector<int> check_hierarchy(const tinygltf::Model& model) {
    size_t n = model.nodes.size();
    std::vector<int> parent(n, -1);
    for (size_t i = 0; i < n; ++i) {
        for (int child : model.nodes[i].children) {
            std::string where = label("node", i, model.nodes[i].name);
            if (!in_range(child, n)) fail(where + ": child " + std::to_string(child) + " out of range");
            if (parent[size_t(child)] != -1)
                fail(label("node", size_t(child), model.nodes[size_t(child)].name) + " has more than one parent");
            parent[size_t(child)] = int(i);
        }
    }
    // With one parent each, a cycle is a loop of parent links: walk up from every node,
    // stopping at nodes already known to reach a root.
    enum : uint8_t { unseen, on_path, reaches_root };
    std::vector<uint8_t> state(n, unseen);
    std::vector<size_t> path;
    for (size_t start = 0; start < n; ++start) {
        path.clear();
        int at = int(start);
        while (at != -1 && state[size_t(at)] == unseen) {
            state[size_t(at)] = on_path;
            path.push_back(size_t(at));
            at = parent[size_t(at)];
        }
        if (at != -1 && state[size_t(at)] == on_path)
            fail("node hierarchy has a cycle through " + label("node", size_t(at), model.nodes[size_t(at)].name));
        for (size_t p : path) state[p] = reaches_root;
    }
    return parent;
}

glm::vec3 translation_of(const glm::mat4& world) { return glm::vec3(world[3]); }

glm::vec3 world_direction(const glm::mat4& world, glm::vec3 local, const std::string& where) {
    glm::vec3 d = glm::mat3(world) * local;
    float length = glm::length(d);
    if (!(length > 1e-20f) || !std::isfinite(length)) fail(where + ": degenerate world transform");
    return d / length;
}

Camera convert_camera(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world,
                      const std::string& where) {
    int index = node.camera;
    if (!in_range(index, model.cameras.size())) fail(where + ": camera " + std::to_string(index) + " out of range");
    const tinygltf::Camera& c = model.cameras[size_t(index)];
    Camera out;
    out.name = !c.name.empty() ? c.name : !node.name.empty() ? node.name : where;
    if (c.type == "perspective") {
        if (!(c.perspective.yfov > 0.0) || !(c.perspective.znear > 0.0))
            fail(where + ": perspective camera needs positive yfov and znear");
        out.yfov = float(c.perspective.yfov);
        out.znear = float(c.perspective.znear);
        out.zfar = float(c.perspective.zfar);
    } else if (c.type == "orthographic") {
        out.orthographic = true;
        out.ymag = float(c.orthographic.ymag);
        out.znear = float(c.orthographic.znear);
        out.zfar = float(c.orthographic.zfar);
    } else {
        fail(where + ": unknown camera type '" + c.type + "'");
    }
    if (!std::isfinite(out.yfov) || !std::isfinite(out.znear) || !std::isfinite(out.zfar) || !std::isfinite(out.ymag))
        fail(where + ": camera values are not finite (too large for floats)");
    out.position = translation_of(world);
    out.target = out.position + world_direction(world, {0, 0, -1}, where);
    out.up = world_direction(world, {0, 1, 0}, where);
    return out;
}

std::optional<Light> node_light(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world,
                                const std::string& where) {
    auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return std::nullopt;
    const tinygltf::Value& index_value = ext->second.IsObject() ? ext->second.Get("light") : tinygltf::Value();
    if (!index_value.IsNumber()) fail(where + ": KHR_lights_punctual without a light index");
    // GetNumberAsInt would convert a real such as 1e30 without a range check (undefined).
    const double number = index_value.GetNumberAsDouble();
    if (!(number >= 0 && number < double(model.lights.size())) || number != std::floor(number)) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", number);
        fail(where + ": light " + text + " out of range (" + std::to_string(model.lights.size()) + " lights)");
    }
    const tinygltf::Light& l = model.lights[size_t(number)];
    Light out;
    if (l.type == "directional") {
        out.type = LightType::directional;
    } else if (l.type == "point") {
        out.type = LightType::point;
    } else if (l.type == "spot") {
        out.type = LightType::spot;
    } else {
        fail(where + ": unknown light type '" + l.type + "'");
    }
    if (l.color.size() == 3) {
        out.color = glm::vec3(l.color[0], l.color[1], l.color[2]);
    } else if (!l.color.empty()) {
        fail(where + ": light color must have 3 numbers");
    }
    out.intensity = float(l.intensity);
    out.range = float(l.range);
    out.inner_cone = float(l.spot.innerConeAngle);
    out.outer_cone = float(l.spot.outerConeAngle);
    const float values[] = {out.color.x, out.color.y, out.color.z, out.intensity, out.range, out.inner_cone,
                            out.outer_cone};
    if (!std::all_of(std::begin(values), std::end(values), [](float v) { return std::isfinite(v); }))
        fail(where + ": light values are not finite (too large for floats)");
    out.position = translation_of(world);
    out.direction = world_direction(world, {0, 0, -1}, where);
    return out;
}

// Every node's world matrix (whatever scene it is in: joints may lie outside the drawn
// one), parents before children.
std::vector<glm::mat4> world_matrices(const tinygltf::Model& model, const std::vector<int>& parent) {
    std::vector<glm::mat4> world(model.nodes.size(), glm::mat4(1.0f));
    // Iterative, so that a deep (hostile) hierarchy cannot overflow the call stack.
    std::vector<int> stack;
    for (size_t i = 0; i < model.nodes.size(); ++i)
        if (parent[i] == -1) stack.push_back(int(i));
    while (!stack.empty()) {
        const int index = stack.back();
        stack.pop_back();
        const tinygltf::Node& node = model.nodes[size_t(index)];
        const std::string where = label("node", size_t(index), node.name);
        const glm::mat4 parent_world = parent[size_t(index)] == -1 ? glm::mat4(1.0f) : world[size_t(parent[size_t(index)])];
        glm::mat4& m = world[size_t(index)];
        m = parent_world * local_matrix(node, where);
        // Finite doubles can still overflow as floats (a scale of 1e39) or in the product.
        for (int c = 0; c < 4; ++c)
            if (!std::isfinite(m[c].x) || !std::isfinite(m[c].y) || !std::isfinite(m[c].z) || !std::isfinite(m[c].w))
                fail(where + ": world transform is not finite (a scale or translation too large for floats)");
        for (int child : node.children) stack.push_back(child);
    }
    return world;
}

// The morph weights a node gives its mesh: node.weights over mesh.weights (empty: none).
std::vector<float> morph_weights(const tinygltf::Node& node, const tinygltf::Mesh& mesh, const std::string& where) {
    const std::vector<double>& chosen = !node.weights.empty() ? node.weights : mesh.weights;
    std::vector<float> out;
    for (double w : chosen) {
        if (!std::isfinite(w)) fail(where + ": a morph weight is not finite");
        out.push_back(float(w));
    }
    return out;
}

// Draws mesh `mesh_index` for the node at `index`, deforming copies where it skins or morphs.
void place_mesh(const tinygltf::Model& model, int index, const std::vector<glm::mat4>& world,
                const std::vector<SkinData>& skins, const std::vector<PrimitiveDeform>& deforms,
                const GltfLimits& limits, Scene& scene) {
    const tinygltf::Node& node = model.nodes[size_t(index)];
    const std::string where = label("node", size_t(index), node.name);
    if (!in_range(node.mesh, scene.meshes.size())) fail(where + ": mesh " + std::to_string(node.mesh) + " out of range");
    if (node.skin != -1 && !in_range(node.skin, skins.size()))
        fail(where + ": skin " + std::to_string(node.skin) + " out of range (" + std::to_string(skins.size()) + " skins)");
    const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
    const std::vector<float> weights = morph_weights(node, mesh, where);
    std::vector<glm::mat4> joints;
    if (node.skin != -1) {
        const SkinData& skin = skins[size_t(node.skin)];
        for (size_t j = 0; j < skin.joints.size(); ++j)
            joints.push_back(world[size_t(skin.joints[j])] * skin.inverse_bind[j]);
    }
    const std::string name = node.name.empty() ? where : node.name;
    const std::vector<uint32_t> primitives = scene.meshes[size_t(node.mesh)].primitives;
    for (size_t p = 0; p < primitives.size(); ++p) {
        const uint32_t primitive = primitives[p];
        const PrimitiveDeform& deform = deforms[primitive];
        const std::string at = where + " " + label("mesh", size_t(node.mesh), mesh.name) + " primitive " + std::to_string(p);
        if (!deform.targets.empty() && !weights.empty() && weights.size() != deform.targets.size())
            fail(at + ": " + std::to_string(weights.size()) + " morph weights for " +
                 std::to_string(deform.targets.size()) + " morph targets");
        const bool morphs = !deform.targets.empty() && std::any_of(weights.begin(), weights.end(), [](float w) { return w != 0.0f; });
        const bool skinned = !joints.empty() && !deform.influences.empty();
        if (!morphs && !skinned) {
            scene.instances.push_back({primitive, world[size_t(index)], name});
            continue;
        }
        Primitive copy = scene.primitives[primitive];
        if (scene.vertices.size() + copy.vertex_count > limits.max_vertices)
            fail(at + ": its skinned or morphed copy takes the scene past the limit of " +
                 std::to_string(limits.max_vertices) + " vertices");
        const std::span<const Vertex> base(scene.vertices.data() + copy.vertex_offset, copy.vertex_count);
        const std::span<const uint32_t> indices(scene.indices.data() + copy.first_index, copy.index_count);
        const Material* material = copy.material < scene.materials.size() ? &scene.materials[copy.material] : nullptr;
        bool mirrored = false;
        std::vector<Vertex> vertices = deform_vertices(
            base, indices, copy.topology, deform, morphs ? std::span<const float>(weights) : std::span<const float>(),
            skinned ? std::span<const glm::mat4>(joints) : std::span<const glm::mat4>(),
            material ? material->tangent_uv_set() : 0u, at, mirrored);
        if (mirrored && copy.topology == Topology::triangles) {
            // A mirroring skin turns the winding: its copy gets its own, reversed triangles.
            if (scene.indices.size() + copy.index_count > limits.max_indices)
                fail(at + ": its mirrored skinned copy takes the scene past the limit of " +
                     std::to_string(limits.max_indices) + " indices");
            const std::vector<uint32_t> reversed_from(indices.begin(), indices.end());
            copy.first_index = uint32_t(scene.indices.size());
            for (size_t t = 0; t + 2 < reversed_from.size(); t += 3)
                scene.indices.insert(scene.indices.end(), {reversed_from[t], reversed_from[t + 2], reversed_from[t + 1]});
        }
        copy.vertex_offset = uint32_t(scene.vertices.size());
        set_bounds(copy, vertices);
        scene.vertices.insert(scene.vertices.end(), vertices.begin(), vertices.end());
        scene.primitives.push_back(copy);
        // Skinned vertices are in world space already: the node's own transform does not apply.
        scene.instances.push_back({uint32_t(scene.primitives.size() - 1), skinned ? glm::mat4(1.0f) : world[size_t(index)], name});
    }
}

}  // namespace

void place_nodes(const tinygltf::Model& model, const std::vector<PrimitiveDeform>& deforms, const GltfLimits& limits,
                 int scene_index, Scene& scene) {
    std::vector<int> parent = check_hierarchy(model);
    const std::vector<glm::mat4> world = world_matrices(model, parent);
    const std::vector<SkinData> skins = read_skins(model);
    std::vector<int> roots;
    if (scene_index != -1 || model.defaultScene != -1 || !model.scenes.empty()) {
        int chosen = scene_index != -1 ? scene_index : model.defaultScene != -1 ? model.defaultScene : 0;
        if (!in_range(chosen, model.scenes.size()))
            fail("scene " + std::to_string(chosen) + " out of range (" + std::to_string(model.scenes.size()) + " scenes)");
        roots = model.scenes[size_t(chosen)].nodes;
        std::vector<bool> listed(model.nodes.size(), false);
        for (int root : roots) {
            if (!in_range(root, model.nodes.size()))
                fail("scene " + std::to_string(chosen) + ": node " + std::to_string(root) + " out of range");
            if (parent[size_t(root)] != -1)
                fail("scene " + std::to_string(chosen) + ": " +
                     label("node", size_t(root), model.nodes[size_t(root)].name) + " is not a root node");
            // glTF requires unique roots; each repeat would place the whole subtree again.
            if (listed[size_t(root)])
                fail("scene " + std::to_string(chosen) + ": " +
                     label("node", size_t(root), model.nodes[size_t(root)].name) + " is listed twice");
            listed[size_t(root)] = true;
        }
    } else {
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (parent[i] == -1) roots.push_back(int(i));
    }

    std::vector<int> stack(roots.rbegin(), roots.rend());
    while (!stack.empty()) {
        const int index = stack.back();
        stack.pop_back();
        const tinygltf::Node& node = model.nodes[size_t(index)];
        std::string where = label("node", size_t(index), node.name);
        const glm::mat4& m = world[size_t(index)];
        if (node.mesh != -1) place_mesh(model, index, world, skins, deforms, limits, scene);
        if (node.camera != -1) scene.cameras.push_back(convert_camera(model, node, m, where));
        if (auto light = node_light(model, node, m, where)) scene.lights.push_back(*light);
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) stack.push_back(*child);
    }
}

}  // namespace facet::gltf_detail
