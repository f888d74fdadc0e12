#include "scene/gltf_meshes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "scene/gltf_accessors.h"
#include "scene/gltf_errors.h"
#include "scene/gltf_topology.h"
#include "scene/tangents.h"

namespace facet::gltf_detail {

namespace {

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
            total.vertices += vertices;
            total.indices += list_index_count(primitive.mode, raw);
        }
    if (total.vertices > limits.max_vertices)
        fail(budget_error(total.vertices, "vertices", limits.max_vertices, "72 bytes each"));
    if (total.indices > limits.max_indices)
        fail(budget_error(total.indices, "list indices", limits.max_indices, "4 bytes each"));
    return total;
}

PrimitiveDeform load_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                               const std::string& where, bool& needs_default_material, Scene& scene) {
    uint32_t default_material = uint32_t(model.materials.size());
    if (primitive.material != -1 && !in_range(primitive.material, model.materials.size()))
        fail(where + ": material " + std::to_string(primitive.material) + " out of range (" +
             std::to_string(model.materials.size()) + " materials)");
    uint32_t material = primitive.material >= 0 ? uint32_t(primitive.material) : default_material;
    needs_default_material |= primitive.material < 0;

    const Topology topology = topology_of(primitive.mode, where);
    PrimitiveVertices read = read_vertices(model, primitive, where);
    std::vector<Vertex>& vertices = read.vertices;
    const size_t count = vertices.size();
    if (scene.vertices.size() + count > kMaxElements)
        fail(where + ": the scene exceeds " + std::to_string(kMaxElements) + " vertices");

    std::vector<uint32_t> indices = list_indices(model, primitive, where, count);
    if (scene.indices.size() + indices.size() > kMaxElements)
        fail(where + ": the scene exceeds " + std::to_string(kMaxElements) + " indices");
    // Points and lines are drawn unlit: no normals or tangents to derive.
    if (topology == Topology::triangles) {
        read.deform.normals_generated = !read.has_normals;
        if (!read.has_normals) generate_normals(vertices, indices);
        const Material* m = material < scene.materials.size() ? &scene.materials[material] : nullptr;
        if (!read.has_tangents && m && m->needs_tangents()) {
            read.deform.tangents_generated = true;
            generate_tangents_for(vertices, indices, m->tangent_uv_set());
        }
    }

    Primitive out;
    out.first_index = uint32_t(scene.indices.size());
    out.index_count = uint32_t(indices.size());
    out.vertex_offset = uint32_t(scene.vertices.size());
    out.vertex_count = uint32_t(count);
    out.material = material;
    out.topology = topology;
    set_bounds(out, vertices);
    scene.vertices.insert(scene.vertices.end(), vertices.begin(), vertices.end());
    scene.indices.insert(scene.indices.end(), indices.begin(), indices.end());
    scene.primitives.push_back(out);
    return std::move(read.deform);
}

}  // namespace facet::gltf_detail
