// The glTF core features drawn on lavapipe, each from a small file written here and
// checked by pixels against values computed here: OPAQUE ignoring alpha, vertex colours,
// KHR_materials_ior and KHR_materials_specular, KHR_materials_unlit (frame and reference
// mode), a texture on TEXCOORD_1, KHR_texture_transform, a mirrored cube shaded and culled right, lines and points
// drawn unlit, and a flat model framed by the default camera. Single-sample frames, so
// that every covered pixel is exact; tolerances are stated per check.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <facet/render/gpu_scene.h>
#include <facet/render/render_job.h>
#include <facet/scene/gltf_loader.h>
#include "support/gltf_files.h"
#include "support/gpu_test.h"
#include "support/tiny_session.h"

namespace facet {
namespace {

using namespace test;

constexpr uint32_t kSize = 64;

struct Pixel {
    float r, g, b, a;
};

// An 8-bit sRGB texel's value in linear light (the sRGB curve, IEC 61966-2-1).
double srgb(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

Pixel at(const std::vector<float>& rgba, uint32_t x, uint32_t y) {
    const float* p = &rgba[(size_t(y) * kSize + x) * 4];
    return {p[0], p[1], p[2], p[3]};
}

// An RGBA8 PNG of `width` x `height` texels, row 0 the image's top (glTF's v = 0).
::testing::AssertionResult write_png(const std::string& path, int width, int height, const unsigned char* rgba) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out || !out->open(path, OIIO::ImageSpec(width, height, 4, OIIO::TypeDesc::UINT8)) ||
        !out->write_image(OIIO::TypeDesc::UINT8, rgba) || !out->close())
        return ::testing::AssertionFailure() << path << ": " << OIIO::geterror();
    return ::testing::AssertionSuccess();
}

// A 2x2 metre quad at z = 0 facing +Z, with optional extra attributes.
const std::vector<float> kQuad = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
const std::vector<uint16_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

// A builder holding the quad's positions (accessor 0) and indices (accessor 1).
GltfBuilder quad_builder() {
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);
    b.add(kQuadIndices, kUshort, "SCALAR", 6);
    return b;
}

// The same with TEXCOORD_0 spanning the texture once (accessor 2, v = 0 at the top) and
// NORMAL +Z (accessor 3).
GltfBuilder lit_quad_builder() {
    GltfBuilder b = quad_builder();
    std::vector<float> uv0;
    for (size_t i = 0; i < 4; ++i) uv0.insert(uv0.end(), {(kQuad[3 * i] + 1.0f) / 2.0f, (1.0f - kQuad[3 * i + 1]) / 2.0f});
    b.add(uv0, kFloat, "VEC2", 4);
    b.add(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 4);
    return b;
}

// The largest per-channel distance of the centre pixel from `colour`.
float centre_off(const std::vector<float>& rgba, glm::vec3 colour) {
    const Pixel q = at(rgba, kSize / 2, kSize / 2);
    return std::max({std::abs(q.r - colour.x), std::abs(q.g - colour.y), std::abs(q.b - colour.z)});
}

std::string mesh_file(const std::string& attributes, int indices, const std::string& material, int mode = 4,
                      const std::string& node = R"({"mesh": 0})") {
    std::string primitive = R"({"attributes": {)" + attributes + R"(}, "material": 0, "mode": )" + std::to_string(mode);
    if (indices >= 0) primitive += R"(, "indices": )" + std::to_string(indices);
    return R"("meshes": [{"primitives": [)" + primitive + R"(}]}],
  "materials": [)" + material + R"(],
  "nodes": [)" + node + R"(], "scenes": [{"nodes": [0]}])";
}

class GltfFeaturesTest : public GpuTest {
protected:
    GltfTempDir dir{"gltf_features"};

    // The suite's sessions share the test process' pipelines (each variant built once).
    RenderJob job(const std::string& env) {
        RenderJob j = head_on_job(env, kSize);
        j.programs = &gpu_programs();
        return j;
    }
    // Loads `path`, makes every material Lambert-only (metallic 0, no specular lobe: the
    // white furnace then shows albedo exactly), and renders it.
    RenderedImages render(const std::string& path, RenderJob job, bool lambert = true,
                          std::unique_ptr<RenderSession>* keep = nullptr) {
        Result<Scene> scene = load_gltf(path);
        EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
        if (!scene) return {};
        if (lambert)
            for (Material& m : scene->materials) {
                m.metallic = 0.0f;
                m.specular_factor = 0.0f;
            }
        auto session = RenderSession::create(ctx(), job, std::move(*scene));
        EXPECT_TRUE(session) << (session ? "" : session.error().message);
        if (!session) return {};
        auto images = (*session)->render_frame();
        EXPECT_TRUE(images) << (images ? "" : images.error().message);
        if (keep) *keep = std::move(*session);
        return images ? *images : RenderedImages{};
    }
};

// glTF: "OPAQUE: the rendered output is fully opaque and any alpha value is ignored".
TEST_F(GltfFeaturesTest, OpaqueMaterialWithAlphaPointThreeWritesAlphaOne) {
    GltfBuilder b = quad_builder();
    const std::string emissive = R"("emissiveFactor": [0.2, 0.4, 0.6], "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, )";
    const RenderedImages opaque =
        render(b.write(dir, "opaque", mesh_file(R"("POSITION": 0)", 1, "{" + emissive + "0.3]}}")), job("none"), false);
    ASSERT_EQ(opaque.hdr.size(), kSize * kSize * 4);
    const Pixel p = at(opaque.hdr, 32, 32);
    EXPECT_EQ(p.a, 1.0f);
    EXPECT_NEAR(p.r, 0.2f, 1e-5f);
    EXPECT_NEAR(p.g, 0.4f, 1e-5f);
    EXPECT_NEAR(p.b, 0.6f, 1e-5f);
    EXPECT_EQ(at(opaque.hdr, 0, 0).a, 0.0f);  // the background stays transparent
    // MASK: above the cutoff, opaque too; below it, nothing.
    const RenderedImages kept = render(
        b.write(dir, "mask", mesh_file(R"("POSITION": 0)", 1, R"({"alphaMode": "MASK", )" + emissive + "0.7]}}")),
        job("none"), false);
    ASSERT_EQ(kept.hdr.size(), kSize * kSize * 4);
    EXPECT_EQ(at(kept.hdr, 32, 32).a, 1.0f);
    const RenderedImages cut = render(
        b.write(dir, "cut", mesh_file(R"("POSITION": 0)", 1, R"({"alphaMode": "MASK", )" + emissive + "0.3]}}")),
        job("none"), false);
    ASSERT_EQ(cut.hdr.size(), kSize * kSize * 4);
    EXPECT_EQ(at(cut.hdr, 32, 32).a, 0.0f);
}

