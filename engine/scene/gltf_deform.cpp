#include "scene/gltf_deform.h"

#include <cmath>

#include "scene/gltf_accessors.h"
#include "scene/gltf_errors.h"
#include "scene/tangents.h"

namespace facet::gltf_detail {

std::vector<SkinData> read_skins(const tinygltf::Model& model) {
    std::vector<SkinData> skins;
    for (size_t s = 0; s < model.skins.size(); ++s) {
        const tinygltf::Skin& skin = model.skins[s];
        const std::string where = label("skin", s, skin.name);
        SkinData out;
        if (skin.joints.empty()) fail(where + ": no joints");
        for (int joint : skin.joints) {
            if (!in_range(joint, model.nodes.size()))
                fail(where + ": joint " + std::to_string(joint) + " is not a node (" + std::to_string(model.nodes.size()) +
                     " nodes)");
            out.joints.push_back(joint);
        }
        out.inverse_bind.assign(skin.joints.size(), glm::mat4(1.0f));
        if (skin.inverseBindMatrices >= 0) {
            AccessorData data = accessor_data(model, skin.inverseBindMatrices, where + " inverseBindMatrices");
            if (data.type != TINYGLTF_TYPE_MAT4 || data.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT)
                fail(where + ": inverseBindMatrices must be MAT4 FLOAT");
            if (data.count < skin.joints.size())
                fail(where + ": " + std::to_string(data.count) + " inverseBindMatrices for " +
                     std::to_string(skin.joints.size()) + " joints");
            for (size_t j = 0; j < skin.joints.size(); ++j)
                for (size_t c = 0; c < 16; ++c) {
                    const float value = component(data, j, c);
                    if (!std::isfinite(value)) fail(where + ": inverse bind matrix " + std::to_string(j) + " is not finite");
                    out.inverse_bind[j][int(c / 4)][int(c % 4)] = value;  // both column-major
                }
        }
        skins.push_back(std::move(out));
    }
    return skins;
}

namespace {

void morph(std::vector<Vertex>& vertices, const PrimitiveDeform& deform, std::span<const float> weights) {
    for (size_t t = 0; t < deform.targets.size() && t < weights.size(); ++t) {
        const MorphTarget& target = deform.targets[t];
        const float w = weights[t];
        if (w == 0.0f) continue;
        for (size_t i = 0; i < vertices.size(); ++i) {
            if (!target.position.empty()) vertices[i].position += w * target.position[i];
            if (!target.normal.empty()) vertices[i].normal += w * target.normal[i];
            if (!target.tangent.empty()) vertices[i].tangent += glm::vec4(w * target.tangent[i], 0.0f);
        }
    }
}

glm::vec3 unit_or(glm::vec3 v, glm::vec3 fallback) {
    const float length = glm::length(v);
    return length > 1e-20f && std::isfinite(length) ? v / length : fallback;
}

// Returns how many vertices' blended matrices mirror.
size_t skin(std::vector<Vertex>& vertices, const PrimitiveDeform& deform, std::span<const glm::mat4> joint_matrices,
            const std::string& where) {
    size_t mirrored = 0;
    for (size_t i = 0; i < vertices.size(); ++i) {
        glm::mat4 m(0.0f);
        float total = 0.0f;
        for (const Influences& in : deform.influences)
            for (int c = 0; c < 4; ++c) {
                const float w = in.weights[i][c];
                if (w == 0.0f) continue;
                const uint16_t joint = in.joints[i][size_t(c)];
                if (joint >= joint_matrices.size())
                    fail(where + ": vertex " + std::to_string(i) + " uses joint " + std::to_string(joint) +
                         " of a skin with " + std::to_string(joint_matrices.size()));
                m += w * joint_matrices[joint];
                total += w;
            }
        // Weights should sum to 1; exporters round them (and quantised ones cannot be exact).
        if (!(total > 1e-6f)) fail(where + ": vertex " + std::to_string(i) + " has no joint weight");
        m /= total;
        Vertex& v = vertices[i];
        v.position = glm::vec3(m * glm::vec4(v.position, 1.0f));
        const glm::mat3 linear(m);
        v.normal = unit_or(glm::transpose(glm::inverse(linear)) * v.normal, v.normal);
        // A mirroring joint flips the bitangent, as it does for a node (forward.vert).
        const bool mirrors = glm::determinant(linear) < 0.0f;
        mirrored += mirrors;
        v.tangent = glm::vec4(unit_or(linear * glm::vec3(v.tangent), glm::vec3(v.tangent)),
                              mirrors ? -v.tangent.w : v.tangent.w);
    }
    return mirrored;
}

}  // namespace

std::vector<Vertex> deform_vertices(std::span<const Vertex> base, std::span<const uint32_t> indices,
                                    Topology topology, const PrimitiveDeform& deform, std::span<const float> weights,
                                    std::span<const glm::mat4> joint_matrices, uint32_t normal_uv_set,
                                    const std::string& where, bool& mirrored) {
    mirrored = false;
    std::vector<Vertex> vertices(base.begin(), base.end());
    if (!weights.empty()) {
        morph(vertices, deform, weights);
        if (topology == Topology::triangles && deform.normals_generated) generate_normals(vertices, indices);
        for (Vertex& v : vertices) {
            if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) || !std::isfinite(v.position.z))
                fail(where + ": a morphed position is not finite");
            v.normal = unit_or(v.normal, glm::vec3(0.0f, 0.0f, 1.0f));
            v.tangent = glm::vec4(unit_or(glm::vec3(v.tangent), glm::vec3(1.0f, 0.0f, 0.0f)), v.tangent.w);
        }
        if (topology == Topology::triangles && deform.tangents_generated)
            generate_tangents_for(vertices, indices, normal_uv_set);
    }
    if (!joint_matrices.empty() && !deform.influences.empty())
        mirrored = 2 * skin(vertices, deform, joint_matrices, where) > vertices.size();
    for (const Vertex& v : vertices)
        if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) || !std::isfinite(v.position.z))
            fail(where + ": a skinned position is not finite");
    return vertices;
}

}  // namespace facet::gltf_detail
