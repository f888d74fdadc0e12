#pragma once
// Large glTF inputs generated at test time, written piece by piece so the test itself
// stays small in memory: a grid GLB of millions of triangles, a textured quad whose
// texture is a PNG written row by row, and files that only declare huge sizes.
#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace facet::test {

inline void put_u32(std::ofstream& out, uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); }

// A flat grid in the XY plane facing +Z, `cells` x `cells` quads: (cells + 1)^2 vertices
// with normals and 2 * cells^2 triangles of uint32 indices, in one .glb.
inline bool write_grid_glb(const std::string& path, uint32_t cells) {
    const uint64_t n = uint64_t(cells + 1) * (cells + 1), triangles = 2ull * cells * cells;
    const uint64_t vec3_bytes = n * 12, index_bytes = triangles * 12;
    const uint64_t bin = 2 * vec3_bytes + index_bytes;
    std::string json = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":)" + std::to_string(bin) +
                       R"(}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" + std::to_string(vec3_bytes) +
                       R"(},{"buffer":0,"byteOffset":)" + std::to_string(vec3_bytes) + R"(,"byteLength":)" +
                       std::to_string(vec3_bytes) + R"(},{"buffer":0,"byteOffset":)" + std::to_string(2 * vec3_bytes) +
                       R"(,"byteLength":)" + std::to_string(index_bytes) +
                       R"(}],"accessors":[{"bufferView":0,"componentType":5126,"count":)" + std::to_string(n) +
                       R"(,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},{"bufferView":1,"componentType":5126,"count":)" +
                       std::to_string(n) + R"(,"type":"VEC3"},{"bufferView":2,"componentType":5125,"count":)" +
                       std::to_string(triangles * 3) +
                       R"(,"type":"SCALAR"}],"meshes":[{"name":"grid","primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"indices":2}]}],)"
                       R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
    while (json.size() % 4) json += ' ';
    std::ofstream out(path, std::ios::binary);
    out.write("glTF", 4);
    put_u32(out, 2);
    put_u32(out, uint32_t(12 + 8 + json.size() + 8 + bin));
    put_u32(out, uint32_t(json.size()));
    out.write("JSON", 4);
    out.write(json.data(), std::streamsize(json.size()));
    put_u32(out, uint32_t(bin));
    out.write("BIN\0", 4);
    std::vector<float> row(size_t(cells + 1) * 3);
    for (uint32_t y = 0; y <= cells; ++y) {
        for (uint32_t x = 0; x <= cells; ++x) {
            row[x * 3] = 2.0f * x / cells - 1.0f;
            row[x * 3 + 1] = 2.0f * y / cells - 1.0f;
            row[x * 3 + 2] = 0.0f;
        }
        out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * 4));
    }
    for (uint32_t x = 0; x <= cells; ++x) row[x * 3] = 0.0f, row[x * 3 + 1] = 0.0f, row[x * 3 + 2] = 1.0f;
    for (uint32_t y = 0; y <= cells; ++y) out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * 4));
    std::vector<uint32_t> quads(size_t(cells) * 6);
    for (uint32_t y = 0; y < cells; ++y) {
        for (uint32_t x = 0; x < cells; ++x) {
            const uint32_t a = y * (cells + 1) + x, b = a + 1, c = a + cells + 1, d = c + 1;
            const uint32_t q[6] = {a, b, d, a, d, c};
            std::memcpy(&quads[size_t(x) * 6], q, sizeof q);
        }
        out.write(reinterpret_cast<const char*>(quads.data()), std::streamsize(quads.size() * 4));
    }
    return bool(out);
}

// A PNG written a row at a time: `row(y, rgb)` fills width * 3 bytes.
inline bool write_png_rows(const std::string& path, uint32_t width, uint32_t height,
                           const std::function<void(uint32_t, std::vector<uint8_t>&)>& row) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return false;
    OIIO::ImageSpec spec(int(width), int(height), 3, OIIO::TypeDesc::UINT8);
    spec.attribute("png:compressionLevel", 1);  // fast: the test's time, not its disk, is scarce
    if (!out->open(path, spec)) return false;
    std::vector<uint8_t> rgb(size_t(width) * 3);
    for (uint32_t y = 0; y < height; ++y) {
        row(y, rgb);
        if (!out->write_scanline(int(y), 0, OIIO::TypeDesc::UINT8, rgb.data())) return false;
    }
    return out->close();
}

// A glTF quad (two triangles, uv 0..1) whose material's base colour texture is `image`
// (a file name beside it). The quad faces +Z, uv (0,0) at its top left.
inline void write_textured_quad(const std::string& path, const std::string& bin_name, const std::string& image) {
    const float vertices[4][5] = {{-1, 1, 0, 0, 0}, {1, 1, 0, 1, 0}, {1, -1, 0, 1, 1}, {-1, -1, 0, 0, 1}};
    const uint16_t indices[6] = {0, 3, 2, 0, 2, 1};
    std::ofstream bin(std::string(path.substr(0, path.find_last_of('/') + 1)) + bin_name, std::ios::binary);
    for (const auto& v : vertices) bin.write(reinterpret_cast<const char*>(v), 12);
    for (const auto& v : vertices) bin.write(reinterpret_cast<const char*>(v + 3), 8);
    bin.write(reinterpret_cast<const char*>(indices), sizeof indices);
    std::ofstream(path) << R"({"asset": {"version": "2.0"},
  "buffers": [{"uri": ")" << bin_name << R"(", "byteLength": 92}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                  {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
  "textures": [{"source": 0}], "images": [{"uri": ")" << image << R"("}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
  "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
}

// A PNG that is only a signature and an IHDR declaring `width` x `height`.
inline void write_png_header_only(const std::string& path, uint32_t width, uint32_t height, uint8_t interlace = 0) {
    auto be = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
    std::string ihdr = be(13) + "IHDR" + be(width) + be(height) + std::string{8, 2, 0, 0, char(interlace)} + be(0);
    std::ofstream(path, std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) << ihdr;
}

}  // namespace facet::test
