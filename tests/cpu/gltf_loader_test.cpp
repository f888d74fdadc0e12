// glTF loading: the shared sample models, hand-written files checked numerically,
// generated normals and tangents, and malformed inputs that must fail cleanly.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <facet/scene/gltf_loader.h>
#include "support/gltf_files.h"
#include "scene/tangents.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using test::expect_error;

const std::string kModels = std::string(FACET_SHARED_DATA_DIR) + "/models";

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_gltf_test_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

void write_file(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// Builds a .gltf with one external .bin: each add() appends a bufferView and an accessor.
struct GltfWriter {
    std::string bin;
    std::vector<std::string> views, accessors;

    template <class T>
    int add(const std::vector<T>& data, int component_type, const char* type, size_t count,
            const std::string& extra = "") {
        while (bin.size() % 4 != 0) bin.push_back('\0');
        size_t offset = bin.size();
        bin.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(T));
        views.push_back(R"({"buffer": 0, "byteOffset": )" + std::to_string(offset) + R"(, "byteLength": )" +
                        std::to_string(data.size() * sizeof(T)) + "}");
        accessors.push_back(R"({"bufferView": )" + std::to_string(views.size() - 1) + R"(, "componentType": )" +
                            std::to_string(component_type) + R"(, "count": )" + std::to_string(count) +
                            R"(, "type": ")" + type + "\"" + extra + "}");
        return int(accessors.size() - 1);
    }

    static std::string join(const std::vector<std::string>& items) {
        std::string out;
        for (const std::string& item : items) out += (out.empty() ? "" : ",\n    ") + item;
        return out;
    }

    // `members`: the rest of the top-level object (meshes, nodes, ...), without a trailing comma.
    std::string json(const std::string& bin_name, const std::string& members) const {
        return "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"buffers\": [{\"uri\": \"" + bin_name +
               "\", \"byteLength\": " + std::to_string(bin.size()) + "}],\n  \"bufferViews\": [\n    " + join(views) +
               "],\n  \"accessors\": [\n    " + join(accessors) + "],\n  " + members + "\n}\n";
    }
};

// A triangle (0,0,0) (1,0,0) (0,1,0) with uint16 indices, drawn by one node.
struct TriangleFile {
    std::string json, bin;
};

TriangleFile triangle(std::vector<uint16_t> indices = {0, 1, 2},
                      std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0}) {
    GltfWriter w;
    w.add(positions, 5126, "VEC3", 3);
    w.add(indices, 5123, "SCALAR", indices.size());
    std::string members = R"("meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "nodes": [{"mesh": 0}],
  "scenes": [{"nodes": [0]}],
  "scene": 0)";
    return {w.json("tri.bin", members), w.bin};
}

void expect_near(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-5f) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
}

void expect_near(const glm::mat4& actual, const glm::mat4& expected) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(actual[c][r], expected[c][r], 1e-5f) << "column " << c << " row " << r;
}

