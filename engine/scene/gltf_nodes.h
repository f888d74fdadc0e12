#pragma once
// Internal to the glTF loader: the node hierarchy into instances, cameras and lights.
#include <tiny_gltf.h>

#include <facet/scene/scene.h>

namespace facet::gltf_detail {

// Walks the default scene (else scene 0, else every root node), checking the hierarchy
// first. Expects scene.meshes already filled, since instances name their primitives.
void place_nodes(const tinygltf::Model& model, Scene& scene);

}  // namespace facet::gltf_detail
