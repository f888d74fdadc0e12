#include "scene/gltf_accessors.h"

#include "scene/gltf_errors.h"

namespace facet::gltf_detail {

namespace {

constexpr uint64_t kMaxDenseBytes = uint64_t(16) << 24;

// `count` elements of `element` bytes at `offset` in bufferView `view`, `stride` apart
// (0: tightly packed), checked to lie inside the view; returns element 0.
const uint8_t* view_span(const tinygltf::Model& model, int view_index, size_t offset, size_t count, size_t element,
                         size_t& stride, const std::string& name) {
    if (!in_range(view_index, model.bufferViews.size()))
        fail(name + ": bufferView " + std::to_string(view_index) + " missing or out of range");
    const tinygltf::BufferView& view = model.bufferViews[size_t(view_index)];
    if (stride == 0) stride = view.byteStride != 0 ? view.byteStride : element;
    if (stride < element) fail(name + ": byteStride " + std::to_string(stride) + " is less than its element size");
    // count <= 2^28 and stride <= 252, so this cannot overflow.
    uint64_t span = count == 0 ? 0 : uint64_t(stride) * (count - 1) + element;
    if (offset > view.byteLength || span > view.byteLength - offset)
        fail(name + " (offset " + std::to_string(offset) + ", stride " + std::to_string(stride) + ", count " +
             std::to_string(count) + ") exceeds its bufferView " + std::to_string(view_index) + " (" +
             std::to_string(view.byteLength) + " bytes)");
    return model.buffers[size_t(view.buffer)].data.data() + view.byteOffset + offset;
}

// The accessor's elements, tightly packed, with its sparse substitutions applied.
void densify(const tinygltf::Model& model, const tinygltf::Accessor& accessor, size_t element, AccessorData& data,
             const std::string& name) {
    // A sparse or view-less accessor's declared count is not backed by bytes in the file:
    // bound it before allocating, at what the largest attribute within the default vertex
    // limit takes (2^24 VEC4 FLOAT, 256 MiB).
    if (uint64_t(data.count) * element > kMaxDenseBytes)
        fail(name + ": " + (accessor.sparse.isSparse ? "sparse" : "view-less") + " accessor of " +
             std::to_string(data.count) + " elements is too large (more than " +
             std::to_string(kMaxDenseBytes >> 20) + " MiB dense)");
    auto dense = std::make_shared<std::vector<uint8_t>>(data.count * element, uint8_t(0));
    if (accessor.bufferView >= 0)
        for (size_t i = 0; i < data.count; ++i) std::memcpy(dense->data() + i * element, data.base + i * data.stride, element);
    if (accessor.sparse.isSparse) {
        const auto& sparse = accessor.sparse;
        const std::string where = name + " sparse";
        if (sparse.count < 1 || size_t(sparse.count) > data.count)
            fail(where + " count " + std::to_string(sparse.count) + " is not in 1.." + std::to_string(data.count));
        const int index_type = sparse.indices.componentType;
        if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail(where + " indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
        if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) fail(where + ": negative byteOffset");
        const size_t index_size = component_size(index_type), count = size_t(sparse.count);
        size_t index_stride = index_size, value_stride = element;  // sparse views are tightly packed
        AccessorData indices;
        indices.base = view_span(model, sparse.indices.bufferView, size_t(sparse.indices.byteOffset), count, index_size,
                                 index_stride, where + " indices");
        indices.stride = index_size;
        indices.component_type = index_type;
        const uint8_t* values = view_span(model, sparse.values.bufferView, size_t(sparse.values.byteOffset), count,
                                          element, value_stride, where + " values");
        uint64_t previous = 0;
        for (size_t i = 0; i < count; ++i) {
            const uint32_t at = index_at(indices, i);
            if (at >= data.count)
                fail(where + " index " + std::to_string(at) + " out of range (the accessor has " +
                     std::to_string(data.count) + " elements)");
            if (i > 0 && at <= previous) fail(where + " indices are not strictly increasing at " + std::to_string(i));
            previous = at;
            std::memcpy(dense->data() + size_t(at) * element, values + i * element, element);
        }
    }
    data.base = dense->data();
    data.stride = element;
    data.dense = std::move(dense);
}

}  // namespace

size_t component_count(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT4: return 16;  // inverse bind matrices (FLOAT: no column padding)
    default: return 0;                   // MAT2/MAT3: never an attribute or skin input
    }
}

void validate_buffer_views(const tinygltf::Model& model) {
    for (size_t i = 0; i < model.bufferViews.size(); ++i) {
        const tinygltf::BufferView& view = model.bufferViews[i];
        std::string where = "bufferView " + std::to_string(i);
        if (!in_range(view.buffer, model.buffers.size()))
            fail(where + ": buffer " + std::to_string(view.buffer) + " out of range");
        size_t size = model.buffers[size_t(view.buffer)].data.size();
        if (view.byteOffset > size || view.byteLength > size - view.byteOffset)
            fail(where + " (offset " + std::to_string(view.byteOffset) + ", length " + std::to_string(view.byteLength) +
                 ") exceeds buffer " + std::to_string(view.buffer) + " (" + std::to_string(size) + " bytes)");
        if (view.byteStride != 0 && (view.byteStride < 4 || view.byteStride > 252))
            fail(where + ": byteStride " + std::to_string(view.byteStride) + " outside 4..252");
    }
}

AccessorData accessor_data(const tinygltf::Model& model, int index, const std::string& where) {
    std::string name = where + ": accessor " + std::to_string(index);
    if (!in_range(index, model.accessors.size())) fail(name + " out of range");
    const tinygltf::Accessor& accessor = model.accessors[size_t(index)];
    size_t element = component_size(accessor.componentType) * component_count(accessor.type);
    if (element == 0) fail(name + " has an unsupported type or component type");
    if (accessor.count > kMaxElements)
        fail(name + ": count " + std::to_string(accessor.count) + " exceeds the limit of " + std::to_string(kMaxElements));

    AccessorData data;
    data.count = accessor.count;
    data.component_type = accessor.componentType;
    data.type = accessor.type;
    data.normalized = accessor.normalized;
    // Without a bufferView an accessor is zeros (glTF 3.6.2.1), which a sparse one may
    // then override; both are made dense.
    if (accessor.bufferView < -1) fail(name + ": bufferView " + std::to_string(accessor.bufferView) + " out of range");
    if (accessor.bufferView >= 0)
        data.base = view_span(model, accessor.bufferView, accessor.byteOffset, accessor.count, element, data.stride, name);
    if (accessor.sparse.isSparse || accessor.bufferView < 0) densify(model, accessor, element, data, name);
    return data;
}

}  // namespace facet::gltf_detail