glm::vec3 transform(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

// Invariants every loaded scene must satisfy. `solid`: no primitive is flat.
void check_scene(const Scene& scene, const std::string& path, bool solid = true) {
    EXPECT_EQ(scene.source, path);
    EXPECT_EQ(scene.content_hash.size(), 16u);
    for (const Primitive& p : scene.primitives) {
        ASSERT_LE(size_t(p.first_index) + p.index_count, scene.indices.size());
        ASSERT_LE(size_t(p.vertex_offset) + p.vertex_count, scene.vertices.size());
        ASSERT_LT(p.material, scene.materials.size());
        EXPECT_EQ(p.index_count % 3, 0u);
        for (uint32_t i = 0; i < p.index_count; ++i) ASSERT_LT(scene.indices[p.first_index + i], p.vertex_count);
        for (int a = 0; a < 3; ++a) {
            EXPECT_TRUE(std::isfinite(p.bounds_min[a]) && std::isfinite(p.bounds_max[a]));
            if (solid) {
                EXPECT_LT(p.bounds_min[a], p.bounds_max[a]);
            }
            EXPECT_LE(p.bounds_min[a], p.bounds_max[a]);
        }
        for (uint32_t v = 0; v < p.vertex_count; ++v) {
            const Vertex& vertex = scene.vertices[p.vertex_offset + v];
            ASSERT_NEAR(glm::length(vertex.normal), 1.0f, 1e-3f) << "vertex " << v;
            for (int a = 0; a < 3; ++a) {
                ASSERT_GE(vertex.position[a], p.bounds_min[a]);
                ASSERT_LE(vertex.position[a], p.bounds_max[a]);
            }
        }
    }
    for (const Material& m : scene.materials)
        for (const TextureRef* ref : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                                      &m.occlusion_texture, &m.emissive_texture}) {
            EXPECT_LT(ref->image, int(scene.images.size()));
            EXPECT_LT(ref->sampler, int(scene.samplers.size()));
        }
    for (const TextureImage& image : scene.images)
        EXPECT_EQ(image.rgba.size(), size_t(image.width) * image.height * 4) << image.name;
    auto [lo, hi] = scene.world_bounds();
    for (int a = 0; a < 3; ++a) {
        EXPECT_TRUE(std::isfinite(lo[a]) && std::isfinite(hi[a]));
        if (solid) {
            EXPECT_LT(lo[a], hi[a]);
        }
        EXPECT_LE(lo[a], hi[a]);
    }
}

// Tangents the loader generated: unit, orthogonal to the normal, w = +-1.
void check_generated_tangents(const Scene& scene, const Primitive& p) {
    for (uint32_t v = 0; v < p.vertex_count; ++v) {
        const Vertex& vertex = scene.vertices[p.vertex_offset + v];
        glm::vec3 t(vertex.tangent);
        ASSERT_NEAR(glm::length(t), 1.0f, 1e-3f) << "vertex " << v;
        ASSERT_NEAR(glm::dot(t, vertex.normal), 0.0f, 1e-3f) << "vertex " << v;
        ASSERT_EQ(std::abs(vertex.tangent.w), 1.0f) << "vertex " << v;
    }
}

Scene load_ok(const std::string& path) {
    Result<Scene> scene = load_gltf(path);
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(scene).value() : Scene{};
}

// ---------------------------------------------------------------- shared models

// Counts below were read from the files' JSON (accessor counts, image headers).
TEST(GltfLoader, DamagedHelmet) {
    std::string path = kModels + "/DamagedHelmet.glb";
    Scene scene = load_ok(path);
    check_scene(scene, path);
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.primitives.size(), 1u);
    EXPECT_EQ(scene.primitives[0].vertex_count, 14556u);
    EXPECT_EQ(scene.primitives[0].index_count, 46356u);
    ASSERT_EQ(scene.materials.size(), 1u);
    const Material& m = scene.materials[0];
    EXPECT_EQ(m.name, "Material_MR");
    EXPECT_EQ(m.base_color_texture.image, 0);
    EXPECT_EQ(m.metallic_roughness_texture.image, 1);
    EXPECT_EQ(m.emissive_texture.image, 2);
    EXPECT_EQ(m.occlusion_texture.image, 3);
    EXPECT_EQ(m.normal_texture.image, 4);
    expect_near(m.emissive, glm::vec3(1.0f));
    ASSERT_EQ(scene.images.size(), 5u);
    for (const TextureImage& image : scene.images) {
        EXPECT_EQ(image.width, 2048u);
        EXPECT_EQ(image.height, 2048u);
    }
    ASSERT_EQ(scene.samplers.size(), 1u);
    EXPECT_EQ(scene.samplers[0], TextureSampler{});
    ASSERT_EQ(scene.instances.size(), 1u);
    expect_near(scene.instances[0].world, glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0)));
    // No TANGENT in the file but a normal texture: the loader generates them.
    check_generated_tangents(scene, scene.primitives[0]);
}