// Where the ray through pixel (x, y)'s centre meets the plane z = 0.
glm::vec3 on_plane(const CameraView& camera, uint32_t x, uint32_t y) {
    const glm::mat4 inverse = glm::inverse(camera.projection(1.0f) * camera.view());
    const glm::vec2 ndc((x + 0.5f) / kSize * 2.0f - 1.0f, (y + 0.5f) / kSize * 2.0f - 1.0f);
    glm::vec4 a = inverse * glm::vec4(ndc, 1.0f, 1.0f), b = inverse * glm::vec4(ndc, 0.5f, 1.0f);
    const glm::vec3 p = glm::vec3(a) / a.w, q = glm::vec3(b) / b.w;
    return p + (q - p) * (-p.z / (q.z - p.z));
}

// An affine colour field is interpolated exactly by any triangulation, so each covered
// pixel must show base colour x the field at the point it sees (white furnace: radiance
// 1 in, Lambert albedo out, within 2e-3 as WhiteFurnaceLambertSphereIsOneEverywhere).
TEST_F(GltfFeaturesTest, VertexColouredQuad) {
    auto field = [](glm::vec3 p) { return glm::vec3(0.5f + 0.5f * p.x, 0.5f + 0.5f * p.y, 0.25f); };
    std::vector<float> colours;
    for (size_t i = 0; i < 4; ++i) {
        const glm::vec3 c = field({kQuad[3 * i], kQuad[3 * i + 1], 0.0f});
        colours.insert(colours.end(), {c.x, c.y, c.z});
    }
    GltfBuilder b = quad_builder();
    b.add(colours, kFloat, "VEC3", 4);
    const glm::vec3 base(1.0f, 0.8f, 1.0f);
    std::unique_ptr<RenderSession> session;
    const RenderedImages images =
        render(b.write(dir, "colours", mesh_file(R"("POSITION": 0, "COLOR_0": 2)", 1,
                                                 R"({"pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 1, 1]}})")),
               job("builtin:white"), true, &session);
    ASSERT_EQ(images.hdr.size(), kSize * kSize * 4);
    int checked = 0;
    double worst = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const glm::vec3 p = on_plane(session->camera(), x, y);
            if (std::abs(p.x) > 0.95f || std::abs(p.y) > 0.95f) continue;  // away from the edges
            const glm::vec3 expected = base * field(p);
            const Pixel px = at(images.hdr, x, y);
            worst = std::max({worst, double(std::abs(px.r - expected.x)), double(std::abs(px.g - expected.y)),
                              double(std::abs(px.b - expected.z))});
            ++checked;
        }
    EXPECT_GT(checked, 500);
    EXPECT_LT(worst, 2e-3);
}

// KHR_materials_ior and KHR_materials_specular reach the shading: the specular_f0 view
// (what the reference mode and the truth read) holds min(((ior - 1) / (ior + 1))^2 x
// specularColorFactor, 1) per channel and specularFactor exactly; under the white furnace a dielectric with specularFactor 0 is
// Lambert and shows its base colour (within 2e-3, as VertexColouredQuad), where the same
// material without the extension shows more than 1% off it (its specular lobe).
TEST_F(GltfFeaturesTest, IorAndSpecularExtensionsReachTheShading) {
    GltfBuilder b = quad_builder();
    auto material = [](const std::string& extensions) {
        return R"({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.6, 0.7, 1], "metallicFactor": 0,
                   "roughnessFactor": 0.5}, "extensions": {)" + extensions + "}}";
    };
    RenderJob views = job("builtin:white");
    views.frame.views = {View::specular_f0};
    const RenderedImages f0 = render(
        b.write(dir, "ior", mesh_file(R"("POSITION": 0)", 1,
                                      material(R"("KHR_materials_ior": {"ior": 2.42},
                                                 "KHR_materials_specular": {"specularFactor": 0.5,
                                                 "specularColorFactor": [1, 0.5, 8]})"))),
        views, false);
    ASSERT_EQ(f0.views.size(), 1u);
    // Per channel min(F0 x colour, 1): 0.172, 0.086, 1 (clamped).
    const double r = (2.42 - 1.0) / (2.42 + 1.0);
    const Pixel p = at(f0.views[0].second, 32, 32);
    EXPECT_NEAR(p.r, r * r, 1e-6);
    EXPECT_NEAR(p.g, 0.5 * r * r, 1e-6);
    EXPECT_NEAR(p.b, 1.0, 1e-6);
    EXPECT_NEAR(p.a, 0.5, 1e-6);
    const glm::vec3 base(0.5f, 0.6f, 0.7f);
    const RenderedImages lambert = render(
        b.write(dir, "lambert", mesh_file(R"("POSITION": 0)", 1, material(R"("KHR_materials_specular": {"specularFactor": 0})"))),
        job("builtin:white"), false);
    ASSERT_EQ(lambert.hdr.size(), kSize * kSize * 4);
    EXPECT_LT(centre_off(lambert.hdr, base), 2e-3f);
    const RenderedImages plain =
        render(b.write(dir, "plain", mesh_file(R"("POSITION": 0)", 1, material(""))), job("builtin:white"), false);
    ASSERT_EQ(plain.hdr.size(), kSize * kSize * 4);
    EXPECT_GT(centre_off(plain.hdr, base), 0.01f);
}

// KHR_materials_specular's textures: specularTexture's A times specularFactor and
// specularColorTexture's RGB (sRGB) times specularColorFactor, per pixel, into the dielectric
// F0 min(0.04 x colour, 1) and the specular weight (the view the reference mode reads); the
// colour texture through KHR_texture_transform (shifted by half: its texels swap sides).
TEST_F(GltfFeaturesTest, SpecularTexturesReachTheDielectricLobe) {
    // Two images: OpenImageIO writes a PNG's colour divided by its alpha (it takes the
    // pixels as premultiplied).
    const unsigned char strength[] = {0, 0, 0, 128, 0, 0, 0, 255};         // A: left | right
    const unsigned char colour[] = {188, 64, 255, 255, 255, 255, 255, 255};  // RGB: left | right
    ASSERT_TRUE(write_png(dir.file("spec_a.png"), 2, 1, strength));
    ASSERT_TRUE(write_png(dir.file("spec_rgb.png"), 2, 1, colour));
    GltfBuilder b = lit_quad_builder();
    const std::string members =
        mesh_file(R"("POSITION": 0, "TEXCOORD_0": 2, "NORMAL": 3)", 1,
                  R"({"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5},
                      "extensions": {"KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [2, 2, 8],
                        "specularTexture": {"index": 0},
                        "specularColorTexture": {"index": 1, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0]}}}}}})") +
        R"(, "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
  "images": [{"uri": "spec_a.png"}, {"uri": "spec_rgb.png"}], "samplers": [{"magFilter": 9728, "minFilter": 9728}],
  "extensionsUsed": ["KHR_materials_specular", "KHR_texture_transform"])";
    RenderJob views = job("builtin:white");
    views.frame.views = {View::specular_f0};
    const RenderedImages images = render(b.write(dir, "specular_textures", members), views, false);
    ASSERT_EQ(images.views.size(), 1u);
    const Pixel left = at(images.views[0].second, kSize / 2 - 8, kSize / 2);
    const Pixel right = at(images.views[0].second, kSize / 2 + 8, kSize / 2);
    // Left: A 128 from specularTexture, the colour texture's right (white) texel.
    EXPECT_NEAR(left.a, 0.5 * 128.0 / 255.0, 1e-4);
    EXPECT_NEAR(left.r, 0.04 * 2.0, 1e-4);
    EXPECT_NEAR(left.g, 0.04 * 2.0, 1e-4);
    EXPECT_NEAR(left.b, 0.04 * 8.0, 1e-4);
    // Right: A 255, the colour texture's left texel (188, 64, 255) decoded from sRGB.
    EXPECT_NEAR(right.a, 0.5, 1e-4);
    EXPECT_NEAR(right.r, 0.04 * 2.0 * srgb(188.0 / 255.0), 2e-4);
    EXPECT_NEAR(right.g, 0.04 * 2.0 * srgb(64.0 / 255.0), 2e-4);
    EXPECT_NEAR(right.b, 0.04 * 8.0, 1e-4);
}

