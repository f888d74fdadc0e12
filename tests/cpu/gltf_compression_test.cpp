// Compressed meshes (EXT_meshopt_compression, KHR_draco_mesh_compression): files the test
// writes with each library's own encoder from geometry it makes, loaded by load_gltf and
// compared with the geometry they came from; corrupt and forged streams fail cleanly.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <facet/scene/gltf_loader.h>
#include "scene/gltf_decompress_meshopt.h"
#include "support/compressed_gltf.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using test::TestGeometry;

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_gltf_compression_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    fs::path file(const std::string& name) const { return path / name; }
};

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void write_text(const fs::path& path, const std::string& text) { test::write_bytes(path, text.data(), text.size()); }

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

Scene load_ok(const fs::path& path) {
    Result<Scene> scene = load_gltf(path.string());
    EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
    return scene.ok() ? std::move(*scene) : Scene{};
}

std::string load_error(const fs::path& path) {
    Result<Scene> scene = load_gltf(path.string());
    EXPECT_FALSE(scene.ok()) << path << " loaded";
    return scene.ok() ? "" : scene.error().message;
}

// The same triangles in the same order, each possibly rotated (meshopt's triangle codec
// may start a triangle at another corner; the winding stays).
void expect_same_triangles(const std::vector<uint32_t>& loaded, const std::vector<uint32_t>& original) {
    ASSERT_EQ(loaded.size(), original.size());
    for (size_t t = 0; t < loaded.size(); t += 3) {
        bool same = false;
        for (int r = 0; r < 3; ++r)
            same = same || (loaded[t] == original[t + r] && loaded[t + 1] == original[t + (r + 1) % 3] &&
                            loaded[t + 2] == original[t + (r + 2) % 3]);
        ASSERT_TRUE(same) << "triangle " << t / 3 << ": " << loaded[t] << " " << loaded[t + 1] << " " << loaded[t + 2];
    }
}

// Lossless: every position, uv and triangle exactly as written; normals within the
// loader's renormalisation (a unit vector divided by its float length).
void expect_exact(const Scene& scene, const TestGeometry& g) {
    ASSERT_EQ(scene.primitives.size(), 1u);
    ASSERT_EQ(scene.vertices.size(), g.vertex_count());
    expect_same_triangles(scene.indices, g.indices);
    for (size_t i = 0; i < g.vertex_count(); ++i) {
        const Vertex& v = scene.vertices[i];
        for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(v.position[c], g.positions[3 * i + c]) << "vertex " << i;
            ASSERT_NEAR(v.normal[c], g.normals[3 * i + c], 1e-6f) << "vertex " << i;
        }
        ASSERT_EQ(v.uv.x, g.uvs[2 * i]) << "vertex " << i;
        ASSERT_EQ(v.uv.y, g.uvs[2 * i + 1]) << "vertex " << i;
    }
}

TEST(GltfMeshopt, LosslessStreamsLoadExactly) {
    TempDir dir;
    const TestGeometry g = test::wavy_grid(23, 17);  // 864 vertices: several 256-vertex blocks
    test::write_meshopt_gltf(dir.file("grid.gltf"), g);
    const Scene scene = load_ok(dir.file("grid.gltf"));
    expect_exact(scene, g);
    EXPECT_TRUE(scene.warnings.empty());
}

TEST(GltfMeshopt, GlbWithFallbackBufferLoadsExactly) {
    // gltfpack's layout: the BIN chunk holds the compressed streams and a fallback buffer
    // without uri declares the decoded size (larger than the BIN chunk here).
    TempDir dir;
    const TestGeometry g = test::wavy_grid(40, 30);
    test::write_meshopt_gltf(dir.file("grid.glb"), g);
    expect_exact(load_ok(dir.file("grid.glb")), g);
}

TEST(GltfMeshopt, IndexSequenceAndOnlyUsed) {
    TempDir dir;
    const TestGeometry g = test::wavy_grid(9, 31);
    test::MeshoptOptions options;
    options.index_sequence = true;
    options.required = false;
    test::write_meshopt_gltf(dir.file("grid.gltf"), g, options);
    expect_exact(load_ok(dir.file("grid.gltf")), g);
}

TEST(GltfMeshopt, FallbackFileIsNeverRead) {
    // gltfpack -cf names a fallback file: Facet decodes instead, so a missing one is fine.
    TempDir dir;
    const TestGeometry g = test::wavy_grid(6, 5);
    test::write_meshopt_gltf(dir.file("grid.gltf"), g);
    write_text(dir.file("grid.gltf"), replaced(read_text(dir.file("grid.gltf")), "\"extensions\": {\"EXT_meshopt_compression\": {\"fallback\"",
                                               "\"uri\": \"absent.fallback.bin\", \"extensions\": {\"EXT_meshopt_compression\": {\"fallback\""));
    expect_exact(load_ok(dir.file("grid.gltf")), g);
}

