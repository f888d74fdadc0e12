#include "scene/gltf_meshes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "scene/gltf_accessors.h"
#include "scene/gltf_errors.h"
#include "scene/tangents.h"

namespace facet::gltf_detail {

namespace {

// The accessor of a vertex attribute, checked for type and for matching POSITION's count.
std::optional<AccessorData> attribute(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                      const char* semantic, const std::string& where, size_t vertex_count) {
    auto it = primitive.attributes.find(semantic);
    if (it == primitive.attributes.end()) return std::nullopt;
    AccessorData data = accessor_data(model, it->second, where + " " + semantic);
    bool type_ok = false;
    std::string expected;
    if (std::string_view(semantic) == "POSITION" || std::string_view(semantic) == "NORMAL") {
        type_ok = is_float(data, TINYGLTF_TYPE_VEC3);
        expected = "VEC3 FLOAT";
    } else if (std::string_view(semantic) == "TANGENT") {
        type_ok = is_float(data, TINYGLTF_TYPE_VEC4);
        expected = "VEC4 FLOAT";
    } else {  // TEXCOORD_0
        bool unorm = data.normalized && (data.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                         data.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
        type_ok = data.type == TINYGLTF_TYPE_VEC2 && (data.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT || unorm);
        expected = "VEC2 FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT";
    }
    if (!type_ok) fail(where + ": " + semantic + " must be " + expected);
    if (vertex_count != SIZE_MAX && data.count != vertex_count)
        fail(where + ": " + semantic + " has " + std::to_string(data.count) + " elements, POSITION has " +
             std::to_string(vertex_count));
    return data;
}

// Raw indices (or 0..n-1) turned into a triangle list per the primitive's mode.
std::vector<uint32_t> triangle_indices(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                       const std::string& where, size_t vertex_count) {
    int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
        mode == TINYGLTF_MODE_LINE_STRIP)
        fail(where + ": points and lines (mode " + std::to_string(mode) + ") are not supported");
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
        fail(where + ": unknown primitive mode " + std::to_string(mode));

    std::vector<uint32_t> raw;
    if (primitive.indices >= 0) {
        AccessorData data = accessor_data(model, primitive.indices, where + " indices");
        bool unsigned_int = data.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                            data.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                            data.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        if (data.type != TINYGLTF_TYPE_SCALAR || !unsigned_int || data.normalized)
            fail(where + ": indices must be SCALAR UNSIGNED_BYTE/UNSIGNED_SHORT/UNSIGNED_INT");
        raw.resize(data.count);
        for (size_t i = 0; i < data.count; ++i) {
            raw[i] = index_at(data, i);
            if (raw[i] >= vertex_count)
                fail(where + ": index " + std::to_string(raw[i]) + " >= vertex count " + std::to_string(vertex_count));
        }
    } else {
        raw.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) raw[i] = uint32_t(i);
    }

    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (raw.size() % 3 != 0)
            fail(where + ": " + std::to_string(raw.size()) + " indices is not a multiple of 3");
        return raw;
    }
    std::vector<uint32_t> list;
    if (raw.size() < 3) return list;
    if (3 * uint64_t(raw.size() - 2) > kMaxElements) fail(where + ": too many triangles");
    list.reserve(3 * (raw.size() - 2));
    for (size_t i = 0; i + 2 < raw.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            // Every other strip triangle swaps two corners to keep the winding.
            bool odd = i % 2 == 1;
            list.insert(list.end(), {raw[i], raw[odd ? i + 2 : i + 1], raw[odd ? i + 1 : i + 2]});
        } else {
            list.insert(list.end(), {raw[i + 1], raw[i + 2], raw[0]});
        }
    }
    return list;
}

// Declared counts, capped where they are absurd anyway (the accessor checks reject
// those later with their own message), so sums cannot overflow.
uint64_t declared_count(const tinygltf::Model& model, int accessor) {
    if (!in_range(accessor, model.accessors.size())) return 0;
    return std::min<uint64_t>(model.accessors[size_t(accessor)].count, kMaxElements + 1);
}

std::string budget_error(uint64_t count, const char* what, uint64_t limit, const char* unit) {
    return "the scene's primitives have " + std::to_string(count) + " " + what + ", more than the limit of " +
           std::to_string(limit) + " (" + unit + ")";
}

}  // namespace

