#include "scene/gltf_loader.h"

// Debian's libtinygltf is a compiled library: include the declarations only.
#include <tiny_gltf.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string_view>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/hash.h"
#include "scene/tangents.h"

namespace facet {

namespace {

namespace fs = std::filesystem;

// Far beyond any real asset: refusing such counts up front keeps a forged file from
// turning into a multi-gigabyte allocation.
constexpr uint64_t kMaxElements = uint64_t(1) << 28;
constexpr uint64_t kMaxFileBytes = uint64_t(INT_MAX);  // tinygltf takes 32-bit sizes

// Checks throw this and load_gltf turns it into Error{"<path>: <reason>"}, which keeps
// each of the many checks below to one line.
struct LoadError {
    std::string reason;
};

[[noreturn]] void fail(std::string reason) { throw LoadError{std::move(reason)}; }

std::string label(const char* kind, size_t index, const std::string& name) {
    if (name.empty()) return std::string(kind) + " " + std::to_string(index);
    return std::string(kind) + " '" + name + "'";
}

bool in_range(int index, size_t size) { return index >= 0 && size_t(index) < size; }

std::string trim(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    return text;
}

// ---------------------------------------------------------------- file and parse

std::vector<uint8_t> read_file(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) fail("file not found");
    if (!fs::is_regular_file(path, ec)) fail("not a regular file");
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) fail("cannot open file");
    std::streamoff size = in.tellg();
    if (size < 0) fail("cannot read file");
    if (uint64_t(size) > kMaxFileBytes) fail("file is larger than 2 GiB");
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    in.seekg(0);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) fail("cannot read file");
    return bytes;
}

bool is_glb(const std::string& path, const std::vector<uint8_t>& bytes) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext == ".glb" || (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0);
}

uint32_t read_u32(const uint8_t* p) {
    uint32_t value;
    std::memcpy(&value, p, 4);  // GLB is little-endian, as are the hosts we build for
    return value;
}

// tinygltf checks the chunks too, but says "Invalid glTF binary." for everything.
void check_glb_header(const std::vector<uint8_t>& bytes) {
    if (bytes.size() < 20) fail("truncated .glb: " + std::to_string(bytes.size()) + " bytes, less than its header");
    if (read_u32(&bytes[4]) != 2) fail(".glb version " + std::to_string(read_u32(&bytes[4])) + " is not 2");
    uint32_t length = read_u32(&bytes[8]);
    if (length > bytes.size())
        fail("truncated .glb: its header says " + std::to_string(length) + " bytes, the file has " +
             std::to_string(bytes.size()));
    if (20 + uint64_t(read_u32(&bytes[12])) > length) fail("truncated .glb: the JSON chunk runs past the end");
}

// tinygltf decodes images while it parses, before anything is validated, and for an
// image in a bufferView it would read the view without checking it against its
// buffer. So this callback only keeps the encoded bytes of uri images (a vector
// tinygltf owns, so safe to read); decoding happens after validation.
using EncodedImages = std::map<int, std::vector<uint8_t>>;

bool keep_encoded_image(tinygltf::Image* image, int index, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void* user) {
    if (image->bufferView >= 0 || size < 0) return true;
    (*static_cast<EncodedImages*>(user))[index].assign(bytes, bytes + size);
    return true;
}

tinygltf::Model parse(const std::string& path, const std::vector<uint8_t>& bytes, EncodedImages& encoded) {
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keep_encoded_image, &encoded);
    std::string err, warn;
    std::string base_dir = fs::path(path).parent_path().string();
    bool ok = false;
    try {
        if (is_glb(path, bytes)) {
            check_glb_header(bytes);
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir);
        } else {
            ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                            unsigned(bytes.size()), base_dir);
        }
    } catch (const std::exception& e) {  // the JSON library may throw past tinygltf
        ok = false;
        err = e.what();
    }
    if (!ok) fail("glTF parse failed: " + trim(err.empty() ? warn : err));
    return model;
}

// ---------------------------------------------------------------- accessors

