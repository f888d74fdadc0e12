#pragma once
// Internal to the glTF loader: the node hierarchy into instances, cameras and lights.
#include <tiny_gltf.h>

#include <vector>

#include <facet/scene/gltf_loader.h>
#include <facet/scene/scene.h>
#include "scene/gltf_attributes.h"

namespace facet::gltf_detail {

// Walks scene `scene_index` (-1: the default scene, else scene 0, else every root node),
// checking the hierarchy first. Expects scene.meshes already filled, since instances
// name their primitives; `deforms` holds each of those primitives' skin and morph
// inputs. A node that skins or morphs a primitive draws a deformed copy of it (skinned
// copies in world space, drawn with an identity world), counted against the limits.
void place_nodes(const tinygltf::Model& model, const std::vector<PrimitiveDeform>& deforms, const GltfLimits& limits,
                 int scene_index, Scene& scene);

}  // namespace facet::gltf_detail
