#pragma once
// Internal to the glTF loader: what the mesh decoders (gltf_decompress_meshopt.cpp,
// gltf_decompress_draco.cpp) share: reading an extension's fields and checking a byte
// range before any decoder sees it.
#include <tiny_gltf.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace facet::gltf_detail {

// Decoded bytes a model may hold, all compressed views and primitives together: far
// beyond a real asset, it keeps a forged count from becoming a huge allocation.
constexpr uint64_t kMaxDecodedBytes = uint64_t(4) << 30;

// The extension object `name` of an object's extensions, or nullptr when absent; a
// value that is not a JSON object is an error naming `where`.
const tinygltf::Value* extension_object(const tinygltf::ExtensionMap& extensions, const char* name,
                                        const std::string& where);

// Field `key` of an extension object as a non-negative integer below 2^53; `fallback`
// when absent, or an error naming `where` when absent and fallback < 0.
uint64_t field_uint(const tinygltf::Value& object, const char* key, const std::string& where, int64_t fallback = -1);
// Field `key` as a string; `fallback` when absent.
std::string field_string(const tinygltf::Value& object, const char* key, const std::string& where,
                         const std::string& fallback);

// Bytes [offset, offset + length) of buffer `buffer`, each checked (index, range).
std::span<const uint8_t> buffer_range(const tinygltf::Model& model, uint64_t buffer, uint64_t offset,
                                      uint64_t length, const std::string& where);

// Appends `bytes` as a new buffer and a bufferView spanning it; returns the view's index.
int add_buffer_view(tinygltf::Model& model, std::vector<uint8_t> bytes, size_t byte_stride);

// Counts decoded bytes against kMaxDecodedBytes; fails naming `where` past it.
struct DecodedBudget {
    uint64_t used = 0;
    void take(uint64_t bytes, const std::string& where);
};

}  // namespace facet::gltf_detail