struct AccessorData {
    const uint8_t* base = nullptr;  // element 0
    size_t stride = 0;
    size_t count = 0;
    int component_type = 0;
    int type = 0;  // TINYGLTF_TYPE_*
    bool normalized = false;
};

size_t component_size(int component_type) {
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

size_t component_count(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;  // matrices: never a vertex attribute we read
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

template <class T>
T load(const uint8_t* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));  // accessors need not be aligned for the host
    return value;
}

// Component c of element i as a float, applying glTF's normalisation rules.
float component(const AccessorData& data, size_t i, size_t c) {
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

uint32_t index_at(const AccessorData& data, size_t i) {
    const uint8_t* p = data.base + i * data.stride;
    switch (data.component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<uint16_t>(p);
    default: return load<uint32_t>(p);
    }
}

bool is_float(const AccessorData& data, int type) {
    return data.type == type && data.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
}

// ---------------------------------------------------------------- meshes

// The accessor of a vertex attribute, checked for type and for matching POSITION's count.
std::optional<AccessorData> attribute(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                      const char* semantic, const std::string& where, size_t vertex_count) {
    auto it = primitive.attributes.find(semantic);
    if (it == primitive.attributes.end()) return std::nullopt;
    AccessorData data = accessor_data(model, it->second, where + " " + semantic);
    bool type_ok = false;
    std::string expected;
    if (std::string_view(semantic) == "POSITION" || std::string_view(semantic) == "NORMAL") {
        type_ok = is_float(data, TINYGLTF_TYPE_VEC3);
        expected = "VEC3 FLOAT";
    } else if (std::string_view(semantic) == "TANGENT") {
        type_ok = is_float(data, TINYGLTF_TYPE_VEC4);
        expected = "VEC4 FLOAT";
    } else {  // TEXCOORD_0
        bool unorm = data.normalized && (data.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                         data.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
        type_ok = data.type == TINYGLTF_TYPE_VEC2 && (data.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT || unorm);
        expected = "VEC2 FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT";
    }
    if (!type_ok) fail(where + ": " + semantic + " must be " + expected);
    if (vertex_count != SIZE_MAX && data.count != vertex_count)
        fail(where + ": " + semantic + " has " + std::to_string(data.count) + " elements, POSITION has " +
             std::to_string(vertex_count));
    return data;
}

// Raw indices (or 0..n-1) turned into a triangle list per the primitive's mode.
std::vector<uint32_t> triangle_indices(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                       const std::string& where, size_t vertex_count) {
    int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
        mode == TINYGLTF_MODE_LINE_STRIP)
        fail(where + ": points and lines (mode " + std::to_string(mode) + ") are not supported");
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
        fail(where + ": unknown primitive mode " + std::to_string(mode));

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

    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (raw.size() % 3 != 0)
            fail(where + ": " + std::to_string(raw.size()) + " indices is not a multiple of 3");
        return raw;
    }
    std::vector<uint32_t> list;
    if (raw.size() < 3) return list;
    if (3 * uint64_t(raw.size() - 2) > kMaxElements) fail(where + ": too many triangles");
    list.reserve(3 * (raw.size() - 2));
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

void load_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                    bool& needs_default_material, Scene& scene) {
    uint32_t default_material = uint32_t(model.materials.size());
    if (primitive.material != -1 && !in_range(primitive.material, model.materials.size()))
        fail(where + ": material " + std::to_string(primitive.material) + " out of range (" +
             std::to_string(model.materials.size()) + " materials)");
    uint32_t material = primitive.material >= 0 ? uint32_t(primitive.material) : default_material;
    needs_default_material |= primitive.material < 0;

    auto positions = attribute(model, primitive, "POSITION", where, SIZE_MAX);
    if (!positions) fail(where + ": no POSITION attribute");
    size_t count = positions->count;
    if (count == 0) fail(where + ": no vertices");
    if (scene.vertices.size() + count > kMaxElements)
        fail(where + ": the scene exceeds " + std::to_string(kMaxElements) + " vertices");
    auto normals = attribute(model, primitive, "NORMAL", where, count);
    auto uvs = attribute(model, primitive, "TEXCOORD_0", where, count);
    auto tangents = attribute(model, primitive, "TANGENT", where, count);

    std::vector<Vertex> vertices(count);
    for (size_t i = 0; i < count; ++i) {
        Vertex& v = vertices[i];
        v.position = {component(*positions, i, 0), component(*positions, i, 1), component(*positions, i, 2)};
        if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) || !std::isfinite(v.position.z))
            fail(where + ": vertex " + std::to_string(i) + " position is not finite");
        if (normals) {
            glm::vec3 n(component(*normals, i, 0), component(*normals, i, 1), component(*normals, i, 2));
            float length = glm::length(n);
            // Exporters round normals; shading and tangent generation expect unit length.
            if (length > 1e-20f && std::isfinite(length)) v.normal = n / length;
        }
        if (uvs) v.uv = {component(*uvs, i, 0), component(*uvs, i, 1)};
        if (tangents)
            v.tangent = {component(*tangents, i, 0), component(*tangents, i, 1), component(*tangents, i, 2),
                         component(*tangents, i, 3) < 0.0f ? -1.0f : 1.0f};
    }

    std::vector<uint32_t> indices = triangle_indices(model, primitive, where, count);
    if (scene.indices.size() + indices.size() > kMaxElements)
        fail(where + ": the scene exceeds " + std::to_string(kMaxElements) + " indices");
    if (!normals) generate_normals(vertices, indices);
    bool has_normal_map = material < scene.materials.size() && scene.materials[material].normal_texture.valid();
    if (!tangents && has_normal_map) generate_tangents(vertices, indices);

    Primitive out;
    out.first_index = uint32_t(scene.indices.size());
    out.index_count = uint32_t(indices.size());
    out.vertex_offset = uint32_t(scene.vertices.size());
    out.vertex_count = uint32_t(count);
    out.material = material;
    out.bounds_min = out.bounds_max = vertices[0].position;
    for (const Vertex& v : vertices) {
        out.bounds_min = glm::min(out.bounds_min, v.position);
        out.bounds_max = glm::max(out.bounds_max, v.position);
    }
    scene.vertices.insert(scene.vertices.end(), vertices.begin(), vertices.end());
    scene.indices.insert(scene.indices.end(), indices.begin(), indices.end());
    scene.primitives.push_back(out);
}

