#pragma once
// Writes glTF files whose mesh is compressed with EXT_meshopt_compression or
// KHR_draco_mesh_compression (and holds a WebP for EXT_texture_webp), from geometry the caller makes, with the libraries' own
// encoders: the compression tests and the load-cost measurement (compressed_mesh_tool).
// Header-only; link meshoptimizer::meshoptimizer and draco::draco.
#include <meshoptimizer.h>

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace facet::test {

// An indexed triangle mesh: 3 floats a position and a normal, 2 a uv.
struct TestGeometry {
    std::vector<float> positions, normals, uvs;
    std::vector<uint32_t> indices;
    size_t vertex_count() const { return positions.size() / 3; }
};

// A wavy (nx+1) x (ny+1) grid of 2 nx ny triangles over [0,1]^2 in XY, every vertex
// distinct, normals from the surface's derivative.
inline TestGeometry wavy_grid(uint32_t nx, uint32_t ny) {
    TestGeometry g;
    for (uint32_t j = 0; j <= ny; ++j)
        for (uint32_t i = 0; i <= nx; ++i) {
            const float u = float(i) / float(nx), v = float(j) / float(ny);
            const float z = 0.1f * std::sin(6.0f * u) * std::cos(4.0f * v);
            const float dzdu = 0.6f * std::cos(6.0f * u) * std::cos(4.0f * v);
            const float dzdv = -0.4f * std::sin(6.0f * u) * std::sin(4.0f * v);
            const float len = std::sqrt(dzdu * dzdu + dzdv * dzdv + 1.0f);
            g.positions.insert(g.positions.end(), {u, v, z});
            g.normals.insert(g.normals.end(), {-dzdu / len, -dzdv / len, 1.0f / len});
            g.uvs.insert(g.uvs.end(), {u, 1.0f - v});
        }
    for (uint32_t j = 0; j < ny; ++j)
        for (uint32_t i = 0; i < nx; ++i) {
            const uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
            g.indices.insert(g.indices.end(), {a, b, d, a, d, c});
        }
    return g;
}

inline void write_bytes(const std::filesystem::path& path, const void* data, size_t size) {
    std::ofstream out(path, std::ios::binary);
    out.write(static_cast<const char*>(data), std::streamsize(size));
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

inline std::string min_max(const std::vector<float>& values, size_t components) {
    std::vector<float> lo(components, INFINITY), hi(components, -INFINITY);
    for (size_t i = 0; i < values.size(); ++i) {
        lo[i % components] = std::min(lo[i % components], values[i]);
        hi[i % components] = std::max(hi[i % components], values[i]);
    }
    std::string text = "\"min\": [";
    for (size_t c = 0; c < components; ++c) text += (c ? ", " : "") + std::to_string(lo[c]);
    text += "], \"max\": [";
    for (size_t c = 0; c < components; ++c) text += (c ? ", " : "") + std::to_string(hi[c]);
    return text + "]";
}

// A .glb: its JSON chunk (padded with spaces) and BIN chunk (padded with zeros).
inline void write_glb(const std::filesystem::path& path, std::string json, std::vector<uint8_t> bin) {
    while (json.size() % 4) json.push_back(' ');
    while (bin.size() % 4) bin.push_back(0);
    std::vector<uint8_t> out;
    auto u32 = [&](uint32_t v) { out.insert(out.end(), reinterpret_cast<uint8_t*>(&v), reinterpret_cast<uint8_t*>(&v) + 4); };
    u32(0x46546C67u);  // "glTF"
    u32(2);
    u32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
    u32(uint32_t(json.size()));
    u32(0x4E4F534Au);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    u32(uint32_t(bin.size()));
    u32(0x004E4942u);  // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
    write_bytes(path, out.data(), out.size());
}

// The rest of a one-mesh, one-node file: POSITION accessor 0, NORMAL 1, TEXCOORD_0 2,
// indices 3; `primitive_extra` goes inside the primitive.
inline std::string mesh_and_node(const std::string& primitive_extra) {
    return R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
        "indices": 3)" + primitive_extra + R"(}]}],
  "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0)";
}

