// The glTF core specification for a still frame, on small files written here: vertex
// colours, TEXCOORD_1, every accessor component type, sparse accessors, primitive modes,
// several scenes, mirrored nodes, the default camera for flat models, and the malformed
// inputs of each path (one error naming the file and the problem).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <facet/render/camera.h>
#include <facet/scene/gltf_loader.h>
#include "support/gltf_files.h"

namespace facet {
namespace {

using namespace test;

const std::vector<float> kQuad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};  // CCW seen from +Z
const std::vector<uint16_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

// One mesh of one primitive (`attributes` JSON, indices accessor or -1, `mode`) drawn by one node.
std::string one_mesh(const std::string& attributes, int indices, int mode = 4, const std::string& more = "") {
    std::string primitive = R"({"attributes": {)" + attributes + "}";
    if (indices >= 0) primitive += R"(, "indices": )" + std::to_string(indices);
    primitive += R"(, "mode": )" + std::to_string(mode) + "}";
    return R"("meshes": [{"name": "m", "primitives": [)" + primitive + R"(]}],
  "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0)" + more;
}

std::string replaced_once(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

Scene load_ok(const std::string& path, int scene = -1) {
    Result<Scene> loaded = load_gltf(path, {}, scene);
    EXPECT_TRUE(loaded.ok()) << (loaded.ok() ? "" : loaded.error().message);
    return loaded.ok() ? std::move(loaded).value() : Scene{};
}

void expect_near(glm::vec4 a, glm::vec4 b, float tolerance = 1e-6f) {
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << "component " << i;
}

TEST(GltfCore, VertexColoursInEveryForm) {
    GltfTempDir dir("gltf_core");
    // VEC3 FLOAT, VEC4 normalized UNSIGNED_BYTE, VEC4 normalized UNSIGNED_SHORT.
    for (int form = 0; form < 3; ++form) {
        GltfBuilder b;
        const int position = b.add(kQuad, kFloat, "VEC3", 4);
        const int indices = b.add(kQuadIndices, kUshort, "SCALAR", 6);
        int color = 0;
        glm::vec4 expected;
        if (form == 0) {
            color = b.add(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}, kFloat, "VEC3", 4);
            expected = {0, 0, 1, 1};
        } else if (form == 1) {
            color = b.add(std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 128, 51, 102, 153, 0, 0, 0, 0, 255}, kUbyte,
                          "VEC4", 4, R"(, "normalized": true)");
            expected = {0.2f, 0.4f, 0.6f, 0.0f};
        } else {
            color = b.add(std::vector<uint16_t>{65535, 0, 0, 65535, 0, 65535, 0, 0, 13107, 0, 65535, 32768, 0, 0, 0, 0},
                          kUshort, "VEC4", 4, R"(, "normalized": true)");
            expected = {0.2f, 0.0f, 1.0f, 32768.0f / 65535.0f};
        }
        const std::string path = b.write(dir, "colour" + std::to_string(form),
                                          one_mesh(R"("POSITION": 0, "COLOR_0": )" + std::to_string(color), indices));
        (void)position;
        Scene scene = load_ok(path);
        ASSERT_EQ(scene.vertices.size(), 4u);
        expect_near(scene.vertices[2].color, expected);
    }
    // Absent: white.
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);
    b.add(kQuadIndices, kUshort, "SCALAR", 6);
    Scene scene = load_ok(b.write(dir, "white", one_mesh(R"("POSITION": 0)", 1)));
    for (const Vertex& v : scene.vertices) expect_near(v.color, glm::vec4(1.0f));
}