// KHR_materials_iridescence's textures: the film's weight is iridescenceFactor x R of
// iridescenceTexture and its thickness mix(minimum, maximum, G of iridescenceThicknessTexture),
// per pixel, as the view the reference mode reads reports (the thickness texture through
// texCoord 0 and KHR_texture_transform shifted by half: its texels swap sides).
TEST_F(GltfFeaturesTest, IridescenceTexturesReachTheFilm) {
    const unsigned char texels[] = {51, 0, 0, 255, 255, 255, 0, 255};  // (R, G): (0.2, 0) | (1, 1)
    ASSERT_TRUE(write_png(dir.file("film.png"), 2, 1, texels));
    GltfBuilder b = lit_quad_builder();
    const std::string members =
        mesh_file(R"("POSITION": 0, "TEXCOORD_0": 2, "NORMAL": 3)", 1,
                  R"({"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5},
                      "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 0.5, "iridescenceIor": 1.6,
                        "iridescenceThicknessMinimum": 200, "iridescenceThicknessMaximum": 800,
                        "iridescenceTexture": {"index": 0},
                        "iridescenceThicknessTexture": {"index": 0, "texCoord": 0,
                          "extensions": {"KHR_texture_transform": {"offset": [0.5, 0]}}}}}})") +
        R"(, "textures": [{"source": 0, "sampler": 0}],
  "images": [{"uri": "film.png"}], "samplers": [{"magFilter": 9728, "minFilter": 9728}],
  "extensionsUsed": ["KHR_materials_iridescence", "KHR_texture_transform"])";
    RenderJob views = job("builtin:white");
    views.frame.views = {View::iridescence};
    const RenderedImages images = render(b.write(dir, "film_textures", members), views, false);
    ASSERT_EQ(images.views.size(), 1u);
    const Pixel left = at(images.views[0].second, kSize / 2 - 8, kSize / 2);
    const Pixel right = at(images.views[0].second, kSize / 2 + 8, kSize / 2);
    // Left: R 0.2 of its own texel, G 1 of the other (shifted): 800 nm.
    EXPECT_NEAR(left.r, 0.5f * 51.0f / 255.0f, 1e-4f);
    EXPECT_NEAR(left.g, 1.6f, 1e-6f);
    EXPECT_NEAR(left.b, 800.0f, 1e-3f);
    // Right: R 1, G 0 of the left texel: 200 nm.
    EXPECT_NEAR(right.r, 0.5f, 1e-4f);
    EXPECT_NEAR(right.b, 200.0f, 1e-3f);
}

// KHR_materials_anisotropy's direction and strength, as the view the reference mode reads
// reports them: on a quad whose tangents are generated (u along +X), rotation 0 stretches
// along the tangent; the texture's RG (1, 0.5) (the tangent) turned by a rotation of pi/2
// stretches along the bitangent (Y); strength x the texture's B.
TEST_F(GltfFeaturesTest, AnisotropyDirectionAndStrengthReachTheLobe) {
    const unsigned char texel[] = {255, 128, 128, 255};  // RG (1, 0.5) -> (1, 0); B 0.502
    ASSERT_TRUE(write_png(dir.file("stretch.png"), 1, 1, texel));
    GltfBuilder b = lit_quad_builder();
    auto stretch_view = [&](const std::string& name, const std::string& extension) {
        const std::string members =
            mesh_file(R"("POSITION": 0, "TEXCOORD_0": 2, "NORMAL": 3)", 1,
                      R"({"pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.5},
                          "extensions": {"KHR_materials_anisotropy": )" + extension + "}}") +
            R"(, "textures": [{"source": 0, "sampler": 0}],
  "images": [{"uri": "stretch.png"}], "samplers": [{"magFilter": 9728, "minFilter": 9728}],
  "extensionsUsed": ["KHR_materials_anisotropy"])";
        RenderJob views = job("builtin:white");
        views.frame.views = {View::anisotropy};
        const RenderedImages images = render(b.write(dir, name, members), views, false);
        EXPECT_EQ(images.views.size(), 1u);
        return images.views.empty() ? Pixel{} : at(images.views[0].second, kSize / 2, kSize / 2);
    };
    const Pixel along = stretch_view("stretch_plain", R"({"anisotropyStrength": 0.8})");
    EXPECT_NEAR(std::abs(along.r), 1.0f, 1e-4f);
    EXPECT_NEAR(along.g, 0.0f, 1e-4f);
    EXPECT_NEAR(along.a, 0.8f, 1e-6f);
    const Pixel turned = stretch_view(
        "stretch_textured", R"({"anisotropyStrength": 0.8, "anisotropyRotation": 1.5707963, "anisotropyTexture": {"index": 0}})");
    // G 128 is 2 x 128/255 - 1 = 0.004, not 0: the direction is off the tangent by that much.
    EXPECT_NEAR(std::abs(turned.r), 0.0039f, 5e-4f);
    EXPECT_NEAR(std::abs(turned.g), 1.0f, 1e-4f);
    EXPECT_NEAR(turned.a, 0.8f * 128.0f / 255.0f, 1e-4f);
}