TEST(GltfMeshopt, ExponentialFilterWithinItsMantissa) {
    TempDir dir;
    const TestGeometry g = test::wavy_grid(16, 16);
    test::MeshoptOptions options;
    options.exponential_positions = true;
    test::write_meshopt_gltf(dir.file("grid.gltf"), g, options);
    const Scene scene = load_ok(dir.file("grid.gltf"));
    ASSERT_EQ(scene.vertices.size(), g.vertex_count());
    // A 24-bit mantissa with the vertex's largest exponent: each component within
    // 2^-23 of the vertex's largest magnitude (coordinates here are at most 1).
    const float step = std::ldexp(1.0f, -23);
    for (size_t i = 0; i < g.vertex_count(); ++i)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(scene.vertices[i].position[c], g.positions[3 * i + c], step) << i;
    expect_same_triangles(scene.indices, g.indices);
}

TEST(GltfMeshopt, CorruptStreamIsOneErrorNamingTheView) {
    TempDir dir;
    test::write_meshopt_gltf(dir.file("grid.gltf"), test::wavy_grid(8, 8));
    std::string bin = read_text(dir.file("grid.bin"));
    bin[0] = char(0x00);  // the vertex codec's header byte (0xa0 | version)
    write_text(dir.file("grid.bin"), bin);
    const std::string error = load_error(dir.file("grid.gltf"));
    EXPECT_NE(error.find("grid.gltf"), std::string::npos) << error;
    EXPECT_NE(error.find("bufferView 0 (EXT_meshopt_compression): the compressed stream is corrupt"), std::string::npos)
        << error;
}

TEST(GltfMeshopt, TruncatedIndexStreamIsAnError) {
    TempDir dir;
    const TestGeometry g = test::wavy_grid(8, 8);
    test::write_meshopt_gltf(dir.file("grid.gltf"), g);
    // The index view's compressed length cut to 5 bytes.
    std::string json = read_text(dir.file("grid.gltf"));
    const size_t at = json.find("\"mode\": \"TRIANGLES\"");
    ASSERT_NE(at, std::string::npos);
    const size_t length = json.rfind("\"byteLength\": ", at);
    const size_t end = json.find(',', length);
    json.replace(length, end - length, "\"byteLength\": 5");
    write_text(dir.file("grid.gltf"), json);
    const std::string error = load_error(dir.file("grid.gltf"));
    EXPECT_NE(error.find("bufferView 3 (EXT_meshopt_compression)"), std::string::npos) << error;
}

TEST(GltfMeshopt, ForgedCountIsRefusedBeforeAllocating) {
    TempDir dir;
    test::write_meshopt_gltf(dir.file("grid.gltf"), test::wavy_grid(4, 4));
    // 25 vertices claimed as 2^27: 1.5 GiB from a stream of a few hundred bytes.
    const std::string json = replaced(read_text(dir.file("grid.gltf")), "\"count\": 25, \"mode\": \"ATTRIBUTES\"",
                                      "\"count\": 134217728, \"mode\": \"ATTRIBUTES\"");
    write_text(dir.file("grid.gltf"), json);
    const std::string error = load_error(dir.file("grid.gltf"));
    EXPECT_NE(error.find("compressed bytes can hold"), std::string::npos) << error;
}

TEST(GltfMeshopt, BadModeAndStrideAreErrors) {
    TempDir dir;
    test::write_meshopt_gltf(dir.file("grid.gltf"), test::wavy_grid(4, 4));
    const std::string json = read_text(dir.file("grid.gltf"));
    write_text(dir.file("mode.gltf"), replaced(json, "\"mode\": \"TRIANGLES\"", "\"mode\": \"QUADS\""));
    fs::copy_file(dir.file("grid.bin"), dir.file("mode.bin"));
    EXPECT_NE(load_error(dir.file("mode.gltf")).find("unknown mode 'QUADS'"), std::string::npos);
    write_text(dir.file("stride.gltf"), replaced(json, "\"byteStride\": 8, \"count\"", "\"byteStride\": 6, \"count\""));
    fs::copy_file(dir.file("grid.bin"), dir.file("stride.bin"));
    EXPECT_NE(load_error(dir.file("stride.gltf")).find("byteStride 6 must be a multiple of 4"), std::string::npos);
}