TEST(GltfCore, SecondUvSetIsLoadedAndNamedByTheMaterial) {
    GltfTempDir dir("gltf_core");
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);
    b.add(kQuadIndices, kUshort, "SCALAR", 6);
    b.add(std::vector<float>{0, 0, 1, 0, 1, 1, 0, 1}, kFloat, "VEC2", 4);
    // TEXCOORD_1 as unnormalized UNSIGNED_SHORT (KHR_mesh_quantization allows it): values 0..2.
    b.add(std::vector<uint16_t>{0, 0, 2, 0, 2, 2, 0, 2}, kUshort, "VEC2", 4);
    const std::string mesh = one_mesh(R"("POSITION": 0, "TEXCOORD_0": 2, "TEXCOORD_1": 3)", 1);
    const std::string materials = R"(,
  "materials": [{"name": "two", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}}}],
  "textures": [{"source": 0}], "images": [{"uri": "pixel.png"}])";
    std::string members = mesh;
    members.replace(members.find(R"("mode": 4})"), 10, R"("mode": 4, "material": 0})");
    // A 1x1 white PNG, so that the image decodes.
    const unsigned char png[] = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
                                 0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00,
                                 0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x08,
                                 0xd7, 0x63, 0xf8, 0xff, 0xff, 0x3f, 0x00, 0x05, 0xfe, 0x02, 0xfe, 0xa7, 0x35, 0x81,
                                 0x84, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    write_bytes(dir.file("pixel.png"), std::string(reinterpret_cast<const char*>(png), sizeof png));
    Scene scene = load_ok(b.write(dir, "uv1", members + materials));
    ASSERT_EQ(scene.vertices.size(), 4u);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].base_color_texture.uv_set, 1u);
    EXPECT_EQ(scene.vertices[2].uv, glm::vec2(1, 1));
    EXPECT_EQ(scene.vertices[2].uv1, glm::vec2(2, 2));
}

// Positions in each integer component type, normalized or not, against the values the
// glTF rules give (KHR_mesh_quantization's forms).
TEST(GltfCore, EveryComponentTypeNormalizedOrNot) {
    GltfTempDir dir("gltf_core");
    struct Case {
        int type;
        bool normalized;
        float scale;  // value of the raw integer 1 ... as loaded: raw / scale
    };
    const Case cases[] = {{kByte, false, 1}, {kByte, true, 127},  {kUbyte, false, 1},  {kUbyte, true, 255},
                          {kShort, false, 1}, {kShort, true, 32767}, {kUshort, false, 1}, {kUshort, true, 65535}};
    for (const Case& c : cases) {
        GltfBuilder b;
        // Three vertices (0,0,0) (r,0,0) (0,r,0) with raw r = 100; padded to 4-byte elements.
        const std::string extra = c.normalized ? R"(, "normalized": true)" : "";
        int view = 0;
        if (c.type == kByte || c.type == kUbyte) {
            view = b.view(std::vector<uint8_t>{0, 0, 0, 0, 100, 0, 0, 0, 0, 100, 0, 0});
            b.views.back().insert(b.views.back().size() - 1, R"(, "byteStride": 4)");
        } else {
            view = b.view(std::vector<uint16_t>{0, 0, 0, 0, 100, 0, 0, 0, 0, 100, 0, 0});
            b.views.back().insert(b.views.back().size() - 1, R"(, "byteStride": 8)");
        }
        b.accessor(view, c.type, "VEC3", 3, extra);
        Scene scene = load_ok(b.write(dir, "types", one_mesh(R"("POSITION": 0)", -1)));
        ASSERT_EQ(scene.vertices.size(), 3u) << c.type;
        EXPECT_NEAR(scene.vertices[1].position.x, 100.0f / c.scale, 1e-6f) << c.type << " " << c.normalized;
        EXPECT_NEAR(scene.vertices[2].position.y, 100.0f / c.scale, 1e-6f) << c.type << " " << c.normalized;
    }
}

// KHR_mesh_quantization's normals and tangents: normalized BYTE and SHORT, unit length
// after loading; an unnormalized integer normal is refused by name.
TEST(GltfCore, QuantisedNormalsAndTangents) {
    GltfTempDir dir("gltf_core");
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);
    b.add(kQuadIndices, kUshort, "SCALAR", 6);
    b.add(std::vector<int8_t>{0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0}, kByte, "VEC3", 4);  // padded
    b.views.back().insert(b.views.back().size() - 1, R"(, "byteStride": 4)");
    b.accessors.back().insert(b.accessors.back().size() - 1, R"(, "normalized": true)");
    b.add(std::vector<int16_t>{32767, 0, 0, -32767, 32767, 0, 0, -32767, 32767, 0, 0, -32767, 32767, 0, 0, -32767},
          kShort, "VEC4", 4, R"(, "normalized": true)");
    Scene scene = load_ok(b.write(dir, "quantised", one_mesh(R"("POSITION": 0, "NORMAL": 2, "TANGENT": 3)", 1)));
    ASSERT_EQ(scene.vertices.size(), 4u);
    for (const Vertex& v : scene.vertices) {
        expect_near(glm::vec4(v.normal, 0.0f), glm::vec4(0, 0, 1, 0));
        expect_near(v.tangent, glm::vec4(1, 0, 0, -1));
    }
    b.accessors[2] = replaced_once(b.accessors[2], R"(, "normalized": true)", "");
    expect_error(b.write(dir, "integer_normals", one_mesh(R"("POSITION": 0, "NORMAL": 2)", 1)),
                 "NORMAL must be VEC3 FLOAT or normalized BYTE/SHORT");
}

