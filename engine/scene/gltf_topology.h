#pragma once
// Internal to the glTF loader: a primitive's indices as a triangle, line or point list.
#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

#include <facet/scene/scene.h>

namespace facet::gltf_detail {

// The topology a glTF mode is drawn as (strips, fans and loops become lists); fails on
// an unknown mode.
Topology topology_of(int mode, const std::string& where);

// How many list indices `raw` indices of `mode` become (for the budget, before reading).
uint64_t list_index_count(int mode, uint64_t raw);

// The primitive's indices (or 0..n-1), each checked against `vertex_count`, converted to
// a list of topology_of(mode): strips keep their winding, loops close.
std::vector<uint32_t> list_indices(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                   const std::string& where, size_t vertex_count);

}  // namespace facet::gltf_detail
