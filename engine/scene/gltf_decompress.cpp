#include "scene/gltf_decompress.h"

#include <cmath>
#include <utility>

#include <facet/core/units.h>
#include "scene/gltf_errors.h"

namespace facet::gltf_detail {

const tinygltf::Value* extension_object(const tinygltf::ExtensionMap& extensions, const char* name,
                                        const std::string& where) {
    auto it = extensions.find(name);
    if (it == extensions.end()) return nullptr;
    if (!it->second.IsObject()) fail(where + ": " + name + " is not a JSON object");
    return &it->second;
}

uint64_t field_uint(const tinygltf::Value& object, const char* key, const std::string& where, int64_t fallback) {
    const std::string name = where + ": " + key;
    if (!object.Has(key)) {
        if (fallback < 0) fail(name + " is missing");
        return uint64_t(fallback);
    }
    const tinygltf::Value& value = object.Get(key);
    if (!value.IsNumber()) fail(name + " is not a number");
    const double number = value.GetNumberAsDouble();
    // 2^53: every integer below it is exact in a double.
    if (!(number >= 0.0) || number >= 9007199254740992.0 || std::floor(number) != number)
        fail(name + " is not a non-negative integer");
    return uint64_t(number);
}

std::string field_string(const tinygltf::Value& object, const char* key, const std::string& where,
                         const std::string& fallback) {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& value = object.Get(key);
    if (!value.IsString()) fail(where + ": " + key + " is not a string");
    return value.Get<std::string>();
}

std::span<const uint8_t> buffer_range(const tinygltf::Model& model, uint64_t buffer, uint64_t offset,
                                      uint64_t length, const std::string& where) {
    if (buffer >= model.buffers.size()) fail(where + ": buffer " + std::to_string(buffer) + " out of range");
    const std::vector<unsigned char>& data = model.buffers[size_t(buffer)].data;
    if (offset > data.size() || length > data.size() - offset)
        fail(where + ": bytes " + std::to_string(offset) + "..+" + std::to_string(length) + " exceed buffer " +
             std::to_string(buffer) + " (" + std::to_string(data.size()) + " bytes)");
    return {data.data() + offset, size_t(length)};
}

int add_buffer_view(tinygltf::Model& model, std::vector<uint8_t> bytes, size_t byte_stride) {
    tinygltf::BufferView view;
    view.buffer = int(model.buffers.size());
    view.byteOffset = 0;
    view.byteLength = bytes.size();
    view.byteStride = byte_stride;
    tinygltf::Buffer buffer;
    buffer.data = std::move(bytes);
    model.buffers.push_back(std::move(buffer));
    model.bufferViews.push_back(std::move(view));
    return int(model.bufferViews.size() - 1);
}

void DecodedBudget::take(uint64_t bytes, const std::string& where) {
    if (bytes > kMaxDecodedBytes - used)
        fail(where + " decodes to " + format_bytes(bytes) + "; with the " + format_bytes(used) +
             " decoded before it the model exceeds the limit of " + format_bytes(kMaxDecodedBytes) +
             " of decompressed mesh data");
    used += bytes;
}

}  // namespace facet::gltf_detail