TEST(GltfCore, SparseAccessorsWithAndWithoutBaseView) {
    GltfTempDir dir("gltf_core");
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);  // 0: base positions
    const int sparse_indices = b.view(std::vector<uint8_t>{1, 3, 0, 0});
    const int sparse_values = b.view(std::vector<float>{5, 0, 0, 0, 7, 0});
    const std::string sparse = R"(, "sparse": {"count": 2, "indices": {"bufferView": )" + std::to_string(sparse_indices) +
                               R"(, "componentType": 5121}, "values": {"bufferView": )" + std::to_string(sparse_values) + "}}";
    b.accessor(0, kFloat, "VEC3", 4, sparse);   // 1: on the base view
    b.accessor(-1, kFloat, "VEC3", 4, sparse);  // 2: on zeros
    b.add(kQuadIndices, kUshort, "SCALAR", 6);  // 3
    Scene on_base = load_ok(b.write(dir, "sparse_base", one_mesh(R"("POSITION": 1)", 3)));
    ASSERT_EQ(on_base.vertices.size(), 4u);
    EXPECT_EQ(on_base.vertices[0].position, glm::vec3(0, 0, 0));
    EXPECT_EQ(on_base.vertices[1].position, glm::vec3(5, 0, 0));
    EXPECT_EQ(on_base.vertices[2].position, glm::vec3(1, 1, 0));
    EXPECT_EQ(on_base.vertices[3].position, glm::vec3(0, 7, 0));
    Scene on_zeros = load_ok(b.write(dir, "sparse_zeros", one_mesh(R"("POSITION": 2)", 3)));
    ASSERT_EQ(on_zeros.vertices.size(), 4u);
    EXPECT_EQ(on_zeros.vertices[1].position, glm::vec3(5, 0, 0));
    EXPECT_EQ(on_zeros.vertices[2].position, glm::vec3(0, 0, 0));
    EXPECT_EQ(on_zeros.vertices[3].position, glm::vec3(0, 7, 0));
    // Without a bufferView and not sparse: zeros (here black vertex colours).
    GltfBuilder zeros = b;
    zeros.accessor(-1, kFloat, "VEC3", 4);  // 4
    Scene black = load_ok(zeros.write(dir, "zeros", one_mesh(R"("POSITION": 0, "COLOR_0": 4)", 3)));
    ASSERT_EQ(black.vertices.size(), 4u);
    for (const Vertex& v : black.vertices) expect_near(v.color, glm::vec4(0, 0, 0, 1));

    // An index beyond the accessor's count: one error naming the file and the index.
    GltfBuilder bad = b;
    const int far = bad.view(std::vector<uint8_t>{1, 9, 0, 0});
    bad.accessor(0, kFloat, "VEC3", 4,
                 R"(, "sparse": {"count": 2, "indices": {"bufferView": )" + std::to_string(far) +
                     R"(, "componentType": 5121}, "values": {"bufferView": )" + std::to_string(sparse_values) + "}}");
    expect_error(bad.write(dir, "sparse_bad", one_mesh(R"("POSITION": 4)", 3)),
                 "POSITION: accessor 4 sparse index 9 out of range (the accessor has 4 elements)");
}