// ---------------------------------------------------------------- materials, samplers, images

TextureRef texture_ref(const tinygltf::Model& model, int texture, int tex_coord, const std::string& where,
                       const char* slot) {
    TextureRef ref;
    if (texture == -1) return ref;
    std::string name = where + ": " + slot;
    if (!in_range(texture, model.textures.size()))
        fail(name + " texture " + std::to_string(texture) + " out of range (" + std::to_string(model.textures.size()) +
             " textures)");
    if (tex_coord != 0)
        fail(name + " uses TEXCOORD_" + std::to_string(tex_coord) + "; only TEXCOORD_0 is supported");
    const tinygltf::Texture& t = model.textures[size_t(texture)];
    if (!in_range(t.source, model.images.size()))
        fail(name + ": texture " + std::to_string(texture) + " image " + std::to_string(t.source) + " out of range");
    if (t.sampler != -1 && !in_range(t.sampler, model.samplers.size()))
        fail(name + ": texture " + std::to_string(texture) + " sampler " + std::to_string(t.sampler) + " out of range");
    ref.image = t.source;
    ref.sampler = t.sampler;
    return ref;
}

Material convert_material(const tinygltf::Model& model, size_t index) {
    const tinygltf::Material& m = model.materials[index];
    std::string where = label("material", index, m.name);
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    Material out;
    out.name = m.name;
    if (pbr.baseColorFactor.size() != 4) fail(where + ": baseColorFactor must have 4 numbers");
    out.base_color = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2],
                               pbr.baseColorFactor[3]);
    out.metallic = float(pbr.metallicFactor);
    out.roughness = float(pbr.roughnessFactor);
    if (m.emissiveFactor.size() == 3) {
        out.emissive = glm::vec3(m.emissiveFactor[0], m.emissiveFactor[1], m.emissiveFactor[2]);
    } else if (!m.emissiveFactor.empty()) {
        fail(where + ": emissiveFactor must have 3 numbers");
    }
    auto strength = m.extensions.find("KHR_materials_emissive_strength");
    if (strength != m.extensions.end() && strength->second.IsObject()) {
        const tinygltf::Value& value = strength->second.Get("emissiveStrength");
        if (value.IsNumber()) out.emissive *= float(value.GetNumberAsDouble());
    }
    out.normal_scale = float(m.normalTexture.scale);
    out.occlusion_strength = float(m.occlusionTexture.strength);
    if (m.alphaMode == "OPAQUE") {
        out.alpha_mode = AlphaMode::opaque;
    } else if (m.alphaMode == "MASK") {
        out.alpha_mode = AlphaMode::mask;
    } else if (m.alphaMode == "BLEND") {
        out.alpha_mode = AlphaMode::blend;
    } else {
        fail(where + ": unknown alphaMode '" + m.alphaMode + "'");
    }
    out.alpha_cutoff = float(m.alphaCutoff);
    out.double_sided = m.doubleSided;
    out.base_color_texture =
        texture_ref(model, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, where, "baseColorTexture");
    out.metallic_roughness_texture = texture_ref(model, pbr.metallicRoughnessTexture.index,
                                                 pbr.metallicRoughnessTexture.texCoord, where, "metallicRoughnessTexture");
    out.normal_texture = texture_ref(model, m.normalTexture.index, m.normalTexture.texCoord, where, "normalTexture");
    out.occlusion_texture =
        texture_ref(model, m.occlusionTexture.index, m.occlusionTexture.texCoord, where, "occlusionTexture");
    out.emissive_texture =
        texture_ref(model, m.emissiveTexture.index, m.emissiveTexture.texCoord, where, "emissiveTexture");
    return out;
}