TEST(GltfLoader, Suzanne) {
    std::string path = kModels + "/suzanne/02_suzanne.gltf";
    Scene scene = load_ok(path);
    check_scene(scene, path);
    ASSERT_EQ(scene.primitives.size(), 1u);
    EXPECT_EQ(scene.primitives[0].vertex_count, 2160u);
    EXPECT_EQ(scene.primitives[0].index_count, 11808u);
    ASSERT_EQ(scene.images.size(), 3u);
    for (const TextureImage& image : scene.images) {
        EXPECT_EQ(image.width, 1024u);
        EXPECT_EQ(image.height, 1024u);
    }
    EXPECT_EQ(scene.images[0].name, "02_Suzanne_BaseColor.png");
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].normal_texture.image, 1);
    EXPECT_EQ(scene.materials[0].normal_texture.sampler, 0);
    ASSERT_EQ(scene.instances.size(), 1u);
    expect_near(glm::vec3(scene.instances[0].world[3]), glm::vec3(0.26462316f, -0.63917279f, -0.26921701f));
    EXPECT_TRUE(scene.cameras.empty());  // its "Camera" node has no camera
}

// Suzanne's exported (MikkTSpace) tangents: ours, generated from the same data, must
// agree with them in direction and handedness on nearly every vertex.
TEST(GltfLoader, GeneratedTangentsMatchExportedOnes) {
    Scene scene = load_ok(kModels + "/suzanne/02_suzanne.gltf");
    ASSERT_EQ(scene.primitives.size(), 1u);
    const Primitive& p = scene.primitives[0];
    std::vector<Vertex> vertices(scene.vertices.begin() + p.vertex_offset,
                                 scene.vertices.begin() + p.vertex_offset + p.vertex_count);
    std::vector<uint32_t> indices(scene.indices.begin() + p.first_index,
                                  scene.indices.begin() + p.first_index + p.index_count);
    generate_tangents(vertices, indices);
    size_t agree = 0;
    for (size_t v = 0; v < vertices.size(); ++v) {
        const glm::vec4& exported = scene.vertices[p.vertex_offset + v].tangent;
        if (glm::dot(glm::vec3(vertices[v].tangent), glm::normalize(glm::vec3(exported))) > 0.9f &&
            vertices[v].tangent.w == exported.w)
            ++agree;
    }
    EXPECT_GT(double(agree) / double(vertices.size()), 0.95) << agree << " of " << vertices.size();
}

TEST(GltfLoader, TeapotAndTorusKnot) {
    struct Expected {
        const char* file;
        uint32_t vertices, indices;
    };
    for (Expected e : {Expected{"teapot.gltf", 4690, 27384}, Expected{"torusknot.gltf", 1573, 8640}}) {
        SCOPED_TRACE(e.file);
        std::string path = kModels + "/" + e.file;
        Scene scene = load_ok(path);
        check_scene(scene, path);
        ASSERT_EQ(scene.primitives.size(), 1u);
        EXPECT_EQ(scene.primitives[0].vertex_count, e.vertices);
        EXPECT_EQ(scene.primitives[0].index_count, e.indices);
        EXPECT_EQ(scene.materials.size(), 1u);
        EXPECT_TRUE(scene.images.empty());
        EXPECT_EQ(scene.instances.size(), 1u);
    }
}

TEST(GltfLoader, BoxTextured) {
    std::string path = kModels + "/box_textured/BoxTextured.gltf";
    Scene scene = load_ok(path);
    check_scene(scene, path);
    ASSERT_EQ(scene.primitives.size(), 1u);
    EXPECT_EQ(scene.primitives[0].vertex_count, 24u);
    EXPECT_EQ(scene.primitives[0].index_count, 36u);
    ASSERT_EQ(scene.images.size(), 1u);
    EXPECT_EQ(scene.images[0].width, 256u);
    EXPECT_EQ(scene.images[0].height, 256u);
    EXPECT_EQ(scene.images[0].name, "CesiumLogoFlat.png");
    ASSERT_EQ(scene.samplers.size(), 1u);  // LINEAR / NEAREST_MIPMAP_LINEAR, REPEAT
    TextureSampler expected;
    expected.min_linear = false;
    EXPECT_EQ(scene.samplers[0], expected);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].metallic, 0.0f);
    EXPECT_EQ(scene.materials[0].base_color_texture.image, 0);
    auto [lo, hi] = scene.world_bounds();
    expect_near(lo, glm::vec3(-0.5f));
    expect_near(hi, glm::vec3(0.5f));

    Scene again = load_ok(path);
    EXPECT_EQ(again.content_hash, scene.content_hash);
    EXPECT_NE(load_ok(kModels + "/teapot.gltf").content_hash, scene.content_hash);
}