GeometryCount count_geometry(const tinygltf::Model& model, const GltfLimits& limits) {
    GeometryCount total;
    for (const tinygltf::Mesh& mesh : model.meshes)
        for (const tinygltf::Primitive& primitive : mesh.primitives) {
            auto position = primitive.attributes.find("POSITION");
            const uint64_t vertices = position == primitive.attributes.end() ? 0 : declared_count(model, position->second);
            const uint64_t raw = primitive.indices >= 0 ? declared_count(model, primitive.indices) : vertices;
            const bool list = primitive.mode < 0 || primitive.mode == TINYGLTF_MODE_TRIANGLES;
            total.vertices += vertices;
            total.indices += list ? raw : raw >= 3 ? 3 * (raw - 2) : 0;
        }
    if (total.vertices > limits.max_vertices)
        fail(budget_error(total.vertices, "vertices", limits.max_vertices, "48 bytes each"));
    if (total.indices > limits.max_indices)
        fail(budget_error(total.indices, "triangle-list indices", limits.max_indices, "4 bytes each"));
    return total;
}

void load_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                    bool& needs_default_material, Scene& scene) {
    uint32_t default_material = uint32_t(model.materials.size());
    if (primitive.material != -1 && !in_range(primitive.material, model.materials.size()))
        fail(where + ": material " + std::to_string(primitive.material) + " out of range (" +
             std::to_string(model.materials.size()) + " materials)");
    uint32_t material = primitive.material >= 0 ? uint32_t(primitive.material) : default_material;
    needs_default_material |= primitive.material < 0;

    auto positions = attribute(model, primitive, "POSITION", where, SIZE_MAX);
    if (!positions) fail(where + ": no POSITION attribute");
    size_t count = positions->count;
    if (count == 0) fail(where + ": no vertices");
    if (scene.vertices.size() + count > kMaxElements)
        fail(where + ": the scene exceeds " + std::to_string(kMaxElements) + " vertices");
    auto normals = attribute(model, primitive, "NORMAL", where, count);
    auto uvs = attribute(model, primitive, "TEXCOORD_0", where, count);
    auto tangents = attribute(model, primitive, "TANGENT", where, count);

    std::vector<Vertex> vertices(count);
    for (size_t i = 0; i < count; ++i) {
        Vertex& v = vertices[i];
        v.position = {component(*positions, i, 0), component(*positions, i, 1), component(*positions, i, 2)};
        if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) || !std::isfinite(v.position.z))
            fail(where + ": vertex " + std::to_string(i) + " position is not finite");
        if (normals) {
            glm::vec3 n(component(*normals, i, 0), component(*normals, i, 1), component(*normals, i, 2));
            float length = glm::length(n);
            // Exporters round normals; shading and tangent generation expect unit length.
            if (length > 1e-20f && std::isfinite(length)) v.normal = n / length;
        }
        if (uvs) {
            v.uv = {component(*uvs, i, 0), component(*uvs, i, 1)};
            if (!std::isfinite(v.uv.x) || !std::isfinite(v.uv.y))
                fail(where + ": vertex " + std::to_string(i) + " TEXCOORD_0 is not finite");
        }
        if (tangents) {
            v.tangent = {component(*tangents, i, 0), component(*tangents, i, 1), component(*tangents, i, 2),
                         component(*tangents, i, 3) < 0.0f ? -1.0f : 1.0f};
            if (!std::isfinite(v.tangent.x) || !std::isfinite(v.tangent.y) || !std::isfinite(v.tangent.z))
                fail(where + ": vertex " + std::to_string(i) + " TANGENT is not finite");
        }
    }

    std::vector<uint32_t> indices = triangle_indices(model, primitive, where, count);
    if (scene.indices.size() + indices.size() > kMaxElements)
        fail(where + ": the scene exceeds " + std::to_string(kMaxElements) + " indices");
    if (!normals) generate_normals(vertices, indices);
    bool has_normal_map = material < scene.materials.size() && scene.materials[material].normal_texture.valid();
    if (!tangents && has_normal_map) generate_tangents(vertices, indices);

    Primitive out;
    out.first_index = uint32_t(scene.indices.size());
    out.index_count = uint32_t(indices.size());
    out.vertex_offset = uint32_t(scene.vertices.size());
    out.vertex_count = uint32_t(count);
    out.material = material;
    out.bounds_min = out.bounds_max = vertices[0].position;
    for (const Vertex& v : vertices) {
        out.bounds_min = glm::min(out.bounds_min, v.position);
        out.bounds_max = glm::max(out.bounds_max, v.position);
    }
    scene.vertices.insert(scene.vertices.end(), vertices.begin(), vertices.end());
    scene.indices.insert(scene.indices.end(), indices.begin(), indices.end());
    scene.primitives.push_back(out);
}

}  // namespace facet::gltf_detail