uint32_t wrap_mode(int gl_wrap, const std::string& where) {
    switch (gl_wrap) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return 0;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return 1;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return 2;
    default: fail(where + ": unknown wrap mode " + std::to_string(gl_wrap));
    }
}

TextureSampler convert_sampler(const tinygltf::Sampler& s, size_t index) {
    std::string where = label("sampler", index, s.name);
    TextureSampler out;
    if (s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) {
        out.mag_linear = false;
    } else if (s.magFilter != -1 && s.magFilter != TINYGLTF_TEXTURE_FILTER_LINEAR) {
        fail(where + ": unknown magFilter " + std::to_string(s.magFilter));
    }
    switch (s.minFilter) {
    case -1: break;  // unspecified: the renderer's choice, trilinear
    case TINYGLTF_TEXTURE_FILTER_NEAREST: out.min_linear = false; out.use_mips = false; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR: out.use_mips = false; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: out.min_linear = false; out.mip_linear = false; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: out.mip_linear = false; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: out.min_linear = false; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: break;
    default: fail(where + ": unknown minFilter " + std::to_string(s.minFilter));
    }
    out.wrap_u = wrap_mode(s.wrapS, where);
    out.wrap_v = wrap_mode(s.wrapT, where);
    return out;
}

std::string image_name(const tinygltf::Image& image, size_t index) {
    if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) return fs::path(image.uri).filename().string();
    if (!image.name.empty()) return image.name;
    return "image " + std::to_string(index);
}