// The same mesh uncompressed (the reference the compressed files are compared with).
inline void write_plain_gltf(const std::filesystem::path& gltf_path, const TestGeometry& g) {
    std::vector<uint8_t> bin;
    std::string views;
    auto add = [&](const void* data, size_t bytes) {
        const size_t at = bin.size();
        bin.insert(bin.end(), static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + bytes);
        views += std::string(views.empty() ? "" : ", ") + "{\"buffer\": 0, \"byteOffset\": " + std::to_string(at) +
                 ", \"byteLength\": " + std::to_string(bytes) + "}";
    };
    add(g.positions.data(), g.positions.size() * 4);
    add(g.normals.data(), g.normals.size() * 4);
    add(g.uvs.data(), g.uvs.size() * 4);
    add(g.indices.data(), g.indices.size() * 4);
    const std::string bin_name = gltf_path.stem().string() + ".bin";
    write_bytes(gltf_path.parent_path() / bin_name, bin.data(), bin.size());
    const std::string n = std::to_string(g.vertex_count());
    const std::string json =
        "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"buffers\": [{\"uri\": \"" + bin_name + "\", \"byteLength\": " +
        std::to_string(bin.size()) + "}],\n  \"bufferViews\": [" + views + "],\n  \"accessors\": [\n" +
        "    {\"bufferView\": 0, \"componentType\": 5126, \"count\": " + n + ", \"type\": \"VEC3\", " +
        min_max(g.positions, 3) + "},\n    {\"bufferView\": 1, \"componentType\": 5126, \"count\": " + n +
        ", \"type\": \"VEC3\"},\n    {\"bufferView\": 2, \"componentType\": 5126, \"count\": " + n +
        ", \"type\": \"VEC2\"},\n    {\"bufferView\": 3, \"componentType\": 5125, \"count\": " +
        std::to_string(g.indices.size()) + ", \"type\": \"SCALAR\"}],\n  " + mesh_and_node("") + "\n}\n";
    write_bytes(gltf_path, json.data(), json.size());
}

struct MeshoptOptions {
    // How the index stream is coded: TRIANGLES (meshopt_encodeIndexBuffer) or INDICES
    // (meshopt_encodeIndexSequence).
    bool index_sequence = false;
    // Positions through the EXPONENTIAL filter (24-bit mantissa) before coding.
    bool exponential_positions = false;
    bool required = true;  // in extensionsRequired, else only used
};