// The filters whose output the loader cannot read yet as vertex data (normalized
// integer normals and rotations need KHR_mesh_quantization): decoded in a model built
// here, the bytes compared with the unit vectors and quaternions they came from.
tinygltf::Model filtered_model(const std::vector<uint8_t>& filtered, size_t count, size_t stride, const char* filter) {
    std::vector<uint8_t> encoded(meshopt_encodeVertexBufferBound(count, stride));
    encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), filtered.data(), count, stride));
    tinygltf::Model model;
    model.buffers.resize(1);
    model.buffers[0].data = encoded;
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteLength = count * stride;
    view.byteStride = stride;
    tinygltf::Value::Object ext;
    ext["buffer"] = tinygltf::Value(0);
    ext["byteLength"] = tinygltf::Value(int(encoded.size()));
    ext["byteStride"] = tinygltf::Value(int(stride));
    ext["count"] = tinygltf::Value(int(count));
    ext["mode"] = tinygltf::Value(std::string("ATTRIBUTES"));
    ext["filter"] = tinygltf::Value(std::string(filter));
    view.extensions["EXT_meshopt_compression"] = tinygltf::Value(ext);
    model.bufferViews.push_back(view);
    return model;
}

std::vector<float> unit_vectors(size_t count) {  // x, y, z, w = 0
    std::vector<float> v;
    for (size_t i = 0; i < count; ++i) {
        const float a = 0.37f * float(i), b = 0.11f * float(i) - 1.3f;
        v.insert(v.end(), {std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b), 0.0f});
    }
    return v;
}

int16_t at16(const std::vector<unsigned char>& bytes, size_t i) {
    int16_t v;
    std::memcpy(&v, &bytes[i * 2], 2);
    return v;
}

TEST(GltfMeshopt, OctahedralFilterGivesTheUnitVectors) {
    const size_t count = 300;
    const std::vector<float> normals = unit_vectors(count);
    std::vector<uint8_t> filtered(count * 8);
    meshopt_encodeFilterOct(filtered.data(), count, 8, 12, normals.data());  // 12-bit, as int16 x 4
    tinygltf::Model model = filtered_model(filtered, count, 8, "OCTAHEDRAL");
    gltf_detail::decompress_meshopt(model);
    ASSERT_TRUE(model.bufferViews[0].extensions.empty());
    const std::vector<unsigned char>& out = model.buffers[size_t(model.bufferViews[0].buffer)].data;
    ASSERT_EQ(out.size(), count * 8);
    // 12 bits over the octahedron's [-1, 1]: a step of 2^-11; the direction within 2e-3.
    for (size_t i = 0; i < count; ++i)
        for (size_t c = 0; c < 3; ++c)
            ASSERT_NEAR(at16(out, 4 * i + c) / 32767.0f, normals[4 * i + c], 2e-3f) << i << " " << c;
}

TEST(GltfMeshopt, QuaternionFilterGivesTheRotations) {
    const size_t count = 200;
    std::vector<float> quats = unit_vectors(count);
    for (size_t i = 0; i < count; ++i) {  // (axis sin(t/2), cos(t/2))
        const float half = 0.05f * float(i), s = std::sin(half);
        for (size_t c = 0; c < 3; ++c) quats[4 * i + c] *= s;
        quats[4 * i + 3] = std::cos(half);
    }
    std::vector<uint8_t> filtered(count * 8);
    meshopt_encodeFilterQuat(filtered.data(), count, 8, 12, quats.data());
    tinygltf::Model model = filtered_model(filtered, count, 8, "QUATERNION");
    gltf_detail::decompress_meshopt(model);
    const std::vector<unsigned char>& out = model.buffers[size_t(model.bufferViews[0].buffer)].data;
    ASSERT_EQ(out.size(), count * 8);
    // q and -q are the same rotation: compare |q . q'|, 1 within the 12-bit step.
    for (size_t i = 0; i < count; ++i) {
        double dot = 0;
        for (size_t c = 0; c < 4; ++c) dot += double(at16(out, 4 * i + c)) / 32767.0 * quats[4 * i + c];
        ASSERT_NEAR(std::abs(dot), 1.0, 2e-3) << i;
    }
}

// Draco quantises: the loaded mesh is compared triangle by triangle (Draco may reorder
// points, faces and each face's corners), every corner within its attribute's step.
void expect_draco_match(const Scene& scene, const TestGeometry& g, const test::DracoOptions& o) {
    ASSERT_EQ(scene.primitives.size(), 1u);
    ASSERT_EQ(scene.indices.size(), g.indices.size());
    ASSERT_EQ(scene.vertices.size(), g.vertex_count());
    // Steps: the attribute's range over 2^bits - 1 (positions span 1 in x and y; uvs 1).
    const float position_step = 1.0f / float((1 << o.position_bits) - 1);
    const float uv_step = 1.0f / float((1 << o.uv_bits) - 1);
    // Draco codes normals octahedrally: the angle per step is about pi / 2^bits.
    const float normal_step = 4.0f / float(1 << o.normal_bits);
    auto corner_matches = [&](uint32_t loaded, uint32_t original) {
        const Vertex& v = scene.vertices[loaded];
        for (int c = 0; c < 3; ++c) {
            if (std::abs(v.position[c] - g.positions[3 * original + c]) > position_step) return false;
            if (std::abs(v.normal[c] - g.normals[3 * original + c]) > normal_step) return false;
        }
        return std::abs(v.uv.x - g.uvs[2 * original]) <= uv_step && std::abs(v.uv.y - g.uvs[2 * original + 1]) <= uv_step;
    };
    std::vector<bool> used(g.indices.size() / 3, false);
    for (size_t t = 0; t < scene.indices.size(); t += 3) {
        bool found = false;
        for (size_t u = 0; u < used.size() && !found; ++u) {
            if (used[u]) continue;
            for (int rotation = 0; rotation < 3 && !found; ++rotation) {
                bool all = true;
                for (int c = 0; c < 3 && all; ++c)
                    all = corner_matches(scene.indices[t + c], g.indices[3 * u + (c + rotation) % 3]);
                if (all) used[u] = found = true;
            }
        }
        ASSERT_TRUE(found) << "loaded triangle " << t / 3 << " matches no original triangle";
    }
}