// KHR_materials_unlit: base colour only, whatever lights it (a sun, the sky, a light) and
// whatever else the material says (emission, metal): the frame and the reference mode both
// show the base colour exactly (1e-5), where the same material lit does not (more than 5%).
TEST_F(GltfFeaturesTest, UnlitMaterialIsItsBaseColourInTheFrameAndTheReference) {
    GltfBuilder b = quad_builder();
    auto material = [](const std::string& extensions) {
        return R"({"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.9, 1], "metallicFactor": 1,
                   "roughnessFactor": 0.1}, "emissiveFactor": [1, 1, 1], "extensions": {)" + extensions + "}}";
    };
    RenderJob lit = job("builtin:sky");
    Light sun;
    sun.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f));
    sun.intensity = 3.0f;
    lit.extra_lights = {sun};
    std::unique_ptr<RenderSession> session;
    const RenderedImages unlit = render(
        b.write(dir, "unlit", mesh_file(R"("POSITION": 0)", 1, material(R"("KHR_materials_unlit": {})"))), lit, false,
        &session);
    ASSERT_EQ(unlit.hdr.size(), kSize * kSize * 4);
    const glm::vec3 base(0.2f, 0.5f, 0.9f);
    EXPECT_LT(centre_off(unlit.hdr, base), 1e-5f);
    ASSERT_TRUE(session);
    const auto reference = session->render_reference(ReferenceSettings{});
    ASSERT_TRUE(reference) << reference.error().message;
    EXPECT_LT(centre_off(reference->hdr, base), 1e-5f);
    // The component views: all of it diffuse, nothing else.
    RenderJob components = lit;
    components.frame.views = {View::diffuse, View::specular, View::D, View::irradiance};
    const RenderedImages views = render(
        b.write(dir, "unlit_views", mesh_file(R"("POSITION": 0)", 1, material(R"("KHR_materials_unlit": {})"))),
        components, false);
    ASSERT_EQ(views.views.size(), 4u);
    EXPECT_LT(centre_off(views.views[0].second, base), 1e-5f);
    for (size_t i = 1; i < 4; ++i) EXPECT_LT(centre_off(views.views[i].second, glm::vec3(0.0f)), 1e-6f) << i;
    const RenderedImages shaded =
        render(b.write(dir, "lit", mesh_file(R"("POSITION": 0)", 1, material(""))), lit, false);
    ASSERT_EQ(shaded.hdr.size(), kSize * kSize * 4);
    EXPECT_GT(centre_off(shaded.hdr, base), 0.05f);
}

// TEXCOORD_0 points at the texture's red half, TEXCOORD_1 at its green half: the material
// says texCoord 1, so the quad is green (white furnace, nearest sampling).
TEST_F(GltfFeaturesTest, TextureOnTheSecondUvSet) {
    const std::string png = dir.file("halves.png");
    const unsigned char texels[] = {255, 0, 0, 255, 0, 255, 0, 255};
    ASSERT_TRUE(write_png(png, 2, 1, texels));
    GltfBuilder b = quad_builder();
    b.add(std::vector<float>(8, 0.25f), kFloat, "VEC2", 4);
    b.add(std::vector<float>{0.75f, 0.5f, 0.75f, 0.5f, 0.75f, 0.5f, 0.75f, 0.5f}, kFloat, "VEC2", 4);
    const std::string members =
        mesh_file(R"("POSITION": 0, "TEXCOORD_0": 2, "TEXCOORD_1": 3)", 1,
                  R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}}})") +
        R"(, "textures": [{"source": 0, "sampler": 0}], "images": [{"uri": "halves.png"}],
  "samplers": [{"magFilter": 9728, "minFilter": 9728}])";
    const RenderedImages images = render(b.write(dir, "uv1", members), job("builtin:white"));
    ASSERT_EQ(images.hdr.size(), kSize * kSize * 4);
    const Pixel p = at(images.hdr, 32, 32);
    EXPECT_NEAR(p.r, 0.0f, 2e-3f);
    EXPECT_NEAR(p.g, 1.0f, 2e-3f);
    EXPECT_NEAR(p.b, 0.0f, 2e-3f);
}

// KHR_texture_transform: a 4x4 texture of distinct colours (nearest, repeat) on a quad whose
// TEXCOORD_0 spans it once; offset, rotation and scale as the extension defines them
// (uv' = T R S (u, v, 1)), computed here per pixel, pick the texel each covered pixel must
// show (white furnace, Lambert: the texel's linear colour within 2e-3; pixels whose uv'
// lies within 5% of a texel's edge are skipped). The extension's texCoord 0 overrides the
// textureInfo's 1 (TEXCOORD_1 points at a texel the transform never shows alone).
TEST_F(GltfFeaturesTest, TextureTransformPicksTheTexelsTheExtensionSays) {
    const std::string png = dir.file("grid.png");
    std::vector<unsigned char> texels;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) texels.insert(texels.end(), {(unsigned char)(40 + 60 * i), (unsigned char)(40 + 60 * j), 128, 255});
    ASSERT_TRUE(write_png(png, 4, 4, texels.data()));
    auto uv_of = [](float x, float y) { return glm::vec2((x + 1.0f) / 2.0f, (1.0f - y) / 2.0f); };
    std::vector<float> uv0;
    for (size_t i = 0; i < 4; ++i) {
        const glm::vec2 uv = uv_of(kQuad[3 * i], kQuad[3 * i + 1]);
        uv0.insert(uv0.end(), {uv.x, uv.y});
    }
    GltfBuilder b = quad_builder();
    b.add(uv0, kFloat, "VEC2", 4);
    b.add(std::vector<float>(8, 0.01f), kFloat, "VEC2", 4);
    const double offset[2] = {0.3, 0.1}, rotation = 0.5, scale[2] = {1.5, 0.75};
    const std::string members =
        mesh_file(R"("POSITION": 0, "TEXCOORD_0": 2, "TEXCOORD_1": 3)", 1,
                  R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1, "extensions":
                     {"KHR_texture_transform": {"offset": [0.3, 0.1], "rotation": 0.5, "scale": [1.5, 0.75],
                      "texCoord": 0}}}}})") +
        R"(, "extensionsUsed": ["KHR_texture_transform"], "textures": [{"source": 0, "sampler": 0}],
  "images": [{"uri": "grid.png"}], "samplers": [{"magFilter": 9728, "minFilter": 9728}])";
    std::unique_ptr<RenderSession> session;
    const RenderedImages images = render(b.write(dir, "transform", members), job("builtin:white"), true, &session);
    ASSERT_EQ(images.hdr.size(), kSize * kSize * 4);
    auto linear = [](int byte) {
        const double c = byte / 255.0;
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    int checked = 0;
    double worst = 0;
    std::set<int> seen;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const glm::vec3 p = on_plane(session->camera(), x, y);
            if (std::abs(p.x) > 0.95f || std::abs(p.y) > 0.95f) continue;
            const glm::vec2 uv = uv_of(p.x, p.y);
            const double c = std::cos(rotation), s = std::sin(rotation);
            const double u = offset[0] + c * scale[0] * uv.x - s * scale[1] * uv.y;
            const double v = offset[1] + s * scale[0] * uv.x + c * scale[1] * uv.y;
            const double fu = (u - std::floor(u)) * 4.0, fv = (v - std::floor(v)) * 4.0;
            auto near_edge = [](double f) { return std::abs(f - std::round(f)) < 0.2; };
            if (near_edge(fu) || near_edge(fv)) continue;
            const int i = int(fu), j = int(fv);
            seen.insert(j * 4 + i);
            const Pixel px = at(images.hdr, x, y);
            worst = std::max({worst, std::abs(px.r - linear(40 + 60 * i)), std::abs(px.g - linear(40 + 60 * j)),
                              std::abs(px.b - linear(128))});
            ++checked;
        }
    EXPECT_GT(checked, 300);
    EXPECT_GE(seen.size(), 10u);  // most of the grid, rotated and repeated
    EXPECT_LT(worst, 2e-3);
    // What the loader read: the extension's matrix and the overriding uv set.
    const Result<Scene> scene = load_gltf(dir.file("transform.gltf"));
    ASSERT_TRUE(scene.ok());
    const TextureRef& ref = scene->materials[0].base_color_texture;
    const double c = std::cos(rotation), s = std::sin(rotation);
    const double expected[6] = {c * scale[0], s * scale[0], -s * scale[1], c * scale[1], offset[0], offset[1]};
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(ref.uv_transform[size_t(k)], expected[k], 1e-6) << k;
    EXPECT_EQ(ref.uv_set, 0u);
    // A uv set the vertices cannot have is an error naming the texture.
    std::string bad = members;
    bad.replace(bad.find(R"("texCoord": 0)"), 13, R"("texCoord": 2)");
    const std::string bad_path = b.write(dir, "bad_transform", bad);
    const Result<Scene> refused = load_gltf(bad_path);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().message, bad_path + ": material 0: baseColorTexture: KHR_texture_transform.texCoord must "
                                                  "be 0 or 1 (TEXCOORD_0 or TEXCOORD_1)");
}

