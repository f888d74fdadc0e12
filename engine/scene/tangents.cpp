#include "scene/tangents.h"

#include <cmath>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

namespace facet {

namespace {

bool triangle_in_range(std::span<const uint32_t> indices, size_t first, size_t vertex_count) {
    return indices[first] < vertex_count && indices[first + 1] < vertex_count &&
           indices[first + 2] < vertex_count;
}

// Any unit vector orthogonal to n, for vertices whose uvs give no direction.
glm::vec3 any_orthogonal(glm::vec3 n) {
    glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(axis - n * glm::dot(n, axis));
}

}  // namespace

void generate_normals(std::span<Vertex> vertices, std::span<const uint32_t> indices) {
    std::vector<glm::vec3> sums(vertices.size(), glm::vec3(0.0f));
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        if (!triangle_in_range(indices, i, vertices.size())) continue;
        uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
        // The cross product's length is twice the triangle's area: area weighting for free.
        glm::vec3 face = glm::cross(vertices[b].position - vertices[a].position,
                                    vertices[c].position - vertices[a].position);
        sums[a] += face;
        sums[b] += face;
        sums[c] += face;
    }
    for (size_t v = 0; v < vertices.size(); ++v) {
        float length = glm::length(sums[v]);
        vertices[v].normal = (length > 1e-30f && std::isfinite(length)) ? sums[v] / length
                                                                        : glm::vec3(0, 0, 1);
    }
}

void generate_tangents(std::span<Vertex> vertices, std::span<const uint32_t> indices) {
    std::vector<glm::vec3> du_sums(vertices.size(), glm::vec3(0.0f));  // dP/du
    std::vector<glm::vec3> dv_sums(vertices.size(), glm::vec3(0.0f));  // dP/dv
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        if (!triangle_in_range(indices, i, vertices.size())) continue;
        const Vertex& a = vertices[indices[i]];
        const Vertex& b = vertices[indices[i + 1]];
        const Vertex& c = vertices[indices[i + 2]];
        glm::vec3 e1 = b.position - a.position, e2 = c.position - a.position;
        glm::vec2 t1 = b.uv - a.uv, t2 = c.uv - a.uv;
        float det = t1.x * t2.y - t2.x * t1.y;
        if (std::abs(det) < 1e-20f || !std::isfinite(det)) continue;  // uvs collapse here
        // Solve e = dP/du * du + dP/dv * dv for both edges.
        glm::vec3 dpdu = (e1 * t2.y - e2 * t1.y) / det;
        glm::vec3 dpdv = (e2 * t1.x - e1 * t2.x) / det;
        for (size_t k = 0; k < 3; ++k) {
            du_sums[indices[i + k]] += dpdu;
            dv_sums[indices[i + k]] += dpdv;
        }
    }
    for (size_t v = 0; v < vertices.size(); ++v) {
        glm::vec3 n = vertices[v].normal;
        glm::vec3 t = du_sums[v] - n * glm::dot(n, du_sums[v]);
        float length = glm::length(t);
        t = (length > 1e-20f && std::isfinite(length)) ? t / length : any_orthogonal(n);
        // glTF's v runs down the image while a normal map's +Y (the bitangent) points up
        // it, so an unmirrored mapping has dP/dv opposite to cross(n, t): w = +1.
        float w = glm::dot(glm::cross(n, t), dv_sums[v]) > 0.0f ? -1.0f : 1.0f;
        vertices[v].tangent = glm::vec4(t, w);
    }
}

void generate_tangents_for(std::span<Vertex> vertices, std::span<const uint32_t> indices, uint32_t uv_set) {
    if (uv_set == 0) return generate_tangents(vertices, indices);
    // The generator reads Vertex::uv: lend it the other set for the while.
    for (Vertex& v : vertices) std::swap(v.uv, v.uv1);
    generate_tangents(vertices, indices);
    for (Vertex& v : vertices) std::swap(v.uv, v.uv1);
}

void set_bounds(Primitive& primitive, std::span<const Vertex> vertices) {
    if (vertices.empty()) return;
    primitive.bounds_min = primitive.bounds_max = vertices[0].position;
    for (const Vertex& v : vertices) {
        primitive.bounds_min = glm::min(primitive.bounds_min, v.position);
        primitive.bounds_max = glm::max(primitive.bounds_max, v.position);
    }
}

}  // namespace facet
