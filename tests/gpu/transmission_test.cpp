// KHR_materials_transmission and KHR_materials_volume drawn on lavapipe, each from a small
// file written here and checked by pixels against values computed here from the
// extensions' equations: a smooth glass quad shows the opaque scene behind it and the
// environment beside it, tinted by its base colour and weighted by 1 - F; a volume attenuates
// by Beer-Lambert over its thickness; a light behind a rough glass shines through its lobe.
// Single-sample 64x64 frames under builtin:white (radiance 1 everywhere).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <facet/render/render_job.h>
#include <facet/scene/gltf_loader.h>
#include "support/gltf_files.h"
#include "support/gpu_test.h"
#include "support/tiny_session.h"

namespace facet {
namespace {

using namespace test;

constexpr uint32_t kSize = 64;
constexpr double kPi = 3.14159265358979323846;

glm::vec3 at(const std::vector<float>& rgba, uint32_t x, uint32_t y) {
    const float* p = &rgba[(size_t(y) * kSize + x) * 4];
    return {p[0], p[1], p[2]};
}

float off(glm::vec3 a, glm::vec3 b) {
    return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)});
}

// Two quads of 2x2 metres facing +Z: mesh 0 at z = 0 with material 0 (the glass), and an
// unlit red one (material 1) spanning x in [-4, 0] at z = -1, behind the glass's left half.
std::string two_quads(const std::string& glass) {
    return R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2, "NORMAL": 3}, "indices": 1,
                  "material": 0}]},
             {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 3}, "indices": 1, "material": 1}]}],
  "materials": [)" + glass + R"(,
    {"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}, "extensions": {"KHR_materials_unlit": {}}}],
  "nodes": [{"mesh": 0}, {"mesh": 1, "translation": [-2, 0, -1], "scale": [2, 2, 1]}],
  "scenes": [{"nodes": [0, 1]}],
  "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_unlit"])";
}

GltfBuilder quads() {
    GltfBuilder b;
    const std::vector<float> quad = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    b.add(quad, kFloat, "VEC3", 4);
    b.add(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, kUshort, "SCALAR", 6);
    b.add(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}, kFloat, "VEC2", 4);
    b.add(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 4);
    return b;
}

std::string glass(const std::string& base, double roughness, const std::string& extensions) {
    return R"({"pbrMetallicRoughness": {"baseColorFactor": [)" + base + R"(, 1], "metallicFactor": 0,
               "roughnessFactor": )" + std::to_string(roughness) + R"(}, "extensions": {)" + extensions + "}}";
}

class TransmissionTest : public GpuTest {
protected:
    GltfTempDir dir{"transmission"};

    RenderJob job() {
        RenderJob job = head_on_job("builtin:white", kSize);
        job.programs = &gpu_programs();  // the suite's pipelines, each built once
        job.ibl.lut.size = 64;
        job.ibl.lut.sample_count = 1024;
        return job;
    }
    std::vector<float> render(const std::string& name, const std::string& glass_material, RenderJob j,
                              std::vector<float>* reference = nullptr) {
        const std::string path = quads().write(dir, name, two_quads(glass_material));
        Result<Scene> scene = load_gltf(path);
        EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
        if (!scene) return {};
        auto session = RenderSession::create(ctx(), j, std::move(*scene));
        EXPECT_TRUE(session) << (session ? "" : session.error().message);
        if (!session) return {};
        auto images = (*session)->render_frame();
        EXPECT_TRUE(images) << (images ? "" : images.error().message);
        if (reference) {
            ReferenceSettings settings;
            settings.min_samples = settings.max_samples = 1024;
            auto exact = (*session)->render_reference(settings);
            EXPECT_TRUE(exact) << (exact ? "" : exact.error().message);
            if (exact) *reference = exact->hdr;
        }
        return images ? images->hdr : std::vector<float>{};
    }
};

// Smooth glass seen head-on under uniform radiance 1: it reflects F0 = 0.04 of it and
// transmits the rest (1 - F0, the split sum's (A + B) - (F0 A + B) at roughness 0) tinted by
// its base colour: the environment on the right, the red quad's radiance (1, 0, 0) on the
// left, where the opaque scene lies behind.
TEST_F(TransmissionTest, SmoothGlassShowsTheSceneBehindTinted) {
    const glm::vec3 albedo(1.0f, 0.5f, 0.25f);
    const std::vector<float> hdr =
        render("thin", glass("1, 0.5, 0.25", 0.0, R"("KHR_materials_transmission": {"transmissionFactor": 1})"), job());
    ASSERT_EQ(hdr.size(), kSize * kSize * 4);
    const glm::vec3 beside = 0.04f + 0.96f * albedo, behind = 0.04f + 0.96f * albedo * glm::vec3(1, 0, 0);
    std::printf("beside %.2e, behind %.2e off\n", off(at(hdr, 40, 32), beside), off(at(hdr, 24, 32), behind));
    EXPECT_LT(off(at(hdr, 40, 32), beside), 0.01f);
    EXPECT_LT(off(at(hdr, 24, 32), behind), 0.01f);
    // Outside the glass: the red quad as it is, and nothing (alpha 0, no skybox) beside it.
    EXPECT_LT(off(at(hdr, 2, 32), glm::vec3(1, 0, 0)), 1e-5f);
    EXPECT_LT(off(at(hdr, 62, 32), glm::vec3(0)), 1e-6f);
    // Half the transmission: half the light goes to the diffuse lobe (irradiance 1 x albedo).
    const std::vector<float> half =
        render("half", glass("1, 0.5, 0.25", 0.0, R"("KHR_materials_transmission": {"transmissionFactor": 0.5})"), job());
    ASSERT_EQ(half.size(), kSize * kSize * 4);
    EXPECT_LT(off(at(half, 40, 32), 0.04f + 0.96f * albedo), 0.01f);
    EXPECT_LT(off(at(half, 24, 32), 0.04f + 0.96f * albedo * glm::vec3(1.0f, 0.5f, 0.5f)), 0.01f);
    // 4x MSAA: the background is drawn single-sample, the glass reads it the same.
    RenderJob msaa = job();
    msaa.frame.samples = 4;
    const std::vector<float> four =
        render("msaa", glass("1, 0.5, 0.25", 0.0, R"("KHR_materials_transmission": {"transmissionFactor": 1})"), msaa);
    ASSERT_EQ(four.size(), kSize * kSize * 4);
    EXPECT_LT(off(at(four, 40, 32), beside), 0.01f);
    EXPECT_LT(off(at(four, 24, 32), behind), 0.01f);
}