// Writes `gltf_path` (.gltf with its .bin beside it, or .glb) holding the compressed
// streams; the fallback buffer has no uri, as gltfpack writes it.
inline void write_meshopt_gltf(const std::filesystem::path& gltf_path, const TestGeometry& g,
                               const MeshoptOptions& options = {}) {
    const size_t n = g.vertex_count();
    std::vector<uint8_t> bin;
    std::string views;
    uint64_t fallback_offset = 0;
    auto add = [&](const void* data, size_t count, size_t stride, const char* mode, const char* filter, bool attribute) {
        std::vector<uint8_t> encoded;
        if (attribute) {
            encoded.resize(meshopt_encodeVertexBufferBound(count, stride));
            encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, count, stride));
        } else if (std::string(mode) == "TRIANGLES") {
            encoded.resize(meshopt_encodeIndexBufferBound(count, n));
            encoded.resize(meshopt_encodeIndexBuffer(encoded.data(), encoded.size(),
                                                     static_cast<const unsigned*>(data), count));
        } else {
            encoded.resize(meshopt_encodeIndexSequenceBound(count, n));
            encoded.resize(meshopt_encodeIndexSequence(encoded.data(), encoded.size(),
                                                       static_cast<const unsigned*>(data), count));
        }
        while (bin.size() % 4) bin.push_back(0);
        const size_t at = bin.size();
        bin.insert(bin.end(), encoded.begin(), encoded.end());
        if (!views.empty()) views += ",\n    ";
        views += "{\"buffer\": 1, \"byteOffset\": " + std::to_string(fallback_offset) +
                 ", \"byteLength\": " + std::to_string(count * stride) +
                 (attribute ? ", \"byteStride\": " + std::to_string(stride) : std::string()) +
                 ", \"extensions\": {\"EXT_meshopt_compression\": {\"buffer\": 0, \"byteOffset\": " +
                 std::to_string(at) + ", \"byteLength\": " + std::to_string(encoded.size()) +
                 ", \"byteStride\": " + std::to_string(stride) + ", \"count\": " + std::to_string(count) +
                 ", \"mode\": \"" + mode + "\"" + (filter ? std::string(", \"filter\": \"") + filter + "\"" : "") +
                 "}}}";
        fallback_offset += count * stride;
    };
    std::vector<float> positions = g.positions;
    if (options.exponential_positions) {
        std::vector<uint32_t> coded(positions.size());
        meshopt_encodeFilterExp(coded.data(), n, 12, 24, positions.data());
        add(coded.data(), n, 12, "ATTRIBUTES", "EXPONENTIAL", true);
    } else {
        add(positions.data(), n, 12, "ATTRIBUTES", nullptr, true);
    }
    add(g.normals.data(), n, 12, "ATTRIBUTES", nullptr, true);
    add(g.uvs.data(), n, 8, "ATTRIBUTES", nullptr, true);
    add(g.indices.data(), g.indices.size(), 4, options.index_sequence ? "INDICES" : "TRIANGLES", nullptr, false);

    const bool glb = gltf_path.extension() == ".glb";  // else .gltf with its .bin beside it
    const std::string bin_name = gltf_path.stem().string() + ".bin";
    if (!glb) write_bytes(gltf_path.parent_path() / bin_name, bin.data(), bin.size());
    const std::string ext = "[\"EXT_meshopt_compression\"]";
    std::string json = "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"extensionsUsed\": " + ext + ",\n";
    if (options.required) json += "  \"extensionsRequired\": " + ext + ",\n";
    json += "  \"buffers\": [{" + (glb ? std::string() : "\"uri\": \"" + bin_name + "\", ") +
            "\"byteLength\": " + std::to_string(bin.size()) + "},\n    {\"byteLength\": " + std::to_string(fallback_offset) +
            ", \"extensions\": {\"EXT_meshopt_compression\": {\"fallback\": true}}}],\n";
    json += "  \"bufferViews\": [\n    " + views + "],\n";
    json += "  \"accessors\": [\n"
            "    {\"bufferView\": 0, \"componentType\": 5126, \"count\": " + std::to_string(n) +
            ", \"type\": \"VEC3\", " + min_max(g.positions, 3) + "},\n"
            "    {\"bufferView\": 1, \"componentType\": 5126, \"count\": " + std::to_string(n) + ", \"type\": \"VEC3\"},\n"
            "    {\"bufferView\": 2, \"componentType\": 5126, \"count\": " + std::to_string(n) + ", \"type\": \"VEC2\"},\n"
            "    {\"bufferView\": 3, \"componentType\": 5125, \"count\": " + std::to_string(g.indices.size()) +
            ", \"type\": \"SCALAR\"}],\n  " + mesh_and_node("") + "\n}\n";
    if (glb) write_glb(gltf_path, json, bin);
    else write_bytes(gltf_path, json.data(), json.size());
}

struct DracoOptions {
    int position_bits = 14, normal_bits = 10, uv_bits = 12;
    int speed = 5;  // Draco's 0 (best compression) .. 10 (fastest)
};

// The Draco stream of `g` and the unique ids of its POSITION, NORMAL and TEXCOORD_0.
struct DracoStream {
    std::vector<uint8_t> bytes;
    uint32_t position_id = 0, normal_id = 0, uv_id = 0;
};

inline DracoStream encode_draco(const TestGeometry& g, const DracoOptions& options) {
    draco::Mesh mesh;
    const size_t n = g.vertex_count();
    mesh.set_num_points(uint32_t(n));
    auto add = [&](draco::GeometryAttribute::Type type, const std::vector<float>& values, int components) {
        draco::GeometryAttribute attribute;
        attribute.Init(type, nullptr, uint8_t(components), draco::DT_FLOAT32, false, sizeof(float) * components, 0);
        const int id = mesh.AddAttribute(attribute, true, uint32_t(n));
        for (size_t i = 0; i < n; ++i)
            mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)), &values[i * components]);
        return mesh.attribute(id)->unique_id();
    };
    DracoStream out;
    out.position_id = add(draco::GeometryAttribute::POSITION, g.positions, 3);
    out.normal_id = add(draco::GeometryAttribute::NORMAL, g.normals, 3);
    out.uv_id = add(draco::GeometryAttribute::TEX_COORD, g.uvs, 2);
    for (size_t t = 0; t + 2 < g.indices.size(); t += 3)
        mesh.AddFace({draco::PointIndex(g.indices[t]), draco::PointIndex(g.indices[t + 1]),
                      draco::PointIndex(g.indices[t + 2])});
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, options.position_bits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, options.normal_bits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, options.uv_bits);
    encoder.SetSpeedOptions(options.speed, options.speed);
    draco::EncoderBuffer buffer;
    const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
    if (!status.ok()) throw std::runtime_error("draco encoding failed: " + status.error_msg_string());
    out.bytes.assign(buffer.data(), buffer.data() + buffer.size());
    return out;
}