// A normal map read through a rotated transform keeps its tilt on the texture's own axes:
// one texel tilted towards +u' (0.6, 0, 0.8) on a quad whose u runs along +x and v along
// -y; rotated by 90 degrees, u' runs along -v, so the world normal is (0, 0.6, 0.8), where
// the untransformed map gives (0.6, 0, 0.8) (the normal view, within 0.02: 8-bit texel).
TEST_F(GltfFeaturesTest, RotatedNormalMapTurnsItsTangentFrame) {
    const std::string png = dir.file("tilt.png");
    const unsigned char texel[] = {204, 128, 230, 255};
    ASSERT_TRUE(write_png(png, 1, 1, texel));
    GltfBuilder b = lit_quad_builder();
    auto normal_at_centre = [&](const std::string& name, const std::string& extension) {
        const std::string members =
            mesh_file(R"("POSITION": 0, "TEXCOORD_0": 2, "NORMAL": 3)", 1,
                      R"({"normalTexture": {"index": 0)" + extension + "}}") +
            R"(, "textures": [{"source": 0, "sampler": 0}], "images": [{"uri": "tilt.png"}],
  "samplers": [{"magFilter": 9728, "minFilter": 9728}])";
        RenderJob views = job("builtin:white");
        views.frame.views = {View::normal};
        const RenderedImages images = render(b.write(dir, name, members), views);
        EXPECT_EQ(images.views.size(), 1u);
        if (images.views.size() != 1) return glm::vec3(0.0f);
        const Pixel p = at(images.views[0].second, 32, 32);
        return glm::vec3(p.r, p.g, p.b);
    };
    const glm::vec3 plain = normal_at_centre("tilt_plain", "");
    EXPECT_NEAR(plain.x, 0.6f, 0.02f);
    EXPECT_NEAR(plain.y, 0.0f, 0.02f);
    EXPECT_NEAR(plain.z, 0.8f, 0.02f);
    const glm::vec3 turned =
        normal_at_centre("tilt_rotated", R"(, "extensions": {"KHR_texture_transform": {"rotation": 1.5707963}})");
    EXPECT_NEAR(turned.x, 0.0f, 0.02f);
    EXPECT_NEAR(turned.y, 0.6f, 0.02f);
    EXPECT_NEAR(turned.z, 0.8f, 0.02f);
}

// KHR_materials_sheen's two textures reach the layer, as the view the reference mode reads
// shows: colour = sheenColorFactor x the colour texture's RGB (sRGB), roughness =
// sheenRoughnessFactor x the roughness texture's A (2x1 textures, nearest: each half of the
// quad its texel); the roughness texture's KHR_texture_transform (offset 0.5 in u, repeat)
// swaps the halves it reads.
TEST_F(GltfFeaturesTest, SheenTexturesReachTheLayer) {
    const unsigned char colours[] = {255, 128, 0, 255, 64, 255, 255, 255};  // RGB | RGB
    ASSERT_TRUE(write_png(dir.file("sheen.png"), 2, 1, colours));
    const unsigned char alphas[] = {255, 255, 255, 255, 255, 255, 255, 64};  // A 1 | A 64/255
    ASSERT_TRUE(write_png(dir.file("sheen_roughness.png"), 2, 1, alphas));
    std::vector<float> uv0;
    for (size_t i = 0; i < 4; ++i) uv0.insert(uv0.end(), {(kQuad[3 * i] + 1.0f) / 2.0f, (1.0f - kQuad[3 * i + 1]) / 2.0f});
    GltfBuilder b = quad_builder();
    b.add(uv0, kFloat, "VEC2", 4);
    b.add(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 4);  // NORMAL
    const std::string members =
        mesh_file(R"("POSITION": 0, "TEXCOORD_0": 2, "NORMAL": 3)", 1,
                  R"({"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 0.8, 0.5],
                      "sheenRoughnessFactor": 0.9, "sheenColorTexture": {"index": 0},
                      "sheenRoughnessTexture": {"index": 1,
                          "extensions": {"KHR_texture_transform": {"offset": [0.5, 0]}}}}}})") +
        R"(, "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
  "images": [{"uri": "sheen.png"}, {"uri": "sheen_roughness.png"}], "samplers": [{"magFilter": 9728, "minFilter": 9728}],
  "extensionsUsed": ["KHR_materials_sheen", "KHR_texture_transform"])";
    RenderJob views = job("builtin:white");
    views.frame.views = {View::sheen};
    const RenderedImages images = render(b.write(dir, "sheen_textured", members), views, false);
    ASSERT_EQ(images.views.size(), 1u);
    const Pixel left = at(images.views[0].second, kSize / 2 - 8, kSize / 2);
    const Pixel right = at(images.views[0].second, kSize / 2 + 8, kSize / 2);
    EXPECT_NEAR(left.r, 1.0f, 2e-3f);
    EXPECT_NEAR(left.g, 0.8 * srgb(128.0 / 255.0), 2e-3f);
    EXPECT_NEAR(left.b, 0.0f, 2e-3f);
    EXPECT_NEAR(left.a, 0.9f * 64.0f / 255.0f, 2e-3f);  // the right texel's A
    EXPECT_NEAR(right.r, srgb(64.0 / 255.0), 2e-3f);
    EXPECT_NEAR(right.g, 0.8f, 2e-3f);
    EXPECT_NEAR(right.b, 0.5f, 2e-3f);
    EXPECT_NEAR(right.a, 0.9f, 2e-3f);  // the left texel's A
}