// Sparse accessors on zeros cost nothing in a file, whatever count they declare: an
// attribute's densified size and a primitive's morphed vertices are bounded.
TEST(GltfCore, SparseCountsAreBoundedBeforeAllocating) {
    GltfTempDir dir("gltf_core");
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);
    b.add(kQuadIndices, kUshort, "SCALAR", 6);
    const int indices = b.view(std::vector<uint8_t>{1, 0, 0, 0});
    const int values = b.view(std::vector<float>{1, 1, 1, 1});
    const std::string sparse = R"(, "sparse": {"count": 1, "indices": {"bufferView": )" + std::to_string(indices) +
                               R"(, "componentType": 5121}, "values": {"bufferView": )" + std::to_string(values) + "}}";
    b.accessor(-1, kFloat, "VEC4", size_t(1) << 25, sparse);  // 2: 512 MiB dense
    expect_error(b.write(dir, "huge_colours", one_mesh(R"("POSITION": 0, "COLOR_0": 2)", 1)),
                 "COLOR_0: accessor 2: sparse accessor of 33554432 elements is too large (more than 256 MiB dense)");
    b.accessor(-1, kFloat, "VEC3", size_t(1) << 22, sparse);  // 3: 4 Mi positions, 48 MiB dense
    std::string members = one_mesh(R"("POSITION": 3)", -1);
    const std::string five_targets = R"(, "targets": [{"POSITION": 3}, {"POSITION": 3}, {"POSITION": 3}, {"POSITION": 3}, {"POSITION": 3}]})";
    members.replace(members.find(R"("mode": 4})"), 10, std::string(R"("mode": 4)") + five_targets);
    expect_error(b.write(dir, "many_targets", members),
                 "5 morph targets of 4194304 vertices exceed the limit of 16777216 morphed vertices");
}

std::vector<uint32_t> loaded_indices(const std::string& path, Topology expected) {
    Scene scene = load_ok(path);
    if (scene.primitives.size() != 1) return {};
    const Primitive& p = scene.primitives[0];
    EXPECT_EQ(p.topology, expected);
    return {scene.indices.begin() + p.first_index, scene.indices.begin() + p.first_index + p.index_count};
}

TEST(GltfCore, PrimitiveModesBecomeLists) {
    GltfTempDir dir("gltf_core");
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);
    const auto mode = [&](int m) { return b.write(dir, "mode" + std::to_string(m), one_mesh(R"("POSITION": 0)", -1, m)); };
    using V = std::vector<uint32_t>;
    EXPECT_EQ(loaded_indices(mode(0), Topology::points), (V{0, 1, 2, 3}));
    EXPECT_EQ(loaded_indices(mode(1), Topology::lines), (V{0, 1, 2, 3}));
    EXPECT_EQ(loaded_indices(mode(2), Topology::lines), (V{0, 1, 1, 2, 2, 3, 3, 0}));  // loop
    EXPECT_EQ(loaded_indices(mode(3), Topology::lines), (V{0, 1, 1, 2, 2, 3}));        // strip
    EXPECT_EQ(loaded_indices(mode(5), Topology::triangles), (V{0, 1, 2, 1, 3, 2}));    // strip, winding kept
    EXPECT_EQ(loaded_indices(mode(6), Topology::triangles), (V{1, 2, 0, 2, 3, 0}));    // fan about vertex 0
}

TEST(GltfCore, SceneChosenByIndexElseTheFilesDefault) {
    GltfTempDir dir("gltf_core");
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);
    b.add(kQuadIndices, kUshort, "SCALAR", 6);
    const std::string members = R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "nodes": [{"mesh": 0, "name": "a"}, {"mesh": 0, "name": "b", "translation": [5, 0, 0]}, {"mesh": 0, "name": "c"}],
  "scenes": [{"nodes": [0]}, {"nodes": [1, 2]}], "scene": 1)";
    const std::string path = b.write(dir, "scenes", members);
    Scene by_default = load_ok(path);
    ASSERT_EQ(by_default.instances.size(), 2u);
    EXPECT_EQ(by_default.instances[0].node, "b");
    EXPECT_EQ(by_default.instances[0].world[3], glm::vec4(5, 0, 0, 1));
    Scene first = load_ok(path, 0);
    ASSERT_EQ(first.instances.size(), 1u);
    EXPECT_EQ(first.instances[0].node, "a");
    Result<Scene> missing = load_gltf(path, {}, 2);
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().message, path + ": scene 2 out of range (2 scenes)");
}