TextureImage decode_image(const tinygltf::Model& model, size_t index, const EncodedImages& encoded) {
    const tinygltf::Image& image = model.images[index];
    TextureImage out;
    out.name = image_name(image, index);
    std::string where = "image '" + out.name + "'";
    const uint8_t* bytes = nullptr;
    size_t size = 0;
    if (image.bufferView >= 0) {
        if (!in_range(image.bufferView, model.bufferViews.size()))
            fail(where + ": bufferView " + std::to_string(image.bufferView) + " out of range");
        const tinygltf::BufferView& view = model.bufferViews[size_t(image.bufferView)];  // validated
        bytes = model.buffers[size_t(view.buffer)].data.data() + view.byteOffset;
        size = view.byteLength;
    } else if (auto it = encoded.find(int(index)); it != encoded.end()) {
        bytes = it->second.data();
        size = it->second.size();
    } else {
        fail(where + ": cannot read '" + image.uri + "'");
    }
    if (size == 0 || size > size_t(INT_MAX)) fail(where + " could not be decoded: it is empty or too large");

    // tinygltf's stb_image decoder; with no options it expands every image to 4 channels.
    tinygltf::Image decoded;
    std::string err, warn;
    if (!tinygltf::LoadImageData(&decoded, int(index), &err, &warn, 0, 0, bytes, int(size), nullptr))
        fail(where + " could not be decoded (PNG or JPEG expected)");
    size_t channels = size_t(decoded.component);
    size_t bytes_per_channel = decoded.bits == 16 ? 2 : 1;
    size_t pixels = size_t(decoded.width) * size_t(decoded.height);
    if (decoded.width <= 0 || decoded.height <= 0 || channels < 1 || channels > 4 ||
        (decoded.bits != 8 && decoded.bits != 16) || decoded.image.size() != pixels * channels * bytes_per_channel)
        fail(where + " could not be decoded: unexpected decoder output");
    out.width = uint32_t(decoded.width);
    out.height = uint32_t(decoded.height);
    out.rgba.resize(pixels * 4);
    for (size_t p = 0; p < pixels; ++p) {
        uint8_t texel[4] = {0, 0, 0, 255};
        for (size_t c = 0; c < channels; ++c) {
            size_t at = (p * channels + c) * bytes_per_channel;
            texel[c] = bytes_per_channel == 2 ? uint8_t((load<uint16_t>(&decoded.image[at]) * 255u + 32767u) / 65535u)
                                              : decoded.image[at];
        }
        // Grey (and grey + alpha) images replicate their value into RGB.
        if (channels <= 2) {
            if (channels == 2) texel[3] = texel[1];
            texel[1] = texel[2] = texel[0];
        }
        std::memcpy(&out.rgba[p * 4], texel, 4);
    }
    return out;
}

// ---------------------------------------------------------------- nodes

glm::mat4 local_matrix(const tinygltf::Node& node, const std::string& where) {
    auto finite = [](const std::vector<double>& values) {
        return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
    };
    if (!finite(node.matrix) || !finite(node.translation) || !finite(node.rotation) || !finite(node.scale))
        fail(where + ": transform is not finite");
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) fail(where + ": matrix must have 16 numbers");
        glm::mat4 m;
        for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = float(node.matrix[size_t(i)]);  // both column-major
        return m;
    }
    glm::mat4 m(1.0f);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3) fail(where + ": translation must have 3 numbers");
        m = glm::translate(m, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) fail(where + ": rotation must have 4 numbers");
        glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]));
        float length = glm::length(q);
        if (!(length > 1e-6f)) fail(where + ": rotation is not a unit quaternion");
        m *= glm::mat4_cast(q / length);  // exporters write rounded quaternions
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3) fail(where + ": scale must have 3 numbers");
        m = glm::scale(m, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    }
    return m;
}

// Children in range, one parent each and no cycles; returns each node's parent (-1 for roots).
std::vector<int> check_hierarchy(const tinygltf::Model& model) {
    size_t n = model.nodes.size();
    std::vector<int> parent(n, -1);
    for (size_t i = 0; i < n; ++i) {
        for (int child : model.nodes[i].children) {
            std::string where = label("node", i, model.nodes[i].name);
            if (!in_range(child, n)) fail(where + ": child " + std::to_string(child) + " out of range");
            if (parent[size_t(child)] != -1)
                fail(label("node", size_t(child), model.nodes[size_t(child)].name) + " has more than one parent");
            parent[size_t(child)] = int(i);
        }
    }
    // With one parent each, a cycle is a loop of parent links: walk up from every node,
    // stopping at nodes already known to reach a root.
    enum : uint8_t { unseen, on_path, reaches_root };
    std::vector<uint8_t> state(n, unseen);
    std::vector<size_t> path;
    for (size_t start = 0; start < n; ++start) {
        path.clear();
        int at = int(start);
        while (at != -1 && state[size_t(at)] == unseen) {
            state[size_t(at)] = on_path;
            path.push_back(size_t(at));
            at = parent[size_t(at)];
        }
        if (at != -1 && state[size_t(at)] == on_path)
            fail("node hierarchy has a cycle through " + label("node", size_t(at), model.nodes[size_t(at)].name));
        for (size_t p : path) state[p] = reaches_root;
    }
    return parent;
}

