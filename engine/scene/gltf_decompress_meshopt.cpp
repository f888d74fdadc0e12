#include "scene/gltf_decompress_meshopt.h"

#include <meshoptimizer.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "scene/gltf_decompress.h"
#include "scene/gltf_errors.h"

namespace facet::gltf_detail {

namespace {

constexpr const char* kMeshoptExtension = "EXT_meshopt_compression";

enum class Mode { attributes, triangles, indices };
enum class Filter { none, octahedral, quaternion, exponential };

struct Stream {
    std::span<const uint8_t> source;
    uint64_t count = 0;
    uint64_t stride = 0;
    Mode mode = Mode::attributes;
    Filter filter = Filter::none;
};

Mode parse_mode(const std::string& text, const std::string& where) {
    if (text == "ATTRIBUTES") return Mode::attributes;
    if (text == "TRIANGLES") return Mode::triangles;
    if (text == "INDICES") return Mode::indices;
    fail(where + ": unknown mode '" + text + "' (ATTRIBUTES, TRIANGLES or INDICES)");
}

Filter parse_filter(const std::string& text, const std::string& where) {
    if (text == "NONE") return Filter::none;
    if (text == "OCTAHEDRAL") return Filter::octahedral;
    if (text == "QUATERNION") return Filter::quaternion;
    if (text == "EXPONENTIAL") return Filter::exponential;
    fail(where + ": unknown filter '" + text + "' (NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL)");
}

// The extension's rules on stride, count and filter, checked before libmeshoptimizer
// sees them: its decoders only assert them.
void check_stream(const Stream& s, const std::string& where) {
    const std::string stride = "byteStride " + std::to_string(s.stride);
    if (s.count > kMaxElements)
        fail(where + ": count " + std::to_string(s.count) + " exceeds the limit of " + std::to_string(kMaxElements));
    if (s.mode == Mode::attributes) {
        if (s.stride == 0 || s.stride % 4 != 0 || s.stride > 256)
            fail(where + ": " + stride + " must be a multiple of 4 from 4 to 256 for ATTRIBUTES");
    } else {
        if (s.stride != 2 && s.stride != 4) fail(where + ": " + stride + " must be 2 or 4 for " +
                                                  (s.mode == Mode::triangles ? "TRIANGLES" : "INDICES"));
        if (s.mode == Mode::triangles && s.count % 3 != 0)
            fail(where + ": count " + std::to_string(s.count) + " is not a multiple of 3 for TRIANGLES");
        if (s.filter != Filter::none) fail(where + ": a filter is allowed with ATTRIBUTES only");
    }
    if (s.filter == Filter::octahedral && s.stride != 4 && s.stride != 8)
        fail(where + ": OCTAHEDRAL needs byteStride 4 or 8, not " + std::to_string(s.stride));
    if (s.filter == Filter::quaternion && s.stride != 8)
        fail(where + ": QUATERNION needs byteStride 8, not " + std::to_string(s.stride));
    // No stream of the codec is denser than 64 decoded bytes per encoded byte (a vertex
    // block spends at least 2 header bits per 16 bytes of a channel; an index takes at
    // least a byte): a larger claim is a forged count, refused before allocating for it.
    const uint64_t decoded = s.count * s.stride;
    if (decoded > uint64_t(s.source.size()) * 64 + 4096)
        fail(where + ": count " + std::to_string(s.count) + " x " + stride + " is more than " +
             std::to_string(s.source.size()) + " compressed bytes can hold");
}

std::vector<uint8_t> decode(const Stream& s, const std::string& where) {
    std::vector<uint8_t> out(size_t(s.count * s.stride));
    int rc = 0;
    switch (s.mode) {
    case Mode::attributes:
        rc = meshopt_decodeVertexBuffer(out.data(), size_t(s.count), size_t(s.stride), s.source.data(), s.source.size());
        break;
    case Mode::triangles:
        rc = meshopt_decodeIndexBuffer(out.data(), size_t(s.count), size_t(s.stride), s.source.data(), s.source.size());
        break;
    case Mode::indices:
        rc = meshopt_decodeIndexSequence(out.data(), size_t(s.count), size_t(s.stride), s.source.data(),
                                         s.source.size());
        break;
    }
    if (rc != 0)
        fail(where + ": the compressed stream is corrupt (" + std::to_string(s.source.size()) +
             " bytes; libmeshoptimizer's decoder returned " + std::to_string(rc) + ")");
    switch (s.filter) {
    case Filter::none: break;
    case Filter::octahedral: meshopt_decodeFilterOct(out.data(), size_t(s.count), size_t(s.stride)); break;
    case Filter::quaternion: meshopt_decodeFilterQuat(out.data(), size_t(s.count), size_t(s.stride)); break;
    case Filter::exponential: meshopt_decodeFilterExp(out.data(), size_t(s.count), size_t(s.stride)); break;
    }
    return out;
}

}  // namespace

void decompress_meshopt(tinygltf::Model& model) {
    DecodedBudget budget;
    for (size_t i = 0; i < model.bufferViews.size(); ++i) {
        const std::string where = "bufferView " + std::to_string(i) + " (" + kMeshoptExtension + ")";
        const tinygltf::Value* ext = extension_object(model.bufferViews[i].extensions, kMeshoptExtension, where);
        if (!ext) continue;
        Stream s;
        s.source = buffer_range(model, field_uint(*ext, "buffer", where), field_uint(*ext, "byteOffset", where, 0),
                                field_uint(*ext, "byteLength", where), where);
        s.count = field_uint(*ext, "count", where);
        s.stride = field_uint(*ext, "byteStride", where);
        s.mode = parse_mode(field_string(*ext, "mode", where, ""), where);
        s.filter = parse_filter(field_string(*ext, "filter", where, "NONE"), where);
        check_stream(s, where);
        // The view describes the decoded bytes; it may not reach past them.
        const uint64_t view_bytes = model.bufferViews[i].byteLength;
        if (view_bytes > s.count * s.stride)
            fail(where + ": byteLength " + std::to_string(view_bytes) + " is more than the " +
                 std::to_string(s.count * s.stride) + " bytes it decodes to (count x byteStride)");
        budget.take(s.count * s.stride, where);
        std::vector<uint8_t> bytes = decode(s, where);
        tinygltf::Buffer decoded;
        decoded.data = std::move(bytes);
        model.buffers.push_back(std::move(decoded));
        tinygltf::BufferView& view = model.bufferViews[i];
        view.buffer = int(model.buffers.size() - 1);
        view.byteOffset = 0;
        view.extensions.erase(kMeshoptExtension);
    }
}

}  // namespace facet::gltf_detail
