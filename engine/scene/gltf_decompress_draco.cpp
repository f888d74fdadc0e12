#include "scene/gltf_decompress_draco.h"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "scene/gltf_accessors.h"
#include "scene/gltf_decompress.h"
#include "scene/gltf_errors.h"

namespace facet::gltf_detail {

namespace {

constexpr const char* kDracoExtension = "KHR_draco_mesh_compression";

size_t components_of(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
    }
}

// Every point's value of `attribute`, converted by Draco to T (it scales normalized
// integers as glTF does), packed as the accessor's elements.
template <class T>
bool write_points(const draco::Mesh& mesh, const draco::PointAttribute& attribute, size_t components,
                  std::vector<uint8_t>& out) {
    T value[4];
    uint8_t* at = out.data();
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
        if (!attribute.ConvertValue<T>(attribute.mapped_index(p), int8_t(components), value)) return false;
        std::memcpy(at, value, components * sizeof(T));
        at += components * sizeof(T);
    }
    return true;
}

bool convert_points(const draco::Mesh& mesh, const draco::PointAttribute& attribute, int component_type,
                    size_t components, std::vector<uint8_t>& out) {
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return write_points<int8_t>(mesh, attribute, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return write_points<uint8_t>(mesh, attribute, components, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return write_points<int16_t>(mesh, attribute, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return write_points<uint16_t>(mesh, attribute, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return write_points<uint32_t>(mesh, attribute, components, out);
    default: return write_points<float>(mesh, attribute, components, out);
    }
}

template <class T>
void write_indices(const draco::Mesh& mesh, std::vector<uint8_t>& out) {
    T* at = reinterpret_cast<T*>(out.data());  // a fresh vector: aligned for any T
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
        for (int corner = 0; corner < 3; ++corner) *at++ = T(mesh.face(f)[corner].value());
}

std::unique_ptr<draco::Mesh> decode_mesh(std::span<const uint8_t> bytes, const std::string& where) {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
        fail(where + ": the compressed stream does not decode (" + std::to_string(bytes.size()) +
             " bytes; libdraco: " + decoded.status().error_msg_string() + ")");
    std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) fail(where + ": the compressed stream holds no mesh");
    if (mesh->num_points() > kMaxElements || uint64_t(mesh->num_faces()) * 3 > kMaxElements)
        fail(where + ": " + std::to_string(mesh->num_points()) + " points and " + std::to_string(mesh->num_faces()) +
             " faces exceed the limit of " + std::to_string(kMaxElements) + " elements");
    return mesh;
}

// The accessor `index` pointed at a new view holding `bytes`.
void rebind(tinygltf::Model& model, int index, std::vector<uint8_t> bytes) {
    const int view = add_buffer_view(model, std::move(bytes), 0);
    tinygltf::Accessor& accessor = model.accessors[size_t(index)];
    accessor.bufferView = view;
    accessor.byteOffset = 0;
}

struct Decoding {
    std::set<int> done;  // accessors already decoded (primitives may share them)
    DecodedBudget budget;
};

void decode_attribute(tinygltf::Model& model, const draco::Mesh& mesh, const std::string& semantic,
                      int accessor_index, uint64_t unique_id, Decoding& state, const std::string& where) {
    const std::string name = where + ": " + semantic;
    if (!in_range(accessor_index, model.accessors.size())) fail(name + ": accessor out of range");
    if (state.done.count(accessor_index)) return;
    const tinygltf::Accessor& accessor = model.accessors[size_t(accessor_index)];
    const draco::PointAttribute* attribute =
        unique_id <= std::numeric_limits<uint32_t>::max() ? mesh.GetAttributeByUniqueId(uint32_t(unique_id)) : nullptr;
    if (!attribute) fail(name + ": the stream has no attribute " + std::to_string(unique_id));
    const size_t components = components_of(accessor.type);
    const size_t component_bytes = component_size(accessor.componentType);
    if (components == 0 || component_bytes == 0) fail(name + ": accessor has a type Draco cannot fill");
    if (attribute->num_components() != components)
        fail(name + ": the stream's attribute has " + std::to_string(attribute->num_components()) +
             " components, the accessor " + std::to_string(components));
    if (accessor.count != mesh.num_points())
        fail(name + ": accessor count " + std::to_string(accessor.count) + " but the stream decodes " +
             std::to_string(mesh.num_points()) + " points");
    const uint64_t size = uint64_t(mesh.num_points()) * components * component_bytes;
    state.budget.take(size, name);
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    if (!convert_points(mesh, *attribute, accessor.componentType, components, bytes))
        fail(name + ": the stream's values do not convert to the accessor's component type");
    rebind(model, accessor_index, std::move(bytes));
    state.done.insert(accessor_index);
}

void decode_indices(tinygltf::Model& model, tinygltf::Primitive& primitive, const draco::Mesh& mesh,
                    Decoding& state, const std::string& where) {
    const uint64_t count = uint64_t(mesh.num_faces()) * 3;
    if (primitive.indices < 0) {  // a non-indexed primitive: the faces still order the points
        tinygltf::Accessor accessor;
        accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        accessor.type = TINYGLTF_TYPE_SCALAR;
        accessor.count = size_t(count);
        model.accessors.push_back(std::move(accessor));
        primitive.indices = int(model.accessors.size() - 1);
    }
    const std::string name = where + ": indices";
    if (!in_range(primitive.indices, model.accessors.size())) fail(name + ": accessor out of range");
    if (state.done.count(primitive.indices)) return;
    const tinygltf::Accessor& accessor = model.accessors[size_t(primitive.indices)];
    if (accessor.count != count)
        fail(name + ": accessor count " + std::to_string(accessor.count) + " but the stream decodes " +
             std::to_string(mesh.num_faces()) + " triangles");
    uint64_t largest = 0;
    switch (accessor.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: largest = 0xff; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: largest = 0xffff; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: largest = 0xffffffff; break;
    default: fail(name + ": component type " + std::to_string(accessor.componentType) + " is not an index type");
    }
    if (mesh.num_points() > 0 && mesh.num_points() - 1 > largest)
        fail(name + ": " + std::to_string(mesh.num_points()) + " points do not fit the accessor's component type");
    const uint64_t size = count * component_size(accessor.componentType);
    state.budget.take(size, name);
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    if (largest == 0xff) write_indices<uint8_t>(mesh, bytes);
    else if (largest == 0xffff) write_indices<uint16_t>(mesh, bytes);
    else write_indices<uint32_t>(mesh, bytes);
    rebind(model, primitive.indices, std::move(bytes));
    state.done.insert(primitive.indices);
}

void decode_primitive(tinygltf::Model& model, size_t m, size_t p, Decoding& state) {
    const std::string where = label("mesh", m, model.meshes[m].name) + " primitive " + std::to_string(p) + " (" +
                              kDracoExtension + ")";
    const tinygltf::Value* ext = extension_object(model.meshes[m].primitives[p].extensions, kDracoExtension, where);
    if (!ext) return;
    const uint64_t view_index = field_uint(*ext, "bufferView", where);
    if (view_index >= model.bufferViews.size())
        fail(where + ": bufferView " + std::to_string(view_index) + " out of range");
    const tinygltf::BufferView& view = model.bufferViews[size_t(view_index)];
    if (view.buffer < 0) fail(where + ": bufferView " + std::to_string(view_index) + " has no buffer");
    const std::unique_ptr<draco::Mesh> mesh =
        decode_mesh(buffer_range(model, uint64_t(view.buffer), view.byteOffset, view.byteLength, where), where);
    const tinygltf::Value& attributes = ext->Get("attributes");
    if (!attributes.IsObject()) fail(where + ": attributes is missing or not an object");
    for (const std::string& semantic : attributes.Keys()) {
        const tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
        auto it = primitive.attributes.find(semantic);
        if (it == primitive.attributes.end()) fail(where + ": " + semantic + " is not an attribute of the primitive");
        decode_attribute(model, *mesh, semantic, it->second, field_uint(attributes, semantic.c_str(), where), state,
                         where);
    }
    tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
    decode_indices(model, primitive, *mesh, state, where);
    // The faces are a triangle list whatever the primitive said (a strip is decoded to one).
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.extensions.erase(kDracoExtension);
}

}  // namespace

void decompress_draco(tinygltf::Model& model) {
    Decoding state;
    for (size_t m = 0; m < model.meshes.size(); ++m)
        for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) decode_primitive(model, m, p, state);
}

}  // namespace facet::gltf_detail