glm::vec3 translation_of(const glm::mat4& world) { return glm::vec3(world[3]); }

glm::vec3 world_direction(const glm::mat4& world, glm::vec3 local, const std::string& where) {
    glm::vec3 d = glm::mat3(world) * local;
    float length = glm::length(d);
    if (!(length > 1e-20f) || !std::isfinite(length)) fail(where + ": degenerate world transform");
    return d / length;
}

Camera convert_camera(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world,
                      const std::string& where) {
    int index = node.camera;
    if (!in_range(index, model.cameras.size())) fail(where + ": camera " + std::to_string(index) + " out of range");
    const tinygltf::Camera& c = model.cameras[size_t(index)];
    Camera out;
    out.name = !c.name.empty() ? c.name : !node.name.empty() ? node.name : where;
    if (c.type == "perspective") {
        if (!(c.perspective.yfov > 0.0) || !(c.perspective.znear > 0.0))
            fail(where + ": perspective camera needs positive yfov and znear");
        out.yfov = float(c.perspective.yfov);
        out.znear = float(c.perspective.znear);
        out.zfar = float(c.perspective.zfar);
    } else if (c.type == "orthographic") {
        out.orthographic = true;
        out.ymag = float(c.orthographic.ymag);
        out.znear = float(c.orthographic.znear);
        out.zfar = float(c.orthographic.zfar);
    } else {
        fail(where + ": unknown camera type '" + c.type + "'");
    }
    out.position = translation_of(world);
    out.target = out.position + world_direction(world, {0, 0, -1}, where);
    out.up = world_direction(world, {0, 1, 0}, where);
    return out;
}

std::optional<Light> node_light(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world,
                                const std::string& where) {
    auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return std::nullopt;
    const tinygltf::Value& index_value = ext->second.IsObject() ? ext->second.Get("light") : tinygltf::Value();
    if (!index_value.IsNumber()) fail(where + ": KHR_lights_punctual without a light index");
    int index = index_value.GetNumberAsInt();
    if (!in_range(index, model.lights.size())) fail(where + ": light " + std::to_string(index) + " out of range");
    const tinygltf::Light& l = model.lights[size_t(index)];
    Light out;
    if (l.type == "directional") {
        out.type = LightType::directional;
    } else if (l.type == "point") {
        out.type = LightType::point;
    } else if (l.type == "spot") {
        out.type = LightType::spot;
    } else {
        fail(where + ": unknown light type '" + l.type + "'");
    }
    if (l.color.size() == 3) {
        out.color = glm::vec3(l.color[0], l.color[1], l.color[2]);
    } else if (!l.color.empty()) {
        fail(where + ": light color must have 3 numbers");
    }
    out.intensity = float(l.intensity);
    out.range = float(l.range);
    out.inner_cone = float(l.spot.innerConeAngle);
    out.outer_cone = float(l.spot.outerConeAngle);
    out.position = translation_of(world);
    out.direction = world_direction(world, {0, 0, -1}, where);
    return out;
}