// ---------------------------------------------------------------- hand-written files

TEST(GltfLoader, NodeHierarchy) {
    TempDir dir;
    TriangleFile tri = triangle();
    write_file(dir.file("tri.bin"), tri.bin);
    std::string json = replaced(tri.json, R"("nodes": [{"mesh": 0}])", R"("nodes": [
    {"name": "parent", "mesh": 0, "translation": [10, 0, 0], "scale": [2, 2, 2], "children": [1, 2]},
    {"name": "child", "mesh": 0, "translation": [0, 1, 0], "rotation": [0, 0, 0.70710678, 0.70710678]},
    {"name": "matrix_child", "mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 3, 1]}])");
    write_file(dir.file("tree.gltf"), json);
    Scene scene = load_ok(dir.file("tree.gltf"));
    check_scene(scene, dir.file("tree.gltf"), false);

    ASSERT_EQ(scene.primitives.size(), 1u);
    ASSERT_EQ(scene.instances.size(), 3u);
    EXPECT_EQ(scene.instances[0].node, "parent");
    EXPECT_EQ(scene.instances[1].node, "child");
    EXPECT_EQ(scene.instances[2].node, "matrix_child");
    glm::mat4 parent = glm::scale(glm::translate(glm::mat4(1.0f), {10, 0, 0}), glm::vec3(2.0f));
    glm::mat4 child = glm::rotate(glm::translate(parent, {0, 1, 0}), glm::radians(90.0f), {0, 0, 1});
    expect_near(scene.instances[0].world, parent);
    expect_near(scene.instances[1].world, child);
    expect_near(scene.instances[2].world, glm::translate(parent, {0, 0, 3}));
    // The same, as points: (1,0,0) rotates to (0,1,0), moves to (0,2,0), scales to (0,4,0).
    expect_near(transform(scene.instances[1].world, {1, 0, 0}), {10, 4, 0});
    expect_near(transform(scene.instances[1].world, {0, 1, 0}), {8, 2, 0});
    expect_near(transform(scene.instances[2].world, {1, 0, 0}), {12, 0, 6});

    auto [lo, hi] = scene.world_bounds();
    expect_near(lo, {8, 0, 0});
    expect_near(hi, {12, 4, 6});
    expect_near(scene.primitives[0].bounds_min, {0, 0, 0});
    expect_near(scene.primitives[0].bounds_max, {1, 1, 0});

    // No material: one default material with glTF's defaults, and generated normals.
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].base_color, glm::vec4(1.0f));
    EXPECT_EQ(scene.materials[0].metallic, 1.0f);
    EXPECT_EQ(scene.materials[0].roughness, 1.0f);
    for (const Vertex& v : scene.vertices) expect_near(v.normal, {0, 0, 1});
}

TEST(GltfLoader, EmptySceneHasInvertedBounds) {
    Scene scene;
    auto [lo, hi] = scene.world_bounds();
    EXPECT_GT(lo.x, hi.x);
}

