// The error prediction's probe (render/error_prediction.h) takes the scene's materials:
// its own (roughness, metalness) pairs where few and untextured, the measure's whole
// range for a scene of mirrors; and the groups of issue 13's measure it then speaks for.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>

#include <facet/scene/builtin_scenes.h>
#include "render/error_prediction.h"

namespace facet {
namespace {

std::set<std::pair<float, float>> pairs_of(const Scene& scene) {
    std::set<std::pair<float, float>> pairs;
    for (const Material& m : scene.materials) pairs.insert({m.roughness, m.metallic});
    return pairs;
}

Scene one_material(float roughness, float metallic) {
    Scene scene = builtin_scene("builtin:sphere").value();
    scene.materials.at(0).roughness = roughness;
    scene.materials.at(0).metallic = metallic;
    return scene;
}

TEST(ProbeScene, TheSpheresGridIsProbedWithItsOwnMaterials) {
    const Scene spheres = builtin_scene("builtin:spheres").value();
    const Scene probe = probe_scene(spheres);
    EXPECT_EQ(probe.materials.size(), spheres.materials.size());
    // Its pairs of roughness 0.2 and up (5 columns x 7 rows), each on some sphere.
    std::set<std::pair<float, float>> wanted;
    for (const Material& m : spheres.materials)
        if (m.roughness >= 0.2f) wanted.insert({m.roughness, m.metallic});
    EXPECT_EQ(wanted.size(), 35u);
    EXPECT_EQ(pairs_of(probe), wanted);
    const std::array<bool, 8> groups = material_groups(probe);
    for (size_t g = 0; g < 8; ++g) EXPECT_TRUE(groups[g]) << g;
}

TEST(ProbeScene, OneRoughMetalIsProbedAsThatMetalOnly) {
    const Scene probe = probe_scene(one_material(1.0f, 1.0f));
    EXPECT_EQ(pairs_of(probe), (std::set<std::pair<float, float>>{{1.0f, 1.0f}}));
    const std::array<bool, 8> groups = material_groups(probe);
    for (size_t g = 0; g < 8; ++g) EXPECT_EQ(groups[g], g == 7) << g;  // [0.8,1] metal alone
}

TEST(ProbeScene, MirrorsGetTheMeasuresWholeRange) {
    const Scene probe = probe_scene(one_material(0.05f, 0.0f));
    float r_lo = 1, r_hi = 0, m_lo = 1, m_hi = 0;
    for (const Material& m : probe.materials) {
        r_lo = std::min(r_lo, m.roughness), r_hi = std::max(r_hi, m.roughness);
        m_lo = std::min(m_lo, m.metallic), m_hi = std::max(m_hi, m.metallic);
    }
    EXPECT_FLOAT_EQ(r_lo, 0.2f);
    EXPECT_FLOAT_EQ(r_hi, 1.0f);
    EXPECT_FLOAT_EQ(m_lo, 0.0f);
    EXPECT_FLOAT_EQ(m_hi, 1.0f);
    const std::array<bool, 8> groups = material_groups(probe);
    for (size_t g = 0; g < 8; ++g) EXPECT_TRUE(groups[g]) << g;
}

}  // namespace
}  // namespace facet
