#include "scene/gltf_accessors.h"

#include "scene/gltf_errors.h"

namespace facet::gltf_detail {

namespace {

size_t component_count(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;  // matrices: never a vertex attribute we read
    }
}

}  // namespace

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
    if (accessor.sparse.isSparse) fail(name + " is sparse, which is not supported");
    if (!in_range(accessor.bufferView, model.bufferViews.size()))
        fail(name + ": bufferView " + std::to_string(accessor.bufferView) + " missing or out of range");
    size_t element = component_size(accessor.componentType) * component_count(accessor.type);
    if (element == 0) fail(name + " has an unsupported type or component type");
    if (accessor.count > kMaxElements)
        fail(name + ": count " + std::to_string(accessor.count) + " exceeds the limit of " + std::to_string(kMaxElements));

    const tinygltf::BufferView& view = model.bufferViews[size_t(accessor.bufferView)];
    size_t stride = view.byteStride != 0 ? view.byteStride : element;
    if (stride < element) fail(name + ": byteStride " + std::to_string(stride) + " is less than its element size");
    // count <= 2^28 and stride <= 252, so this cannot overflow.
    uint64_t span = accessor.count == 0 ? 0 : uint64_t(stride) * (accessor.count - 1) + element;
    if (accessor.byteOffset > view.byteLength || span > view.byteLength - accessor.byteOffset)
        fail(name + " (offset " + std::to_string(accessor.byteOffset) + ", stride " + std::to_string(stride) +
             ", count " + std::to_string(accessor.count) + ") exceeds its bufferView " +
             std::to_string(accessor.bufferView) + " (" + std::to_string(view.byteLength) + " bytes)");

    AccessorData data;
    data.base = model.buffers[size_t(view.buffer)].data.data() + view.byteOffset + accessor.byteOffset;
    data.stride = stride;
    data.count = accessor.count;
    data.component_type = accessor.componentType;
    data.type = accessor.type;
    data.normalized = accessor.normalized;
    return data;
}

}  // namespace facet::gltf_detail