// Interleaved positions and normalized uint16 uvs (byteStride 16), uint8 indices,
// and strip / fan modes converted to lists.
TEST(GltfLoader, InterleavedQuantisedStripAndFan) {
    struct Packed {
        float position[3];
        uint16_t uv[2];
    };
    std::vector<Packed> packed = {{{0, 0, 0}, {0, 65535}}, {{1, 0, 0}, {65535, 65535}},
                                  {{0, 1, 0}, {0, 0}},     {{1, 1, 0}, {65535, 0}}};
    GltfWriter w;
    w.add(packed, 5126, "VEC3", 4);
    w.views.back() = replaced(w.views.back(), "}", R"(, "byteStride": 16})");
    w.accessors.push_back(R"({"bufferView": 0, "byteOffset": 12, "componentType": 5123, "normalized": true, "count": 4, "type": "VEC2"})");
    w.add(std::vector<uint8_t>{0, 1, 2, 3}, 5121, "SCALAR", 4);
    std::string members = R"("meshes": [{"name": "quad", "primitives": [
      {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "mode": 5},
      {"attributes": {"POSITION": 0}, "mode": 6}]}],
  "nodes": [{"mesh": 0}])";
    TempDir dir;
    write_file(dir.file("quad.bin"), w.bin);
    write_file(dir.file("quad.gltf"), w.json("quad.bin", members));
    Scene scene = load_ok(dir.file("quad.gltf"));
    check_scene(scene, dir.file("quad.gltf"), false);
    ASSERT_EQ(scene.primitives.size(), 2u);
    ASSERT_EQ(scene.instances.size(), 2u);  // no scenes: every root node
    const Primitive& strip = scene.primitives[0];
    std::vector<uint32_t> strip_indices(scene.indices.begin() + strip.first_index,
                                        scene.indices.begin() + strip.first_index + strip.index_count);
    EXPECT_EQ(strip_indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
    const Primitive& fan = scene.primitives[1];
    std::vector<uint32_t> fan_indices(scene.indices.begin() + fan.first_index,
                                      scene.indices.begin() + fan.first_index + fan.index_count);
    EXPECT_EQ(fan_indices, (std::vector<uint32_t>{1, 2, 0, 2, 3, 0}));
    EXPECT_EQ(fan.vertex_offset, 4u);
    EXPECT_EQ(scene.vertices[1].uv, glm::vec2(1.0f, 1.0f));
    EXPECT_EQ(scene.vertices[2].uv, glm::vec2(0.0f, 0.0f));
    expect_near(scene.vertices[3].position, {1, 1, 0});
}

TEST(GltfLoader, LightsAndCameras) {
    std::string json = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "directional", "color": [1, 0.5, 0.25], "intensity": 3},
    {"type": "point", "intensity": 100, "range": 20},
    {"type": "spot", "intensity": 50, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}}]}},
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100}},
              {"name": "top", "type": "orthographic", "orthographic": {"xmag": 3, "ymag": 2, "znear": 0.01, "zfar": 50}}],
  "nodes": [
    {"name": "sun", "rotation": [-0.70710678, 0, 0, 0.70710678], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "bulb", "translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"name": "rig", "translation": [0, 5, 0], "children": [3]},
    {"name": "spot", "rotation": [-0.70710678, 0, 0, 0.70710678], "extensions": {"KHR_lights_punctual": {"light": 2}}},
    {"name": "cam", "translation": [0, 1, 5], "camera": 0},
    {"name": "ortho", "translation": [0, 10, 0], "rotation": [-0.70710678, 0, 0, 0.70710678], "camera": 1}],
  "scenes": [{"nodes": [0, 1, 2, 4, 5]}]
})";
    TempDir dir;
    write_file(dir.file("lights.gltf"), json);
    Scene scene = load_ok(dir.file("lights.gltf"));
    ASSERT_EQ(scene.lights.size(), 3u);
    const Light& sun = scene.lights[0];
    EXPECT_EQ(sun.type, LightType::directional);
    expect_near(sun.color, {1, 0.5f, 0.25f});
    EXPECT_FLOAT_EQ(sun.intensity, 3.0f);
    expect_near(sun.direction, {0, -1, 0});
    const Light& bulb = scene.lights[1];
    EXPECT_EQ(bulb.type, LightType::point);
    expect_near(bulb.position, {1, 2, 3});
    expect_near(bulb.color, {1, 1, 1});
    EXPECT_FLOAT_EQ(bulb.intensity, 100.0f);
    EXPECT_FLOAT_EQ(bulb.range, 20.0f);
    const Light& spot = scene.lights[2];
    EXPECT_EQ(spot.type, LightType::spot);
    expect_near(spot.position, {0, 5, 0});
    expect_near(spot.direction, {0, -1, 0});
    EXPECT_FLOAT_EQ(spot.inner_cone, 0.2f);
    EXPECT_FLOAT_EQ(spot.outer_cone, 0.6f);

    ASSERT_EQ(scene.cameras.size(), 2u);
    const Camera& cam = scene.cameras[0];
    EXPECT_EQ(cam.name, "cam");
    EXPECT_FALSE(cam.orthographic);
    expect_near(cam.position, {0, 1, 5});
    expect_near(cam.target, {0, 1, 4});
    expect_near(cam.up, {0, 1, 0});
    EXPECT_FLOAT_EQ(cam.yfov, 0.8f);
    EXPECT_FLOAT_EQ(cam.znear, 0.1f);
    EXPECT_FLOAT_EQ(cam.zfar, 100.0f);
    const Camera& top = scene.cameras[1];
    EXPECT_EQ(top.name, "top");
    EXPECT_TRUE(top.orthographic);
    expect_near(top.position, {0, 10, 0});
    expect_near(top.target, {0, 9, 0});
    expect_near(top.up, {0, 0, -1});
    EXPECT_FLOAT_EQ(top.ymag, 2.0f);
    EXPECT_FLOAT_EQ(top.zfar, 50.0f);

    EXPECT_TRUE(scene.instances.empty());
    auto [lo, hi] = scene.world_bounds();
    EXPECT_GT(lo.x, hi.x);
}