// KHR_materials_clearcoat's three textures reach the layer, as the views the reference mode
// reads show: weight = clearcoatFactor x R and roughness = clearcoatRoughnessFactor x G
// (a 2x1 texture, nearest: each half of the quad its texel), and the layer's normal map
// (no TANGENT in the file: the loader makes them for it) turns the layer's normal alone,
// with its KHR_texture_transform's rotation; the surface's normal stays the geometry's.
TEST_F(GltfFeaturesTest, ClearcoatTexturesReachTheLayer) {
    const unsigned char halves[] = {255, 128, 0, 255, 64, 255, 0, 255};  // (R, G): (1, 0.5) | (0.25, 1)
    ASSERT_TRUE(write_png(dir.file("coat.png"), 2, 1, halves));
    const unsigned char tilt[] = {204, 128, 230, 255};  // (0.6, 0, 0.8) in tangent space
    ASSERT_TRUE(write_png(dir.file("tilt.png"), 1, 1, tilt));
    GltfBuilder b = lit_quad_builder();
    auto views_of = [&](const std::string& name, const std::string& normal_extension) {
        const std::string members =
            mesh_file(R"("POSITION": 0, "TEXCOORD_0": 2, "NORMAL": 3)", 1,
                      R"({"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 0.8,
                          "clearcoatRoughnessFactor": 0.6, "clearcoatTexture": {"index": 0},
                          "clearcoatRoughnessTexture": {"index": 0},
                          "clearcoatNormalTexture": {"index": 1)" + normal_extension + "}}}}") +
            R"(, "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
  "images": [{"uri": "coat.png"}, {"uri": "tilt.png"}], "samplers": [{"magFilter": 9728, "minFilter": 9728}],
  "extensionsUsed": ["KHR_materials_clearcoat", "KHR_texture_transform"])";
        RenderJob views = job("builtin:white");
        views.frame.views = {View::normal, View::clearcoat, View::clearcoat_normal};
        const RenderedImages images = render(b.write(dir, name, members), views, false);
        EXPECT_EQ(images.views.size(), 3u);
        return images;
    };
    const RenderedImages plain = views_of("coat_plain", "");
    ASSERT_EQ(plain.views.size(), 3u);
    const Pixel left = at(plain.views[1].second, kSize / 2 - 8, kSize / 2), right = at(plain.views[1].second, kSize / 2 + 8, kSize / 2);
    EXPECT_NEAR(left.r, 0.8f, 2e-3f);
    EXPECT_NEAR(left.g, 0.6f * 128.0f / 255.0f, 2e-3f);
    EXPECT_NEAR(right.r, 0.8f * 64.0f / 255.0f, 2e-3f);
    EXPECT_NEAR(right.g, 0.6f, 2e-3f);
    const Pixel n = at(plain.views[0].second, kSize / 2, kSize / 2);
    EXPECT_NEAR(n.b, 1.0f, 1e-4f);  // the surface's normal: the geometry's
    const Pixel coat_n = at(plain.views[2].second, kSize / 2, kSize / 2);
    EXPECT_NEAR(coat_n.r, 0.6f, 0.02f);
    EXPECT_NEAR(coat_n.g, 0.0f, 0.02f);
    EXPECT_NEAR(coat_n.b, 0.8f, 0.02f);
    const RenderedImages turned =
        views_of("coat_turned", R"(, "extensions": {"KHR_texture_transform": {"rotation": 1.5707963}})");
    ASSERT_EQ(turned.views.size(), 3u);
    const Pixel turned_n = at(turned.views[2].second, kSize / 2, kSize / 2);
    EXPECT_NEAR(turned_n.r, 0.0f, 0.02f);
    EXPECT_NEAR(turned_n.g, 0.6f, 0.02f);
    EXPECT_NEAR(turned_n.b, 0.8f, 0.02f);
}

// A unit cube, single-sided, mirrored by its node (scale -1 in x), seen from 45 degrees
// between +Z and +X and lit along the same diagonal. Each face is coloured by its
// vertices: with the winding flipped the outer faces are drawn (not the inner ones the
// camera would see through culled front faces), and with normals mirrored correctly both
// visible faces receive the light at 45 degrees: radiance = albedo x E/pi x cos 45.
TEST_F(GltfFeaturesTest, MirroredCubeShowsItsFrontFaces) {
    std::vector<float> positions, colours;
    std::vector<uint16_t> indices;
    // Face normal axis, sign, and its colour (original +X blue, -X yellow, +Z green, -Z red, Y grey).
    const struct {
        int axis;
        float sign;
        glm::vec3 colour;
    } faces[] = {{0, 1, {0, 0, 1}}, {0, -1, {1, 1, 0}}, {1, 1, {.5f, .5f, .5f}},
                 {1, -1, {.5f, .5f, .5f}}, {2, 1, {0, 1, 0}}, {2, -1, {1, 0, 0}}};
    for (const auto& f : faces) {
        const int u = (f.axis + 1) % 3, v = (f.axis + 2) % 3;
        const uint16_t first = uint16_t(positions.size() / 3);
        const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const auto& c : corners) {
            glm::vec3 p(0.0f);
            p[f.axis] = f.sign;
            p[u] = c[0];
            p[v] = c[1];
            positions.insert(positions.end(), {p.x, p.y, p.z});
            colours.insert(colours.end(), {f.colour.x, f.colour.y, f.colour.z});
        }
        // (u, v, axis) is right-handed: CCW seen from +axis; reversed for the -axis face.
        if (f.sign > 0) indices.insert(indices.end(), {first, uint16_t(first + 1), uint16_t(first + 2), first,
                                                       uint16_t(first + 2), uint16_t(first + 3)});
        else indices.insert(indices.end(), {first, uint16_t(first + 2), uint16_t(first + 1), first,
                                            uint16_t(first + 3), uint16_t(first + 2)});
    }
    GltfBuilder b;
    b.add(positions, kFloat, "VEC3", 24);
    b.add(indices, kUshort, "SCALAR", 36);
    b.add(colours, kFloat, "VEC3", 24);
    const std::string members = mesh_file(R"("POSITION": 0, "COLOR_0": 2)", 1, "{}", 4,
                                          R"({"mesh": 0, "scale": [-1, 1, 1]})");
    RenderJob j = job("none");
    j.orbit = std::array<float, 3>{45.0f, 0.0f, 6.0f};
    Light sun;
    sun.direction = glm::normalize(glm::vec3(-1.0f, 0.0f, -1.0f));
    sun.intensity = float(M_PI);  // E/pi = 1
    j.extra_lights = {sun};
    const RenderedImages images = render(b.write(dir, "mirrored", members), j);
    ASSERT_EQ(images.hdr.size(), kSize * kSize * 4);
    const float c45 = std::sqrt(0.5f);
    // Left of the centre the +Z face (green); right of it the face now at +X, the
    // original -X face (yellow).
    const Pixel left = at(images.hdr, 24, 32), right = at(images.hdr, 40, 32);
    EXPECT_NEAR(left.r, 0.0f, 2e-3f);
    EXPECT_NEAR(left.g, c45, 2e-3f);
    EXPECT_NEAR(left.b, 0.0f, 2e-3f);
    EXPECT_NEAR(right.r, c45, 2e-3f);
    EXPECT_NEAR(right.g, c45, 2e-3f);
    EXPECT_NEAR(right.b, 0.0f, 2e-3f);
}

