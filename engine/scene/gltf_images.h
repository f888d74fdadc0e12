#pragma once
// Internal to the glTF loader: images, each sized from its PNG or JPEG header and the
// whole set checked against the model's texture budget before any is decoded; then
// decoded, box-downsampled while read where larger than the limit.
#include <tiny_gltf.h>

#include <cstddef>
#include <string>
#include <vector>

#include "io/image_header.h"
#include <facet/scene/gltf_loader.h>
#include "scene/gltf_parse.h"
#include <facet/scene/scene.h>

namespace facet::gltf_detail {

struct ImagePlan {
    std::string name;  // file name or "image N"
    ImageHeader header;
    uint32_t width = 0, height = 0;  // as it will be kept (smaller when downsampled)
    bool srgb = false;               // used as colour (base colour, emissive): means in linear light
};

// Expects validate_buffer_views to have passed and scene.materials converted (they say
// which images are sRGB colour). Fails on an image over the hard limits or a set over
// limits.max_texture_bytes.
std::vector<ImagePlan> plan_images(const tinygltf::Model& model, const EncodedImages& encoded, const Scene& scene,
                                   const GltfLimits& limits);

// Image `index` decoded to RGBA8 at the planned size, from its bufferView or from the
// bytes parse kept for a uri image.
TextureImage decode_image(const tinygltf::Model& model, size_t index, const EncodedImages& encoded,
                          const ImagePlan& plan);

}  // namespace facet::gltf_detail
