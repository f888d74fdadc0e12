#pragma once
// Internal to the glTF loader: materials and samplers.
#include <tiny_gltf.h>

#include <cstddef>
#include <string>
#include <vector>

#include "scene/gltf_parse.h"
#include <facet/scene/scene.h>

namespace facet::gltf_detail {

// Material `index` with the extensions that change its BRDF (gltf_material_extensions.h).
Material convert_material(const tinygltf::Model& model, size_t index);

// A textureInfo's texture `texture` (-1: none) read with texCoord `tex_coord` and its
// KHR_texture_transform; errors name `where` and the slot.
TextureRef texture_ref(const tinygltf::Model& model, int texture, int tex_coord, const tinygltf::ExtensionMap& extensions,
                       const std::string& where, const char* slot);

TextureSampler convert_sampler(const tinygltf::Sampler& s, size_t index);

}  // namespace facet::gltf_detail