// Writes `gltf_path` (.gltf with its .bin beside it, or .glb) holding the Draco stream of
// `g` (required; the accessors have no bufferView, as the extension allows).
inline void write_draco_gltf(const std::filesystem::path& gltf_path, const TestGeometry& g,
                             const DracoOptions& options = {}) {
    const DracoStream stream = encode_draco(g, options);
    const bool glb = gltf_path.extension() == ".glb";  // else .gltf with its .bin beside it
    const std::string bin_name = gltf_path.stem().string() + ".bin";
    if (!glb) write_bytes(gltf_path.parent_path() / bin_name, stream.bytes.data(), stream.bytes.size());
    const std::string n = std::to_string(g.vertex_count());
    const std::string ext = "[\"KHR_draco_mesh_compression\"]";
    std::string json = "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"extensionsUsed\": " + ext +
                       ",\n  \"extensionsRequired\": " + ext + ",\n";
    json += "  \"buffers\": [{" + (glb ? std::string() : "\"uri\": \"" + bin_name + "\", ") +
            "\"byteLength\": " + std::to_string(stream.bytes.size()) +
            "}],\n  \"bufferViews\": [{\"buffer\": 0, \"byteLength\": " + std::to_string(stream.bytes.size()) + "}],\n";
    json += "  \"accessors\": [\n"
            "    {\"componentType\": 5126, \"count\": " + n + ", \"type\": \"VEC3\", " + min_max(g.positions, 3) + "},\n"
            "    {\"componentType\": 5126, \"count\": " + n + ", \"type\": \"VEC3\"},\n"
            "    {\"componentType\": 5126, \"count\": " + n + ", \"type\": \"VEC2\"},\n"
            "    {\"componentType\": 5125, \"count\": " + std::to_string(g.indices.size()) +
            ", \"type\": \"SCALAR\"}],\n  ";
    json += mesh_and_node(", \"extensions\": {\"KHR_draco_mesh_compression\": {\"bufferView\": 0, "
                          "\"attributes\": {\"POSITION\": " + std::to_string(stream.position_id) +
                          ", \"NORMAL\": " + std::to_string(stream.normal_id) +
                          ", \"TEXCOORD_0\": " + std::to_string(stream.uv_id) + "}}}");
    json += "\n}\n";
    if (glb) write_glb(gltf_path, json, stream.bytes);
    else write_bytes(gltf_path, json.data(), json.size());
}

// EXT_texture_webp's test image (the extension and fuzz tests).
// A 3x2 lossless WebP made once with libwebp 1.2.4 (WebPEncodeLosslessRGBA; OpenImageIO
// 2.4's WebP writer mangles colours, so it cannot make one here) holding kWebpTexels.
inline const uint8_t kWebp[84] = {
    0x52, 0x49, 0x46, 0x46, 0x4c, 0x00, 0x00, 0x00, 0x57, 0x45, 0x42, 0x50, 0x56, 0x50, 0x38, 0x4c, 0x3f,
    0x00, 0x00, 0x00, 0x2f, 0x02, 0x40, 0x00, 0x10, 0x2f, 0x40, 0x20, 0x69, 0x33, 0xd6, 0x61, 0x85, 0xdf,
    0xfb, 0x3d, 0xc8, 0xa4, 0x6d, 0x4a, 0xcf, 0xf9, 0xd7, 0x33, 0x6b, 0x55, 0xd0, 0x80, 0x00, 0xe3, 0xf4,
    0x10, 0x47, 0xff, 0x42, 0x86, 0x40, 0xd2, 0x66, 0xd5, 0x96, 0x6c, 0x3c, 0xf9, 0x03, 0x7e, 0x22, 0x6a,
    0xde, 0xd6, 0xd2, 0x5e, 0x21, 0x20, 0x21, 0x53, 0xf2, 0xc8, 0x17, 0x11, 0xfd, 0x8f, 0x58, 0x00};
// Straight (not premultiplied) RGBA, rows top first.
inline const std::vector<uint8_t> kWebpTexels = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 255,
                                          10, 20, 30, 255, 200, 150, 100, 64, 1, 2, 3, 255};

}  // namespace facet::test
