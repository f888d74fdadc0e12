// Skins and morph targets in the pose a glTF file defines (no animation), applied on the
// CPU when the nodes are placed, checked against positions computed here by hand; and
// their malformed inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <facet/scene/gltf_loader.h>
#include "support/gltf_files.h"

namespace facet {
namespace {

using namespace test;

void expect_near(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-5f) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
}

// Two bones along +Y: joint A at the origin, joint B one metre up, rotated 90 degrees
// about +Z. Vertices at x = 0.5 and heights 0, 1, 2: bound to A, half and half, to B.
struct TwoBones {
    GltfBuilder b;
    std::string members;
    explicit TwoBones(const std::string& joints = "[1, 2]") {
        b.add(std::vector<float>{0.5f, 0, 0, 0.5f, 1, 0, 0.5f, 2, 0}, kFloat, "VEC3", 3);
        b.add(std::vector<uint16_t>{0, 1, 2}, kUshort, "SCALAR", 3);
        b.add(std::vector<uint8_t>{0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0}, kUbyte, "VEC4", 3);  // JOINTS_0
        b.add(std::vector<float>{1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0}, kFloat, "VEC4", 3);  // WEIGHTS_0
        // Inverse bind matrices: identity for A, a translation by -1 in y for B (column-major).
        b.add(std::vector<float>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,  //
                                 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1},
              kFloat, "MAT4", 2);
        const float s = std::sqrt(0.5f);
        members = R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 2, "WEIGHTS_0": 3}, "indices": 1}]}],
  "skins": [{"joints": )" + joints + R"(, "inverseBindMatrices": 4}],
  "nodes": [{"name": "skinned", "mesh": 0, "skin": 0, "translation": [10, 0, 0]},
            {"name": "A", "children": [2]},
            {"name": "B", "translation": [0, 1, 0], "rotation": [0, 0, )" + std::to_string(s) + ", " + std::to_string(s) + R"(]}],
  "scenes": [{"nodes": [0, 1]}])";
    }
};

TEST(GltfDeform, TwoBoneSkinPosedByItsJoints) {
    GltfTempDir dir("gltf_deform");
    TwoBones bones;
    Result<Scene> loaded = load_gltf(bones.b.write(dir, "skin", bones.members));
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    const Scene& scene = *loaded;
    ASSERT_EQ(scene.instances.size(), 1u);
    const Instance& instance = scene.instances[0];
    // Skinned vertices are in world space: the skinned node's own translation does not apply.
    EXPECT_EQ(instance.world, glm::mat4(1.0f));
    const Primitive& p = scene.primitives[instance.primitive];
    ASSERT_EQ(p.vertex_count, 3u);
    const Vertex* v = &scene.vertices[p.vertex_offset];
    // B's matrix: translate(0,1,0) rotate90z translate(0,-1,0); rotate90z (x, y) = (-y, x).
    expect_near(v[0].position, {0.5f, 0.0f, 0.0f});   // A alone: unchanged
    expect_near(v[1].position, {0.25f, 1.25f, 0.0f});  // (0.5,1,0) and (0,1.5,0), averaged
    expect_near(v[2].position, {-1.0f, 1.5f, 0.0f});   // B alone
    expect_near(p.bounds_min, {-1.0f, 0.0f, 0.0f});
    expect_near(p.bounds_max, {0.5f, 1.5f, 0.0f});
}

// The same skin under a root scaled by -1 in x: every skin matrix mirrors, so the
// skinned copy's triangle winds the other way round (as a mirrored node's would).
TEST(GltfDeform, MirroringSkinTurnsTheWinding) {
    GltfTempDir dir("gltf_deform");
    TwoBones bones;
    bones.members.replace(bones.members.find(R"({"name": "A", "children": [2]})"), 30,
                          R"({"name": "A", "children": [2], "scale": [-1, 1, 1]})");
    Result<Scene> loaded = load_gltf(bones.b.write(dir, "mirrored_skin", bones.members));
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    const Scene& scene = *loaded;
    ASSERT_EQ(scene.instances.size(), 1u);
    const Primitive& p = scene.primitives[scene.instances[0].primitive];
    ASSERT_EQ(p.index_count, 3u);
    EXPECT_EQ(scene.indices[p.first_index], 0u);
    EXPECT_EQ(scene.indices[p.first_index + 1], 2u);
    EXPECT_EQ(scene.indices[p.first_index + 2], 1u);
    const Vertex* v = &scene.vertices[p.vertex_offset];
    expect_near(v[0].position, {-0.5f, 0.0f, 0.0f});
    expect_near(v[2].position, {1.0f, 1.5f, 0.0f});
}

