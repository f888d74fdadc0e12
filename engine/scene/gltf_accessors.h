#pragma once
// Internal to the glTF loader: bounds-checked views of accessor data.
#include <tiny_gltf.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace facet::gltf_detail {

struct AccessorData {
    const uint8_t* base = nullptr;  // element 0
    size_t stride = 0;
    size_t count = 0;
    int component_type = 0;
    int type = 0;  // TINYGLTF_TYPE_*
    bool normalized = false;
    // Sparse accessors and those without a bufferView (all zeros) are made dense here;
    // `base` then points into this copy.
    std::shared_ptr<const std::vector<uint8_t>> dense;
};

// Every bufferView inside its buffer, so later reads through a view need only check
// against the view.
void validate_buffer_views(const tinygltf::Model& model);

// Elements of an accessor type (SCALAR 1 ... MAT4 16); 0 for an unknown type.
size_t component_count(int type);

// Accessor `index`, with every element it spans checked to lie inside its bufferView.
// Sparse accessors (with or without a base bufferView) come back densified, their
// indices checked to be in range and strictly increasing.
AccessorData accessor_data(const tinygltf::Model& model, int index, const std::string& where);

// The readers below are inline because they run once per vertex component: keeping
// them visible to their callers keeps the loops as fast as in a single file.

template <class T>
T load(const uint8_t* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));  // accessors need not be aligned for the host
    return value;
}

inline size_t component_size(int component_type) {
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

// Component c of element i as a float, applying glTF's normalisation rules.
inline float component(const AccessorData& data, size_t i, size_t c) {
    const uint8_t* p = data.base + i * data.stride + c * component_size(data.component_type);
    switch (data.component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return data.normalized ? p[0] / 255.0f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return data.normalized ? load<uint16_t>(p) / 65535.0f : float(load<uint16_t>(p));
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        return data.normalized ? std::max(load<int8_t>(p) / 127.0f, -1.0f) : float(load<int8_t>(p));
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        return data.normalized ? std::max(load<int16_t>(p) / 32767.0f, -1.0f) : float(load<int16_t>(p));
    default: return float(load<uint32_t>(p));
    }
}

inline uint32_t index_at(const AccessorData& data, size_t i) {
    const uint8_t* p = data.base + i * data.stride;
    switch (data.component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<uint16_t>(p);
    default: return load<uint32_t>(p);
    }
}

inline bool is_float(const AccessorData& data, int type) {
    return data.type == type && data.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
}

}  // namespace facet::gltf_detail