// A volume of thickness 0.5 m, attenuation colour (0.5, 0.8, 1) at 0.25 m: the light through
// it keeps colour^(0.5 / 0.25) = (0.25, 0.64, 1) (the view ray crosses it head-on).
TEST_F(TransmissionTest, VolumeAttenuatesByBeerLambert) {
    const std::vector<float> hdr = render(
        "volume", glass("1, 1, 1", 0.0, R"("KHR_materials_transmission": {"transmissionFactor": 1},
            "KHR_materials_volume": {"thicknessFactor": 0.5, "attenuationDistance": 0.25,
                                     "attenuationColor": [0.5, 0.8, 1]})"),
        job());
    ASSERT_EQ(hdr.size(), kSize * kSize * 4);
    const glm::vec3 kept(0.25f, 0.64f, 1.0f);
    std::printf("beside %.2e, behind %.2e off\n", off(at(hdr, 40, 32), 0.04f + 0.96f * kept),
                off(at(hdr, 24, 32), 0.04f + 0.96f * kept * glm::vec3(1, 0, 0)));
    EXPECT_LT(off(at(hdr, 40, 32), 0.04f + 0.96f * kept), 0.01f);
    EXPECT_LT(off(at(hdr, 24, 32), 0.04f + 0.96f * kept * glm::vec3(1, 0, 0)), 0.01f);
}

// A directional light of 0.5 lux straight behind a rough glass (roughness 0.5, white): the
// pixel at the centre sees it through the mirrored lobe at h = n, kd D V |n.l| E =
// (1 - 0.04) x 1 / (pi alpha^2) x 0.25 x 0.5 (glTF's height-correlated V at n.v = n.l = 1),
// alpha = 0.25: the frame with the light minus the frame without it.
TEST_F(TransmissionTest, LightBehindRoughGlassShinesThroughItsLobe) {
    const std::string material = glass("1, 1, 1", 0.5, R"("KHR_materials_transmission": {"transmissionFactor": 1})");
    RenderJob lit = job();
    Light behind;
    behind.direction = glm::vec3(0.0f, 0.0f, 1.0f);  // travelling towards the camera
    behind.intensity = 0.5f;
    lit.extra_lights = {behind};
    const std::vector<float> with = render("lit", material, lit), without = render("unlit", material, job());
    ASSERT_EQ(with.size(), kSize * kSize * 4);
    ASSERT_EQ(without.size(), kSize * kSize * 4);
    const double alpha = 0.25, expected = 0.96 / (kPi * alpha * alpha) * 0.25 * 0.5;
    const glm::vec3 d = at(with, 32, 32) - at(without, 32, 32);
    std::printf("through the lobe %.4f, expected %.4f\n", d.x, expected);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(d[c], expected, 0.01 * expected) << c;
}

// The reference mode integrates the same lobes by sampling (the environment behind, not the
// scene: it shades the surface each pixel sees): under uniform light the split sum is exact
// up to the LUT, so rough glass (r 0.5, tinted) reads the same in both where the environment
// lies behind it.
TEST_F(TransmissionTest, ReferenceModeAgreesUnderUniformLight) {
    std::vector<float> reference;
    const std::vector<float> hdr =
        render("reference", glass("1, 0.5, 0.25", 0.5, R"("KHR_materials_transmission": {"transmissionFactor": 0.8})"),
               job(), &reference);
    ASSERT_EQ(hdr.size(), kSize * kSize * 4);
    ASSERT_EQ(reference.size(), kSize * kSize * 4);
    // The mean over a block of 12 x 8 pixels, against the reference's sampling noise.
    glm::dvec3 f(0.0), r(0.0);
    for (uint32_t y = 28; y < 36; ++y)
        for (uint32_t x = 36; x < 48; ++x) {
            f += glm::dvec3(at(hdr, x, y));
            r += glm::dvec3(at(reference, x, y));
        }
    f /= 96.0;
    r /= 96.0;
    std::printf("frame (%.4f %.4f %.4f), reference (%.4f %.4f %.4f)\n", f.x, f.y, f.z, r.x, r.y, r.z);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], r[c], 0.02 * r[c]) << c;
}

}  // namespace
}  // namespace facet