// A quad with a normal-mapped material and no TANGENT: the loader generates them.
TEST(GltfLoader, GeneratesTangentsForNormalMappedMaterial) {
    TempDir dir;
    fs::copy_file(kModels + "/box_textured/CesiumLogoFlat.png", dir.file("normal.png"));
    GltfWriter w;
    w.add(std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, 5126, "VEC3", 4);
    w.add(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}, 5126, "VEC2", 4);
    w.add(std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, 5125, "SCALAR", 6);
    std::string members = R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
  "materials": [{"name": "bumpy", "normalTexture": {"index": 0, "scale": 0.5}, "occlusionTexture": {"index": 0, "strength": 0.25},
                 "emissiveFactor": [1, 0.5, 0], "alphaMode": "MASK", "alphaCutoff": 0.3, "doubleSided": true,
                 "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}],
  "textures": [{"source": 0, "sampler": 0}],
  "samplers": [{"magFilter": 9728, "minFilter": 9729, "wrapS": 33071, "wrapT": 33648}],
  "images": [{"uri": "normal.png"}],
  "nodes": [{"mesh": 0}],
  "scenes": [{"nodes": [0]}])";
    write_file(dir.file("quad.bin"), w.bin);
    write_file(dir.file("quad.gltf"), w.json("quad.bin", members));
    Scene scene = load_ok(dir.file("quad.gltf"));
    check_scene(scene, dir.file("quad.gltf"), false);
    ASSERT_EQ(scene.vertices.size(), 4u);
    for (const Vertex& v : scene.vertices) {
        expect_near(v.normal, {0, 0, 1});
        expect_near(glm::vec3(v.tangent), {1, 0, 0});
        EXPECT_EQ(v.tangent.w, 1.0f);
    }
    const Material& m = scene.materials.at(0);
    EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
    EXPECT_FLOAT_EQ(m.occlusion_strength, 0.25f);
    expect_near(m.emissive, {4, 2, 0});
    EXPECT_EQ(m.alpha_mode, AlphaMode::mask);
    EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.3f);
    EXPECT_TRUE(m.double_sided);
    ASSERT_EQ(scene.samplers.size(), 1u);
    EXPECT_FALSE(scene.samplers[0].mag_linear);
    EXPECT_TRUE(scene.samplers[0].min_linear);
    EXPECT_FALSE(scene.samplers[0].use_mips);
    EXPECT_EQ(scene.samplers[0].wrap_u, 1u);
    EXPECT_EQ(scene.samplers[0].wrap_v, 2u);
}

// ---------------------------------------------------------------- normals and tangents

std::vector<Vertex> quad(std::vector<glm::vec2> uvs) {
    std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    std::vector<Vertex> vertices(4);
    for (size_t i = 0; i < 4; ++i) {
        vertices[i].position = positions[i];
        vertices[i].uv = uvs[i];
    }
    return vertices;
}

const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