TEST(GltfDeform, SkinJointThatIsNotANode) {
    GltfTempDir dir("gltf_deform");
    TwoBones bones("[1, 7]");
    expect_error(bones.b.write(dir, "bad_skin", bones.members), "skin 0: joint 7 is not a node (3 nodes)");
}

// A quad with one morph target lifting vertex 2 by 1 in z (and tilting its normal).
struct MorphQuad {
    GltfBuilder b;
    explicit MorphQuad(size_t target_count = 4) {
        b.add(std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, kFloat, "VEC3", 4);
        b.add(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 4);  // NORMAL
        b.add(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, kUshort, "SCALAR", 6);
        std::vector<float> lift(3 * target_count, 0.0f), tilt(3 * target_count, 0.0f);
        if (target_count > 2) lift[3 * 2 + 2] = 1.0f;
        if (target_count > 2) tilt[3 * 2 + 0] = 2.0f;
        b.add(lift, kFloat, "VEC3", target_count);
        b.add(tilt, kFloat, "VEC3", target_count);
    }
    std::string members(const std::string& node_weights) const {
        return R"("meshes": [{"weights": [0.25], "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2,
      "targets": [{"POSITION": 3, "NORMAL": 4}]}]}],
  "nodes": [{"name": "own", "mesh": 0)" + node_weights + R"(}, {"name": "mesh's", "mesh": 0, "translation": [3, 0, 0]}],
  "scenes": [{"nodes": [0, 1]}])";
    }
};

TEST(GltfDeform, MorphWithDefaultWeightsNodeOverMesh) {
    GltfTempDir dir("gltf_deform");
    MorphQuad quad;
    Result<Scene> loaded = load_gltf(quad.b.write(dir, "morph", quad.members(R"(, "weights": [0.5])")));
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    const Scene& scene = *loaded;
    ASSERT_EQ(scene.instances.size(), 2u);
    const float weight[] = {0.5f, 0.25f};  // the node's own, then the mesh's
    for (size_t i = 0; i < 2; ++i) {
        const Instance& instance = scene.instances[i];
        const Primitive& p = scene.primitives[instance.primitive];
        const Vertex* v = &scene.vertices[p.vertex_offset];
        expect_near(v[2].position, {1.0f, 1.0f, weight[i]});
        expect_near(v[0].position, {0.0f, 0.0f, 0.0f});
        expect_near(v[2].normal, glm::normalize(glm::vec3(2.0f * weight[i], 0.0f, 1.0f)));
        expect_near(v[1].normal, {0.0f, 0.0f, 1.0f});
        EXPECT_NEAR(p.bounds_max.z, weight[i], 1e-6f);
        // Morphing keeps the node's transform.
        EXPECT_EQ(instance.world[3], glm::vec4(i == 0 ? 0.0f : 3.0f, 0.0f, 0.0f, 1.0f));
    }
}

TEST(GltfDeform, MorphTargetWithTheWrongCount) {
    GltfTempDir dir("gltf_deform");
    MorphQuad quad(3);
    expect_error(quad.b.write(dir, "bad_morph", quad.members("")),
                 "mesh 0 primitive 0 morph target 0: NORMAL has 3 elements, POSITION has 4");
    MorphQuad weights;
    expect_error(weights.b.write(dir, "bad_weights", weights.members(R"(, "weights": [0.5, 0.5])")),
                 "2 morph weights for 1 morph targets");
}

}  // namespace
}  // namespace facet
