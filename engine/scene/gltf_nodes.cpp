#include "scene/gltf_nodes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

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

}  // namespace

void place_nodes(const tinygltf::Model& model, Scene& scene) {
    std::vector<int> parent = check_hierarchy(model);
    std::vector<int> roots;
    if (model.defaultScene != -1 || !model.scenes.empty()) {
        int chosen = model.defaultScene != -1 ? model.defaultScene : 0;
        if (!in_range(chosen, model.scenes.size())) fail("scene " + std::to_string(chosen) + " out of range");
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

    // Iterative, so that a deep (hostile) hierarchy cannot overflow the call stack.
    std::vector<std::pair<int, glm::mat4>> stack;
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) stack.emplace_back(*root, glm::mat4(1.0f));
    while (!stack.empty()) {
        auto [index, parent_world] = stack.back();
        stack.pop_back();
        const tinygltf::Node& node = model.nodes[size_t(index)];
        std::string where = label("node", size_t(index), node.name);
        glm::mat4 world = parent_world * local_matrix(node, where);
        // Finite doubles can still overflow as floats (a scale of 1e39) or in the product.
        for (int c = 0; c < 4; ++c)
            if (!std::isfinite(world[c].x) || !std::isfinite(world[c].y) || !std::isfinite(world[c].z) ||
                !std::isfinite(world[c].w))
                fail(where + ": world transform is not finite (a scale or translation too large for floats)");
        if (node.mesh != -1) {
            if (!in_range(node.mesh, scene.meshes.size()))
                fail(where + ": mesh " + std::to_string(node.mesh) + " out of range");
            for (uint32_t primitive : scene.meshes[size_t(node.mesh)].primitives)
                scene.instances.push_back({primitive, world, node.name.empty() ? where : node.name});
        }
        if (node.camera != -1) scene.cameras.push_back(convert_camera(model, node, world, where));
        if (auto light = node_light(model, node, world, where)) scene.lights.push_back(*light);
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
            stack.emplace_back(*child, world);
    }
}

}  // namespace facet::gltf_detail