TEST(Tangents, QuadTangentsAndHandedness) {
    // The image's top-left at the quad's top-left (glTF v runs down): right-handed, w = +1.
    std::vector<Vertex> upright = quad({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    generate_normals(upright, kQuadIndices);
    generate_tangents(upright, kQuadIndices);
    for (const Vertex& v : upright) {
        expect_near(v.normal, {0, 0, 1});
        expect_near(glm::vec3(v.tangent), {1, 0, 0});
        EXPECT_EQ(v.tangent.w, 1.0f);
    }
    // Mirrored in u: the tangent flips and so does the handedness.
    std::vector<Vertex> mirrored = quad({{1, 1}, {0, 1}, {0, 0}, {1, 0}});
    generate_normals(mirrored, kQuadIndices);
    generate_tangents(mirrored, kQuadIndices);
    for (const Vertex& v : mirrored) {
        expect_near(glm::vec3(v.tangent), {-1, 0, 0});
        EXPECT_EQ(v.tangent.w, -1.0f);
    }
}

TEST(Tangents, GramSchmidtAgainstTiltedNormals) {
    std::vector<Vertex> vertices = quad({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    for (Vertex& v : vertices) v.normal = glm::normalize(glm::vec3(1, 0, 1));
    generate_tangents(vertices, kQuadIndices);
    // (1,0,0) minus its projection on the normal: (0.5, 0, -0.5), normalised.
    for (const Vertex& v : vertices) expect_near(glm::vec3(v.tangent), {0.70710678f, 0, -0.70710678f});
}

TEST(Tangents, AreaWeightedNormals) {
    // Triangle A (area 0.5) faces +Z; triangle B (area 1) faces -Y. They share vertices 0 and 1.
    std::vector<Vertex> vertices(4);
    vertices[0].position = {0, 0, 0};
    vertices[1].position = {1, 0, 0};
    vertices[2].position = {0, 1, 0};
    vertices[3].position = {0, 0, -2};
    std::vector<uint32_t> indices = {0, 1, 2, 0, 3, 1};
    generate_normals(vertices, indices);
    glm::vec3 shared = glm::vec3(0, -2, 1) / std::sqrt(5.0f);
    expect_near(vertices[0].normal, shared);
    expect_near(vertices[1].normal, shared);
    expect_near(vertices[2].normal, {0, 0, 1});
    expect_near(vertices[3].normal, {0, -1, 0});
}

// ---------------------------------------------------------------- bad inputs

// Writes the triangle (JSON edited by `edit`) and expects loading it to fail.
template <class Edit>
void expect_triangle_error(const std::string& phrase, Edit edit, std::vector<uint16_t> indices = {0, 1, 2},
                           std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0}) {
    TempDir dir;
    TriangleFile tri = triangle(indices, positions);
    write_file(dir.file("tri.bin"), tri.bin);
    write_file(dir.file("bad.gltf"), edit(tri.json));
    expect_error(dir.file("bad.gltf"), phrase);
}

TEST(GltfLoaderErrors, MissingFile) {
    TempDir dir;
    expect_error(dir.file("nothing.gltf"), "file not found");
}

TEST(GltfLoaderErrors, InvalidJson) {
    TempDir dir;
    write_file(dir.file("broken.gltf"), R"({"asset": {"version": "2.0"}, "meshes": [)");
    expect_error(dir.file("broken.gltf"), "parse error");
}

TEST(GltfLoaderErrors, MissingBuffer) {
    expect_triangle_error("File not found : missing.bin",
                          [](std::string json) { return replaced(json, "tri.bin", "missing.bin"); });
}

TEST(GltfLoaderErrors, AccessorOutOfItsBufferView) {
    expect_triangle_error("accessor 0 (offset 0, stride 12, count 4) exceeds its bufferView 0 (36 bytes)",
                          [](std::string json) {
                              return replaced(json, R"("count": 3, "type": "VEC3")", R"("count": 4, "type": "VEC3")");
                          });
}

TEST(GltfLoaderErrors, PositionOfWrongType) {
    expect_triangle_error("mesh 'tri' primitive 0: POSITION must be VEC3 FLOAT", [](std::string json) {
        return replaced(json, R"("count": 3, "type": "VEC3")", R"("count": 3, "type": "VEC2")");
    });
}

TEST(GltfLoaderErrors, IndexBeyondVertexCount) {
    expect_triangle_error("mesh 'tri' primitive 0: index 7 >= vertex count 3", [](std::string json) { return json; },
                          {0, 1, 7});
}

TEST(GltfLoaderErrors, MaterialIndexOutOfRange) {
    expect_triangle_error("mesh 'tri' primitive 0: material 5 out of range", [](std::string json) {
        return replaced(json, R"("indices": 1})", R"("indices": 1, "material": 5})");
    });
}

TEST(GltfLoaderErrors, CorruptPng) {
    TempDir dir;
    TriangleFile tri = triangle();
    write_file(dir.file("tri.bin"), tri.bin);
    write_file(dir.file("bad.png"), std::string("\x89PNG\r\n\x1a\n", 8) + "definitely not zlib data");
    std::string json = replaced(tri.json, R"("indices": 1})", R"("indices": 1, "material": 0})");
    json = replaced(json, R"("nodes":)", R"("materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
  "textures": [{"source": 0}],
  "images": [{"uri": "bad.png"}],
  "nodes":)");
    write_file(dir.file("bad.gltf"), json);
    expect_error(dir.file("bad.gltf"), "image 'bad.png' could not be decoded");
}

TEST(GltfLoaderErrors, NodeCycle) {
    expect_triangle_error("node hierarchy has a cycle", [](std::string json) {
        return replaced(json, R"("nodes": [{"mesh": 0}])", R"("nodes": [{"mesh": 0, "children": [1]}, {"children": [0]}])");
    });
}

TEST(GltfLoaderErrors, TruncatedGlb) {
    std::ifstream in(kModels + "/DamagedHelmet.glb", std::ios::binary);
    std::string bytes(4096, '\0');
    in.read(bytes.data(), std::streamsize(bytes.size()));
    ASSERT_TRUE(in);
    TempDir dir;
    write_file(dir.file("cut.glb"), bytes);
    expect_error(dir.file("cut.glb"), "truncated .glb");
    write_file(dir.file("tiny.glb"), bytes.substr(0, 10));
    expect_error(dir.file("tiny.glb"), "truncated .glb");
}

TEST(GltfLoaderErrors, MoreBrokenReferences) {
    expect_triangle_error("bufferView 1 (offset 36, length 600) exceeds buffer 0 (42 bytes)", [](std::string json) {
        return replaced(json, R"("byteOffset": 36, "byteLength": 6)", R"("byteOffset": 36, "byteLength": 600)");
    });
    expect_triangle_error("node 0: mesh 3 out of range",
                          [](std::string json) { return replaced(json, R"({"mesh": 0})", R"({"mesh": 3})"); });
    expect_triangle_error("scene 0: node 9 out of range",
                          [](std::string json) { return replaced(json, R"("nodes": [0])", R"("nodes": [9])"); });
    // Points and lines are drawn now (gltf_core_test); an unknown mode is still refused.
    expect_triangle_error("unknown primitive mode 9", [](std::string json) {
        return replaced(json, R"("indices": 1})", R"("indices": 1, "mode": 9})");
    });
    expect_triangle_error("indices must be SCALAR", [](std::string json) {
        return replaced(json, R"("componentType": 5123)", R"("componentType": 5122)");
    });
    // TEXCOORD_1 is loaded now (gltf_core_test); a third set is still refused by name.
    expect_triangle_error("material 'm': baseColorTexture uses TEXCOORD_2", [](std::string json) {
        json = replaced(json, R"("indices": 1})", R"("indices": 1, "material": 0})");
        return replaced(json, R"("nodes":)", R"("materials": [{"name": "m", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 2}}}],
  "textures": [{"source": 0}], "images": [{"uri": "x.png"}],
  "nodes":)");
    });
    expect_triangle_error("requires unsupported extension KHR_made_up_extension", [](std::string json) {
        return replaced(json, R"("meshes":)", R"("extensionsRequired": ["KHR_made_up_extension"],
  "meshes":)");
    });
    expect_triangle_error("vertex 1 position is not finite", [](std::string json) { return json; }, {0, 1, 2},
                          {0, 0, 0, 1, NAN, 0, 0, 1, 0});
}

}  // namespace
}  // namespace facet