TEST(GltfCore, MirroredNodeKeepsItsNegativeDeterminant) {
    GltfTempDir dir("gltf_core");
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);
    b.add(kQuadIndices, kUshort, "SCALAR", 6);
    std::string members = one_mesh(R"("POSITION": 0)", 1);
    members.replace(members.find(R"({"mesh": 0})"), 11, R"({"mesh": 0, "scale": [-1, 1, 1]})");
    Scene scene = load_ok(b.write(dir, "mirror", members));
    ASSERT_EQ(scene.instances.size(), 1u);
    EXPECT_LT(glm::determinant(glm::mat3(scene.instances[0].world)), 0.0f);
}

// A quad lying in the XZ plane (and one in YZ) must not be framed edge-on: every corner
// inside the frame and the projected quad covering a fair part of it; an ordinary box
// keeps the +Z view.
TEST(GltfCore, DefaultCameraSeesFlatModels) {
    const float yfov = glm::radians(45.0f), aspect = 1.5f;
    auto projected_area = [&](const CameraView& c, const std::vector<glm::vec3>& corners) {
        const glm::mat4 vp = c.projection(aspect) * c.view();
        std::vector<glm::vec2> ndc;
        for (glm::vec3 p : corners) {
            const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
            EXPECT_GT(clip.w, 0.0f);
            const glm::vec2 n = glm::vec2(clip) / clip.w;
            EXPECT_LE(std::abs(n.x), 1.0f);
            EXPECT_LE(std::abs(n.y), 1.0f);
            ndc.push_back(n);
        }
        float twice = 0.0f;  // shoelace, in NDC units (the frame is 4)
        for (size_t i = 0; i < ndc.size(); ++i) {
            const glm::vec2 a = ndc[i], b = ndc[(i + 1) % ndc.size()];
            twice += a.x * b.y - a.y * b.x;
        }
        return std::abs(twice) * 0.5f / 4.0f;
    };
    const std::vector<glm::vec3> xz = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
    EXPECT_GT(projected_area(frame_bounds({-1, 0, -1}, {1, 0, 1}, yfov, aspect), xz), 0.1f);
    const std::vector<glm::vec3> yz = {{0, -1, -1}, {0, 1, -1}, {0, 1, 1}, {0, -1, 1}};
    EXPECT_GT(projected_area(frame_bounds({0, -1, -1}, {0, 1, 1}, yfov, aspect), yz), 0.1f);
    const CameraView cube = frame_bounds({-1, -1, -1}, {1, 1, 1}, yfov, aspect);
    EXPECT_NEAR(cube.position.x, 0.0f, 1e-6f);
    EXPECT_NEAR(cube.position.y, 0.0f, 1e-6f);
    EXPECT_GT(cube.position.z, 1.0f);
}

// The fuzz seeds of the new paths (tests/fuzz/corpus/gltf, make_corpus_gltf.cpp) reach
// the check they were written for, and the valid ones load.
TEST(GltfCore, FuzzSeedsReachTheirChecks) {
    const std::string corpus = std::string(FACET_SOURCE_DIR) + "/tests/fuzz/corpus/gltf/";
    const std::pair<const char*, const char*> refused[] = {
        {"bad_mode_unknown.gltf", "unknown primitive mode 9"},
        {"bad_morph_count.gltf", "morph target 0: POSITION has 3 elements, POSITION has 4"},
        {"bad_morph_weights.gltf", "2 morph weights for 1 morph targets"},
        {"bad_scene_index.gltf", "scene 7 out of range (1 scenes)"},
        {"bad_skin_joint.gltf", "skin 0: joint 7 is not a node (2 nodes)"},
        {"bad_skin_vertex_joint.gltf", "vertex 1 uses joint 1 of a skin with 1"},
        {"bad_sparse_index.gltf", "sparse index 3 out of range (the accessor has 2 elements)"},
        {"bad_texcoord_2.gltf", "baseColorTexture uses TEXCOORD_2"}};
    for (const auto& [name, phrase] : refused) expect_error(corpus + name, phrase);
    for (const char* name : {"colours_uv1.gltf", "lines_points.gltf", "skin_morph.gltf", "sparse_quantised.gltf"}) {
        Result<Scene> scene = load_gltf(corpus + name);
        EXPECT_TRUE(scene.ok()) << name << ": " << (scene.ok() ? "" : scene.error().message);
    }
}

}  // namespace
}  // namespace facet
