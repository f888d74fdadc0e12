#include "scene/gltf_topology.h"

#include "scene/gltf_accessors.h"
#include "scene/gltf_errors.h"

namespace facet::gltf_detail {

namespace {

int mode_or_default(int mode) { return mode < 0 ? TINYGLTF_MODE_TRIANGLES : mode; }

}  // namespace

Topology topology_of(int mode, const std::string& where) {
    switch (mode_or_default(mode)) {
    case TINYGLTF_MODE_POINTS: return Topology::points;
    case TINYGLTF_MODE_LINE:
    case TINYGLTF_MODE_LINE_LOOP:
    case TINYGLTF_MODE_LINE_STRIP: return Topology::lines;
    case TINYGLTF_MODE_TRIANGLES:
    case TINYGLTF_MODE_TRIANGLE_STRIP:
    case TINYGLTF_MODE_TRIANGLE_FAN: return Topology::triangles;
    default: fail(where + ": unknown primitive mode " + std::to_string(mode));
    }
}

uint64_t list_index_count(int mode, uint64_t raw) {
    switch (mode_or_default(mode)) {
    case TINYGLTF_MODE_LINE_STRIP: return raw >= 2 ? 2 * (raw - 1) : 0;
    case TINYGLTF_MODE_LINE_LOOP: return raw >= 2 ? 2 * raw : 0;
    case TINYGLTF_MODE_TRIANGLE_STRIP:
    case TINYGLTF_MODE_TRIANGLE_FAN: return raw >= 3 ? 3 * (raw - 2) : 0;
    default: return raw;
    }
}

std::vector<uint32_t> list_indices(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                   const std::string& where, size_t vertex_count) {
    const int mode = mode_or_default(primitive.mode);
    topology_of(mode, where);  // an unknown mode fails before any index is read

    std::vector<uint32_t> raw;
    if (primitive.indices >= 0) {
        AccessorData data = accessor_data(model, primitive.indices, where + " indices");
        bool unsigned_int = data.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                            data.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                            data.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        if (data.type != TINYGLTF_TYPE_SCALAR || !unsigned_int || data.normalized)
            fail(where + ": indices must be SCALAR UNSIGNED_BYTE/UNSIGNED_SHORT/UNSIGNED_INT");
        raw.resize(data.count);
        for (size_t i = 0; i < data.count; ++i) {
            raw[i] = index_at(data, i);
            if (raw[i] >= vertex_count)
                fail(where + ": index " + std::to_string(raw[i]) + " >= vertex count " + std::to_string(vertex_count));
        }
    } else {
        raw.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) raw[i] = uint32_t(i);
    }

    auto multiple_of = [&](size_t n) {
        if (raw.size() % n != 0)
            fail(where + ": " + std::to_string(raw.size()) + " indices is not a multiple of " + std::to_string(n));
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) multiple_of(3);
    if (mode == TINYGLTF_MODE_LINE) multiple_of(2);
    if (mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_POINTS) return raw;

    const uint64_t listed = list_index_count(mode, raw.size());
    if (listed > kMaxElements) fail(where + ": too many primitives");
    std::vector<uint32_t> list;
    list.reserve(size_t(listed));
    if (mode == TINYGLTF_MODE_LINE_STRIP || mode == TINYGLTF_MODE_LINE_LOOP) {
        if (raw.size() < 2) return list;
        for (size_t i = 0; i + 1 < raw.size(); ++i) list.insert(list.end(), {raw[i], raw[i + 1]});
        if (mode == TINYGLTF_MODE_LINE_LOOP) list.insert(list.end(), {raw.back(), raw.front()});
        return list;
    }
    if (raw.size() < 3) return list;
    for (size_t i = 0; i + 2 < raw.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            // Every other strip triangle swaps two corners to keep the winding.
            bool odd = i % 2 == 1;
            list.insert(list.end(), {raw[i], raw[odd ? i + 2 : i + 1], raw[odd ? i + 1 : i + 2]});
        } else {
            list.insert(list.end(), {raw[i + 1], raw[i + 2], raw[0]});
        }
    }
    return list;
}

}  // namespace facet::gltf_detail
