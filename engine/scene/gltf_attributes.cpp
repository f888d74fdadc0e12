#include "scene/gltf_attributes.h"

#include <cmath>
#include <optional>
#include <string_view>

#include "scene/gltf_accessors.h"
#include "scene/gltf_errors.h"

namespace facet::gltf_detail {

namespace {

constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE, kUbyte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
              kShort = TINYGLTF_COMPONENT_TYPE_SHORT, kUshort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
              kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;

// Which accessor forms each attribute may take (glTF 2.0 section 3.7.2.1, widened by
// KHR_mesh_quantization for positions, normals, tangents and texture coordinates).
struct Allowed {
    std::vector<int> types;  // TINYGLTF_TYPE_*
    bool float_ok = true;
    std::vector<int> normalized;    // integer component types allowed when normalized
    std::vector<int> unnormalized;  // integer component types allowed when not
    const char* text;
};

Allowed allowed_for(std::string_view semantic, bool target) {
    if (semantic == "POSITION")
        return target ? Allowed{{TINYGLTF_TYPE_VEC3}, true, {kByte, kShort}, {kByte, kShort}, "VEC3 FLOAT, BYTE or SHORT"}
                      : Allowed{{TINYGLTF_TYPE_VEC3}, true, {kByte, kUbyte, kShort, kUshort},
                                {kByte, kUbyte, kShort, kUshort}, "VEC3 FLOAT, (UNSIGNED_)BYTE or (UNSIGNED_)SHORT"};
    if (semantic == "NORMAL")
        return {{TINYGLTF_TYPE_VEC3}, true, {kByte, kShort}, {}, "VEC3 FLOAT or normalized BYTE/SHORT"};
    if (semantic == "TANGENT")
        return {{target ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4}, true, {kByte, kShort}, {},
                target ? "VEC3 FLOAT or normalized BYTE/SHORT" : "VEC4 FLOAT or normalized BYTE/SHORT"};
    if (semantic.rfind("TEXCOORD_", 0) == 0)
        return {{TINYGLTF_TYPE_VEC2}, true, {kByte, kUbyte, kShort, kUshort}, {kByte, kUbyte, kShort, kUshort},
                "VEC2 FLOAT, (UNSIGNED_)BYTE or (UNSIGNED_)SHORT"};
    if (semantic.rfind("COLOR_", 0) == 0)
        return {{TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, true, {kUbyte, kUshort}, {},
                "VEC3/VEC4 FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT"};
    if (semantic.rfind("JOINTS_", 0) == 0)
        return {{TINYGLTF_TYPE_VEC4}, false, {}, {kUbyte, kUshort}, "VEC4 UNSIGNED_BYTE or UNSIGNED_SHORT"};
    // WEIGHTS_n
    return {{TINYGLTF_TYPE_VEC4}, true, {kUbyte, kUshort}, {}, "VEC4 FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT"};
}

bool contains(const std::vector<int>& list, int value) {
    for (int v : list)
        if (v == value) return true;
    return false;
}

// The accessor of attribute `semantic` in `attributes`, checked for its form and for
// having `count` elements; nullopt when absent.
std::optional<AccessorData> attribute(const tinygltf::Model& model, const std::map<std::string, int>& attributes,
                                      const std::string& semantic, const std::string& where, size_t count,
                                      bool target = false) {
    auto it = attributes.find(semantic);
    if (it == attributes.end()) return std::nullopt;
    AccessorData data = accessor_data(model, it->second, where + " " + semantic);
    const Allowed allowed = allowed_for(semantic, target);
    const bool integer_ok = data.normalized ? contains(allowed.normalized, data.component_type)
                                            : contains(allowed.unnormalized, data.component_type);
    const bool ok = contains(allowed.types, data.type) &&
                    (data.component_type == kFloat ? allowed.float_ok && !data.normalized : integer_ok);
    if (!ok) fail(where + ": " + semantic + " must be " + allowed.text);
    if (count != SIZE_MAX && data.count != count)
        fail(where + ": " + semantic + " has " + std::to_string(data.count) + " elements, POSITION has " +
             std::to_string(count));
    return data;
}

glm::vec3 vec3_at(const AccessorData& d, size_t i) { return {component(d, i, 0), component(d, i, 1), component(d, i, 2)}; }

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::vector<glm::vec3> read_vec3s(const AccessorData& d, const std::string& where, const std::string& what) {
    std::vector<glm::vec3> out(d.count);
    for (size_t i = 0; i < d.count; ++i) {
        out[i] = vec3_at(d, i);
        if (!finite(out[i])) fail(where + ": " + what + " " + std::to_string(i) + " is not finite");
    }
    return out;
}

// Targets x vertices a primitive may displace: far beyond real assets (100 targets of
// 160,000 vertices), and bounds what sparse targets on zeros, cheap in a file, can cost
// (12 bytes per attribute each).
constexpr uint64_t kMaxMorphedVertices = uint64_t(1) << 24;

void read_targets(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                  size_t count, PrimitiveDeform& deform) {
    for (size_t t = 0; t < primitive.targets.size(); ++t) {
        const std::string at = where + " morph target " + std::to_string(t);
        MorphTarget target;
        for (const auto& [semantic, accessor] : primitive.targets[t]) {
            (void)accessor;
            auto data = attribute(model, primitive.targets[t], semantic, at, count, true);
            if (semantic == "POSITION") target.position = read_vec3s(*data, at, "POSITION");
            else if (semantic == "NORMAL") target.normal = read_vec3s(*data, at, "NORMAL");
            else if (semantic == "TANGENT") target.tangent = read_vec3s(*data, at, "TANGENT");
            // Other attributes (TEXCOORD_n, COLOR_n) may be morphed too; no viewer we
            // compare with does, and neither do we.
        }
        deform.targets.push_back(std::move(target));
    }
}

void read_influences(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                     size_t count, PrimitiveDeform& deform) {
    for (int set = 0;; ++set) {
        const std::string n = std::to_string(set);
        auto joints = attribute(model, primitive.attributes, "JOINTS_" + n, where, count);
        auto weights = attribute(model, primitive.attributes, "WEIGHTS_" + n, where, count);
        if (!joints && !weights) break;
        if (!joints || !weights) fail(where + ": JOINTS_" + n + " and WEIGHTS_" + n + " must come together");
        Influences in;
        in.joints.resize(count);
        in.weights.resize(count);
        for (size_t i = 0; i < count; ++i)
            for (int c = 0; c < 4; ++c) {
                in.joints[i][size_t(c)] = uint16_t(component(*joints, i, size_t(c)));
                in.weights[i][c] = component(*weights, i, size_t(c));
                if (!std::isfinite(in.weights[i][c]))
                    fail(where + ": WEIGHTS_" + n + " of vertex " + std::to_string(i) + " is not finite");
            }
        deform.influences.push_back(std::move(in));
    }
}

}  // namespace

PrimitiveVertices read_vertices(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                const std::string& where) {
    auto positions = attribute(model, primitive.attributes, "POSITION", where, SIZE_MAX);
    if (!positions) fail(where + ": no POSITION attribute");
    const size_t count = positions->count;
    if (count == 0) fail(where + ": no vertices");
    if (uint64_t(primitive.targets.size()) * count > kMaxMorphedVertices)
        fail(where + ": " + std::to_string(primitive.targets.size()) + " morph targets of " + std::to_string(count) +
             " vertices exceed the limit of " + std::to_string(kMaxMorphedVertices) + " morphed vertices");
    auto normals = attribute(model, primitive.attributes, "NORMAL", where, count);
    auto tangents = attribute(model, primitive.attributes, "TANGENT", where, count);
    auto uv0 = attribute(model, primitive.attributes, "TEXCOORD_0", where, count);
    auto uv1 = attribute(model, primitive.attributes, "TEXCOORD_1", where, count);
    auto colors = attribute(model, primitive.attributes, "COLOR_0", where, count);

    PrimitiveVertices out;
    out.has_normals = normals.has_value();
    out.has_tangents = tangents.has_value();
    out.vertices.resize(count);
    auto uv_at = [&](const AccessorData& d, size_t i, const char* name) {
        glm::vec2 uv(component(d, i, 0), component(d, i, 1));
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
            fail(where + ": vertex " + std::to_string(i) + " " + name + " is not finite");
        return uv;
    };
    for (size_t i = 0; i < count; ++i) {
        Vertex& v = out.vertices[i];
        v.position = vec3_at(*positions, i);
        if (!finite(v.position)) fail(where + ": vertex " + std::to_string(i) + " position is not finite");
        if (normals) {
            glm::vec3 n = vec3_at(*normals, i);
            float length = glm::length(n);
            // Exporters round normals; shading and tangent generation expect unit length.
            if (length > 1e-20f && std::isfinite(length)) v.normal = n / length;
        }
        if (uv0) v.uv = uv_at(*uv0, i, "TEXCOORD_0");
        if (uv1) v.uv1 = uv_at(*uv1, i, "TEXCOORD_1");
        if (tangents) {
            v.tangent = glm::vec4(vec3_at(*tangents, i), component(*tangents, i, 3) < 0.0f ? -1.0f : 1.0f);
            if (!finite(glm::vec3(v.tangent))) fail(where + ": vertex " + std::to_string(i) + " TANGENT is not finite");
        }
        if (colors) {
            for (size_t c = 0; c < 3; ++c) v.color[int(c)] = component(*colors, i, c);
            v.color.a = colors->type == TINYGLTF_TYPE_VEC4 ? component(*colors, i, 3) : 1.0f;
            if (!finite(glm::vec3(v.color)) || !std::isfinite(v.color.a))
                fail(where + ": vertex " + std::to_string(i) + " COLOR_0 is not finite");
        }
    }
    read_influences(model, primitive, where, count, out.deform);
    read_targets(model, primitive, where, count, out.deform);
    return out;
}

}  // namespace facet::gltf_detail
