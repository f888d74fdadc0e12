#pragma once
// Internal to the glTF loader: materials and samplers.
#include <tiny_gltf.h>

#include <cstddef>

#include "scene/gltf_parse.h"
#include <facet/scene/scene.h>

namespace facet::gltf_detail {

Material convert_material(const tinygltf::Model& model, size_t index);

TextureSampler convert_sampler(const tinygltf::Sampler& s, size_t index);

}  // namespace facet::gltf_detail