// A normal map tilting the normal towards the bitangent, on a quad mirrored in x (and,
// for comparison, on the same quad unmirrored): the bitangent is +Y either way (a mirror
// in x leaves Y alone), so both must shade as Lambert with the tilted normal under a
// light from above. Without the handedness flip the mirrored one would tilt towards -Y.
TEST_F(GltfFeaturesTest, MirroredNormalMapKeepsItsBitangent) {
    const std::string png = dir.file("tilt.png");
    const unsigned char texel[] = {128, 191, 238, 255};
    ASSERT_TRUE(write_png(png, 1, 1, texel));
    const glm::vec3 tangent_space = glm::normalize(glm::vec3(texel[0], texel[1], texel[2]) / 255.0f * 2.0f - 1.0f);
    const glm::vec3 n = glm::normalize(glm::vec3(0.0f, tangent_space.y, tangent_space.z));  // x: along the tangent
    ASSERT_NEAR(tangent_space.x, 0.0f, 0.01f);
    GltfBuilder b = quad_builder();
    b.add(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 4);                  // NORMAL
    b.add(std::vector<float>{1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, kFloat, "VEC4", 4);     // TANGENT
    b.add(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}, kFloat, "VEC2", 4);
    Light sun;
    sun.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f));  // from above and in front
    sun.intensity = float(M_PI);
    const float expected = std::max(0.0f, -glm::dot(n, sun.direction));
    for (const char* node : {R"({"mesh": 0})", R"({"mesh": 0, "scale": [-1, 1, 1]})"}) {
        const std::string members =
            mesh_file(R"("POSITION": 0, "NORMAL": 2, "TANGENT": 3, "TEXCOORD_0": 4)", 1,
                      R"({"normalTexture": {"index": 0}})", 4, node) +
            R"(, "textures": [{"source": 0, "sampler": 0}], "images": [{"uri": "tilt.png"}],
  "samplers": [{"magFilter": 9728, "minFilter": 9728}])";
        RenderJob j = job("none");
        j.extra_lights = {sun};
        const RenderedImages images = render(b.write(dir, "tilt", members), j);
        ASSERT_EQ(images.hdr.size(), kSize * kSize * 4);
        const Pixel p = at(images.hdr, 32, 32);
        EXPECT_NEAR(p.r, expected, 2e-3f) << node;
        EXPECT_NEAR(p.g, expected, 2e-3f) << node;
    }
}

// Lines (a loop around the quad's outline) and points (a 5 x 5 grid), unlit: base
// colour x vertex colour + emissive, exactly.
TEST_F(GltfFeaturesTest, LinesAndPointsDrawnUnlit) {
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);
    b.add(std::vector<float>{1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0}, kFloat, "VEC3", 4);
    std::vector<float> grid;
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 5; ++x) grid.insert(grid.end(), {-0.8f + 0.4f * x, -0.8f + 0.4f * y, 0.0f});
    b.add(grid, kFloat, "VEC3", 25);
    const std::string material = R"({"emissiveFactor": [0, 0, 0.5], "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]}})";
    const RenderedImages lines =
        render(b.write(dir, "loop", mesh_file(R"("POSITION": 0, "COLOR_0": 1)", -1, material, 2)), job("none"), false);
    ASSERT_EQ(lines.hdr.size(), kSize * kSize * 4);
    const RenderedImages points =
        render(b.write(dir, "points", mesh_file(R"("POSITION": 2)", -1, material, 0)), job("none"), false);
    ASSERT_EQ(points.hdr.size(), kSize * kSize * 4);
    int line_pixels = 0, point_pixels = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const Pixel l = at(lines.hdr, x, y), p = at(points.hdr, x, y);
            if (l.a > 0.0f) {
                ++line_pixels;
                EXPECT_NEAR(l.r, 1.0f, 1e-5f);
                EXPECT_NEAR(l.g, 0.0f, 1e-5f);
                EXPECT_NEAR(l.b, 0.5f, 1e-5f);
            }
            if (p.a > 0.0f) {
                ++point_pixels;
                EXPECT_NEAR(p.r, 1.0f, 1e-5f);
                EXPECT_NEAR(p.g, 1.0f, 1e-5f);
                EXPECT_NEAR(p.b, 1.5f, 1e-5f);
            }
        }
    // The outline spans about 2/2.49 of the 64-pixel frame on each of its four sides
    // (45 degree field of view at 3 m), one pixel wide; the points are ~10 pixels apart.
    EXPECT_GT(line_pixels, 4 * 45);
    EXPECT_LT(line_pixels, 4 * 60);
    EXPECT_EQ(point_pixels, 25);
}

// The quad's right edge (vertices 1 and 2, at x = 1) moved to x = 0 three ways: by a
// sparse accessor, by a morph target with the mesh's default weight, by a skin joint
// translated by -1 in x. Each image must cover exactly the rectangle [-1, 0] x [-1, 1]:
// pixels whose centre sees a point more than 0.05 m inside it are covered, those more
// than 0.05 m outside are not (the margin is about one pixel).
TEST_F(GltfFeaturesTest, SparseMorphedAndSkinnedQuadsLandWhereComputed) {
    GltfBuilder b;
    b.add(kQuad, kFloat, "VEC3", 4);                                                       // 0
    b.add(kQuadIndices, kUshort, "SCALAR", 6);                                             // 1
    const int sparse_indices = b.view(std::vector<uint16_t>{1, 2});
    const int sparse_values = b.view(std::vector<float>{0, -1, 0, 0, 1, 0});
    b.accessor(0, kFloat, "VEC3", 4,
               R"(, "sparse": {"count": 2, "indices": {"bufferView": )" + std::to_string(sparse_indices) +
                   R"(, "componentType": 5123}, "values": {"bufferView": )" + std::to_string(sparse_values) + "}}");  // 2
    b.add(std::vector<float>{0, 0, 0, -2, 0, 0, -2, 0, 0, 0, 0, 0}, kFloat, "VEC3", 4);   // 3: morph target
    b.add(std::vector<uint8_t>{0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0}, kUbyte, "VEC4", 4);  // 4: JOINTS_0
    b.add(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, kFloat, "VEC4", 4);     // 5: WEIGHTS_0
    const std::string material = R"("materials": [{"emissiveFactor": [1, 1, 1], "doubleSided": true}])";
    const std::string scenes = R"("scenes": [{"nodes": [0]}])";
    const std::string files[] = {
        R"("meshes": [{"primitives": [{"attributes": {"POSITION": 2}, "indices": 1, "material": 0}]}],
  "nodes": [{"mesh": 0}], )" + material + ", " + scenes,
        R"("meshes": [{"weights": [0.5], "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0,
      "targets": [{"POSITION": 3}]}]}],
  "nodes": [{"mesh": 0}], )" + material + ", " + scenes,
        R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 4, "WEIGHTS_0": 5}, "indices": 1, "material": 0}]}],
  "skins": [{"joints": [1, 2]}],
  "nodes": [{"mesh": 0, "skin": 0, "children": [1, 2]}, {}, {"translation": [-1, 0, 0]}], )" + material + ", " + scenes};
    const char* names[] = {"sparse", "morph", "skin"};
    for (int f = 0; f < 3; ++f) {
        std::unique_ptr<RenderSession> session;
        const RenderedImages images = render(b.write(dir, names[f], files[f]), job("none"), false, &session);
        ASSERT_EQ(images.hdr.size(), kSize * kSize * 4) << names[f];
        int inside = 0, outside = 0, wrong = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const glm::vec3 p = on_plane(session->camera(), x, y);
                const float distance_in = std::min({p.x + 1.0f, 0.0f - p.x, p.y + 1.0f, 1.0f - p.y});
                const bool covered = at(images.hdr, x, y).a > 0.0f;
                if (distance_in > 0.05f) {
                    ++inside;
                    wrong += !covered;
                } else if (distance_in < -0.05f) {
                    ++outside;
                    wrong += covered;
                }
            }
        EXPECT_GT(inside, 300) << names[f];
        EXPECT_GT(outside, 1000) << names[f];
        EXPECT_EQ(wrong, 0) << names[f];
    }
}

