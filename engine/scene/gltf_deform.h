#pragma once
// Internal to the glTF loader: a node's morph weights and skin applied to a copy of a
// primitive's vertices (the still pose the file defines; no animation).
#include <tiny_gltf.h>

#include <span>
#include <string>
#include <vector>

#include <facet/scene/scene.h>
#include "scene/gltf_attributes.h"

namespace facet::gltf_detail {

// Each skin's joints checked to be nodes and its inverse bind matrices read (identity
// where absent); fails naming the skin.
struct SkinData {
    std::vector<int> joints;
    std::vector<glm::mat4> inverse_bind;
};
std::vector<SkinData> read_skins(const tinygltf::Model& model);

// `base` morphed by `weights` (one per target; empty: no morphing), then, when
// `joint_matrices` is not empty, skinned by them (world space: joint world x inverse
// bind). Normals and tangents follow; generated ones are generated again from the
// morphed positions. `indices` are the primitive's (relative to `base`). `mirrored` is
// set when most vertices' skin matrices mirror (negative determinant): the triangles'
// winding then turns, as for a mirrored node.
std::vector<Vertex> deform_vertices(std::span<const Vertex> base, std::span<const uint32_t> indices,
                                    Topology topology, const PrimitiveDeform& deform, std::span<const float> weights,
                                    std::span<const glm::mat4> joint_matrices, uint32_t normal_uv_set,
                                    const std::string& where, bool& mirrored);

}  // namespace facet::gltf_detail