void place_nodes(const tinygltf::Model& model, Scene& scene) {
    std::vector<int> parent = check_hierarchy(model);
    std::vector<int> roots;
    if (model.defaultScene != -1 || !model.scenes.empty()) {
        int chosen = model.defaultScene != -1 ? model.defaultScene : 0;
        if (!in_range(chosen, model.scenes.size())) fail("scene " + std::to_string(chosen) + " out of range");
        roots = model.scenes[size_t(chosen)].nodes;
        for (int root : roots) {
            if (!in_range(root, model.nodes.size()))
                fail("scene " + std::to_string(chosen) + ": node " + std::to_string(root) + " out of range");
            if (parent[size_t(root)] != -1)
                fail("scene " + std::to_string(chosen) + ": " +
                     label("node", size_t(root), model.nodes[size_t(root)].name) + " is not a root node");
        }
    } else {
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (parent[i] == -1) roots.push_back(int(i));
    }

    // Iterative, so that a deep (hostile) hierarchy cannot overflow the call stack.
    std::vector<std::pair<int, glm::mat4>> stack;
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) stack.emplace_back(*root, glm::mat4(1.0f));
    while (!stack.empty()) {
        auto [index, parent_world] = stack.back();
        stack.pop_back();
        const tinygltf::Node& node = model.nodes[size_t(index)];
        std::string where = label("node", size_t(index), node.name);
        glm::mat4 world = parent_world * local_matrix(node, where);
        if (node.mesh != -1) {
            if (!in_range(node.mesh, scene.meshes.size()))
                fail(where + ": mesh " + std::to_string(node.mesh) + " out of range");
            for (uint32_t primitive : scene.meshes[size_t(node.mesh)].primitives)
                scene.instances.push_back({primitive, world, node.name.empty() ? where : node.name});
        }
        if (node.camera != -1) scene.cameras.push_back(convert_camera(model, node, world, where));
        if (auto light = node_light(model, node, world, where)) scene.lights.push_back(*light);
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
            stack.emplace_back(*child, world);
    }
}

Scene convert(const tinygltf::Model& model) {
    // A required extension changes what the data means (compressed meshes, quantised
    // attributes, other image formats): loading on without it would draw garbage.
    for (const std::string& extension : model.extensionsRequired)
        if (extension != "KHR_lights_punctual" && extension != "KHR_materials_emissive_strength")
            fail("requires unsupported extension " + extension);
    Scene scene;
    validate_buffer_views(model);
    for (size_t i = 0; i < model.samplers.size(); ++i) scene.samplers.push_back(convert_sampler(model.samplers[i], i));
    for (size_t i = 0; i < model.materials.size(); ++i) scene.materials.push_back(convert_material(model, i));

    bool needs_default_material = false;
    for (size_t m = 0; m < model.meshes.size(); ++m) {
        const tinygltf::Mesh& mesh = model.meshes[m];
        Mesh out;
        out.name = mesh.name;
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            std::string where = label("mesh", m, mesh.name) + " primitive " + std::to_string(p);
            load_primitive(model, mesh.primitives[p], where, needs_default_material, scene);
            out.primitives.push_back(uint32_t(scene.primitives.size() - 1));
        }
        scene.meshes.push_back(std::move(out));
    }
    if (needs_default_material) {
        Material fallback;  // glTF's defaults: white, metallic 1, roughness 1
        fallback.name = "default";
        scene.materials.push_back(fallback);
    }
    place_nodes(model, scene);
    return scene;
}

}  // namespace

Result<Scene> load_gltf(const std::string& path) {
    try {
        std::vector<uint8_t> bytes = read_file(path);
        EncodedImages encoded;
        tinygltf::Model model = parse(path, bytes, encoded);
        Scene scene = convert(model);
        // Images last: the cheap structural checks above fail faster on broken files.
        for (size_t i = 0; i < model.images.size(); ++i) scene.images.push_back(decode_image(model, i, encoded));

        Hash64 hash;
        hash.add(bytes.data(), bytes.size());
        for (const tinygltf::Buffer& buffer : model.buffers) hash.add(buffer.data.data(), buffer.data.size());
        for (const TextureImage& image : scene.images) hash.add(image.rgba.data(), image.rgba.size());
        scene.content_hash = hash.hex();
        scene.source = path;
        return scene;
    } catch (const LoadError& e) {
        return Error{path + ": " + e.reason};
    } catch (const std::bad_alloc&) {
        return Error{path + ": out of memory"};
    }
}

}  // namespace facet
