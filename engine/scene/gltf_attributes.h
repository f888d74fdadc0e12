#pragma once
// Internal to the glTF loader: a primitive's vertex attributes, in every component type
// glTF (and KHR_mesh_quantization) allows, into Vertex and the deformation inputs.
#include <tiny_gltf.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <facet/scene/scene.h>

namespace facet::gltf_detail {

// One JOINTS_n / WEIGHTS_n pair: four influences per vertex.
struct Influences {
    std::vector<std::array<uint16_t, 4>> joints;
    std::vector<glm::vec4> weights;
};

// A morph target's displacements; an attribute the target lacks is left empty.
struct MorphTarget {
    std::vector<glm::vec3> position, normal, tangent;
};

// What a node may do to a primitive's vertices when it is placed: skinning and morphing
// (glTF's default pose and default weights, applied on the CPU).
struct PrimitiveDeform {
    std::vector<Influences> influences;  // JOINTS_0/WEIGHTS_0, JOINTS_1/WEIGHTS_1, ...
    std::vector<MorphTarget> targets;
    bool normals_generated = false;   // regenerated after morphing
    bool tangents_generated = false;  // likewise
    bool empty() const { return influences.empty() && targets.empty(); }
};

struct PrimitiveVertices {
    std::vector<Vertex> vertices;
    bool has_normals = false, has_tangents = false;
    PrimitiveDeform deform;
};

// POSITION, NORMAL, TANGENT, TEXCOORD_0/1, COLOR_0, JOINTS_n/WEIGHTS_n and the morph
// targets, each checked for its allowed types, for POSITION's count and for finite values.
PrimitiveVertices read_vertices(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                const std::string& where);

}  // namespace facet::gltf_detail