// An occlusion texture and a metallic-roughness texture of the same size, coordinates and
// sampler are packed into one image (GpuScene: R from the occlusion), and the frame is
// what it is with the two read apart (the occlusion through a second, identical sampler,
// which keeps them apart): 4x4 textures of distinct texels whose metallic-roughness R is
// not the occlusion, under the sun sky, where the occlusion darkens the environment's light.
// Likewise one image in both slots (an ORM texture) read once.
TEST_F(GltfFeaturesTest, OcclusionPackedWithMetallicRoughnessRendersAsTwoTextures) {
    std::vector<unsigned char> mr(4 * 4 * 4), ao(4 * 4 * 4);
    for (int i = 0; i < 16; ++i) {
        const unsigned char rgba_mr[] = {static_cast<unsigned char>(250 - 11 * i), static_cast<unsigned char>(60 + 12 * i),
                                         static_cast<unsigned char>(i % 2 ? 255 : 0), 255};
        const unsigned char rgba_ao[] = {static_cast<unsigned char>(40 + 13 * i), 200, 100, 255};
        std::copy(rgba_mr, rgba_mr + 4, &mr[4 * i]);
        std::copy(rgba_ao, rgba_ao + 4, &ao[4 * i]);
    }
    ASSERT_TRUE(write_png(dir.file("mr.png"), 4, 4, mr.data()));
    ASSERT_TRUE(write_png(dir.file("ao.png"), 4, 4, ao.data()));
    GltfBuilder b = lit_quad_builder();
    const std::string attributes = R"("POSITION": 0, "TEXCOORD_0": 2, "NORMAL": 3)";
    auto file = [&](const std::string& name, int occlusion_texture, bool with_occlusion) {
        std::string material = R"({"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.4, 1],
            "metallicRoughnessTexture": {"index": 0}})";
        if (with_occlusion)
            material += R"(, "occlusionTexture": {"index": )" + std::to_string(occlusion_texture) + "}";
        material += "}";
        return b.write(dir, name, mesh_file(attributes, 1, material) + R"(,
  "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}, {"source": 1, "sampler": 1},
               {"source": 0, "sampler": 1}],
  "images": [{"uri": "mr.png"}, {"uri": "ao.png"}],
  "samplers": [{"magFilter": 9729, "minFilter": 9987}, {"magFilter": 9729, "minFilter": 9987}])");
    };
    struct Case {
        const char* name;
        int occlusion;  // texture index
        bool packed;
    };
    const Case cases[] = {{"packed", 1, true}, {"apart", 2, false}, {"orm", 0, true}, {"orm_apart", 3, false}};
    std::vector<RenderedImages> frames;
    for (const Case& c : cases) {
        const std::string path = file(c.name, c.occlusion, true);
        Result<Scene> scene = load_gltf(path);
        ASSERT_TRUE(scene) << scene.error().message;
        auto gpu = GpuScene::create(ctx(), *scene);
        ASSERT_TRUE(gpu) << gpu.error().message;
        EXPECT_EQ((*gpu)->occlusion_in_metallic_roughness(0), c.packed) << c.name;
        frames.push_back(render(path, job("builtin:sky"), false));
        ASSERT_EQ(frames.back().hdr.size(), kSize * kSize * 4) << c.name;
    }
    const RenderedImages plain = render(file("no_occlusion", 0, false), job("builtin:sky"), false);
    ASSERT_EQ(plain.hdr.size(), kSize * kSize * 4);
    // Packed against apart: the same to float rounding; and the occlusion seen (a frame
    // without it is brighter by far more than that).
    for (size_t pair = 0; pair < 2; ++pair) {
        const std::vector<float>& one = frames[2 * pair].hdr;
        const std::vector<float>& two = frames[2 * pair + 1].hdr;
        double worst = 0.0, darkened = 0.0;
        int covered = 0;
        for (size_t i = 0; i < one.size(); i += 4) {
            if (two[i + 3] <= 0.0f) continue;
            ++covered;
            for (size_t c = 0; c < 3; ++c) {
                worst = std::max(worst, std::abs(double(one[i + c]) - two[i + c]) / std::max(double(two[i + c]), 1e-3));
                darkened = std::max(darkened, (double(plain.hdr[i + c]) - two[i + c]) / std::max(double(two[i + c]), 1e-3));
            }
        }
        EXPECT_GT(covered, int(kSize * kSize / 4)) << cases[2 * pair].name;
        EXPECT_LT(worst, 1e-5) << cases[2 * pair].name << " against " << cases[2 * pair + 1].name;
        EXPECT_GT(darkened, 0.1) << cases[2 * pair].name << ": the occlusion is not seen";
    }
}

// A quad lying in the XZ plane, framed by the default camera: it must cover a fair part
// of the frame (seen edge-on from +Z it would cover nothing).
TEST_F(GltfFeaturesTest, FlatModelInXzIsFramed) {
    GltfBuilder b;
    b.add(std::vector<float>{-1, 0, 1, 1, 0, 1, 1, 0, -1, -1, 0, -1}, kFloat, "VEC3", 4);  // CCW from +Y
    b.add(kQuadIndices, kUshort, "SCALAR", 6);
    RenderJob j = job("none");
    j.orbit.reset();
    j.target.reset();
    const RenderedImages images = render(
        b.write(dir, "flat", mesh_file(R"("POSITION": 0)", 1, R"({"emissiveFactor": [1, 1, 1]})")), j, false);
    ASSERT_EQ(images.hdr.size(), kSize * kSize * 4);
    int covered = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) covered += at(images.hdr, x, y).a > 0.0f;
    EXPECT_GT(covered, int(kSize * kSize / 10));
}

}  // namespace
}  // namespace facet