TEST(GltfDraco, DecodedWithinTheQuantizationStep) {
    TempDir dir;
    const TestGeometry g = test::wavy_grid(12, 9);
    const test::DracoOptions options;
    test::write_draco_gltf(dir.file("grid.gltf"), g, options);
    const Scene scene = load_ok(dir.file("grid.gltf"));
    expect_draco_match(scene, g, options);
    EXPECT_TRUE(scene.warnings.empty());
}

TEST(GltfDraco, SequentialEncodingToo) {
    TempDir dir;
    const TestGeometry g = test::wavy_grid(7, 5);
    test::DracoOptions options;
    options.speed = 10;  // Draco's fastest setting codes the mesh sequentially
    options.position_bits = 11;
    test::write_draco_gltf(dir.file("grid.gltf"), g, options);
    expect_draco_match(load_ok(dir.file("grid.gltf")), g, options);
}

TEST(GltfDraco, CorruptStreamIsOneErrorNamingThePrimitive) {
    TempDir dir;
    test::write_draco_gltf(dir.file("grid.gltf"), test::wavy_grid(6, 6));
    std::string bin = read_text(dir.file("grid.bin"));
    bin.replace(0, 5, "XXXXX");  // the "DRACO" magic
    write_text(dir.file("grid.bin"), bin);
    const std::string error = load_error(dir.file("grid.gltf"));
    EXPECT_NE(error.find("grid.gltf"), std::string::npos) << error;
    EXPECT_NE(error.find("mesh 0 primitive 0 (KHR_draco_mesh_compression): the compressed stream does not decode"),
              std::string::npos)
        << error;
}

TEST(GltfDraco, GarbledAndTruncatedStreamsFailCleanly) {
    TempDir dir;
    test::write_draco_gltf(dir.file("grid.gltf"), test::wavy_grid(6, 6));
    const std::string bin = read_text(dir.file("grid.bin"));
    // Every byte after the header flipped in turn, then the stream cut at every length:
    // each load either succeeds or fails with an error naming the primitive.
    for (size_t cut = 0; cut < bin.size(); cut += 7) {
        write_text(dir.file("grid.bin"), bin.substr(0, cut) + std::string(bin.size() - cut, '\xff'));
        Result<Scene> scene = load_gltf(dir.file("grid.gltf").string());
        if (!scene.ok()) EXPECT_NE(scene.error().message.find("grid.gltf: "), std::string::npos);
    }
}

TEST(GltfDraco, CountDisagreeingWithTheStreamIsAnError) {
    TempDir dir;
    const TestGeometry g = test::wavy_grid(3, 3);  // 16 points
    test::write_draco_gltf(dir.file("grid.gltf"), g);
    write_text(dir.file("grid.gltf"), replaced(read_text(dir.file("grid.gltf")),
                                               "{\"componentType\": 5126, \"count\": 16, \"type\": \"VEC2\"}",
                                               "{\"componentType\": 5126, \"count\": 15, \"type\": \"VEC2\"}"));
    const std::string error = load_error(dir.file("grid.gltf"));
    EXPECT_NE(error.find("TEXCOORD_0: accessor count 15 but the stream decodes 16 points"), std::string::npos) << error;
}

TEST(GltfDraco, UnknownAttributeIdIsAnError) {
    TempDir dir;
    test::write_draco_gltf(dir.file("grid.gltf"), test::wavy_grid(3, 3));
    write_text(dir.file("grid.gltf"),
               replaced(read_text(dir.file("grid.gltf")), "\"TEXCOORD_0\": 2}}", "\"TEXCOORD_0\": 9}}"));
    const std::string error = load_error(dir.file("grid.gltf"));
    EXPECT_NE(error.find("TEXCOORD_0: the stream has no attribute 9"), std::string::npos) << error;
}

}  // namespace
}  // namespace facet
