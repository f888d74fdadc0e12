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

// The bytes a model has read from disk (its file, external buffers and images) against
// GltfLimits::max_file_bytes; every file's size is checked before it is read.
struct FileBudget {
    uint64_t limit = 0;
    uint64_t used = 0;
    std::string refusal;  // why a file was refused, when one was
};

std::vector<uint8_t> read_file(const std::string& path, FileBudget& budget);

// Parses without decoding any image: uri images' bytes are kept in `encoded`.
tinygltf::Model parse(const std::string& path, const std::vector<uint8_t>& bytes, EncodedImages& encoded,
                      FileBudget& budget);

}  // namespace facet::gltf_detail
