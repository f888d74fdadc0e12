#pragma once
// Internal to the glTF loader: reading a .gltf or .glb file into a tinygltf::Model.
#include <tiny_gltf.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace facet::gltf_detail {

// Encoded bytes of uri images by image index; decoded only after validation.
using EncodedImages = std::map<int, std::vector<uint8_t>>;

std::vector<uint8_t> read_file(const std::string& path);

// Parses without decoding any image: uri images' bytes are kept in `encoded`.
tinygltf::Model parse(const std::string& path, const std::vector<uint8_t>& bytes, EncodedImages& encoded);

}  // namespace facet::gltf_detail
