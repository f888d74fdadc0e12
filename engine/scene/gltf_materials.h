#pragma once
// Internal to the glTF loader: materials, samplers and images.
#include <tiny_gltf.h>

#include <cstddef>

#include "scene/gltf_parse.h"
#include "scene/scene.h"

namespace facet::gltf_detail {

Material convert_material(const tinygltf::Model& model, size_t index);

TextureSampler convert_sampler(const tinygltf::Sampler& s, size_t index);

// Image `index` decoded to RGBA8, from its bufferView (expects validate_buffer_views to
// have passed) or from the bytes parse kept for a uri image.
TextureImage decode_image(const tinygltf::Model& model, size_t index, const EncodedImages& encoded);

}  // namespace facet::gltf_detail
