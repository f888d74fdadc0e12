// KHR_materials_unlit read as a flag that clears the lit inputs; KHR_materials_ior and
// KHR_materials_specular read into the dielectric lobe's F0 and strength (scene/gltf_material_extensions.h), against the extensions' formulas computed
// here: F0 = ((ior - 1) / (ior + 1))^2, then min(F0 x specularColor, 1), and the
// specular weight = specularFactor (its textures are drawn: tests/gpu/gltf_features_test.cpp);
// invalid values an error naming the material. KHR_materials_clearcoat's factors read as they are (the
// layer's shading is tested against the truth in tests/gpu/brdf_models_truth_test.cpp).
// KHR_materials_transmission and KHR_materials_volume: their factors, defaults and textures.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <facet/scene/gltf_loader.h>
#include <facet/scene/scene_needs.h>
#include "support/gltf_files.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

struct TempDir : test::GltfTempDir {
    TempDir() : GltfTempDir("gltf_material_ext") {}
};

// One triangle whose material 0 has `extensions` (a JSON object's members); `members`: more
// top-level members, each followed by a comma (textures, images).
Result<Scene> load_material(const TempDir& dir, const std::string& extensions, const std::string& members = "") {
    const std::string text = R"({"asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_materials_ior", "KHR_materials_specular", "KHR_materials_unlit", "KHR_materials_clearcoat",
                     "KHR_materials_iridescence", "KHR_materials_anisotropy", "KHR_materials_sheen",
                     "KHR_materials_transmission", "KHR_materials_volume", "KHR_texture_transform"],
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
  "materials": [{"name": "glass", "emissiveFactor": [1, 0.5, 0.25], "extensions": {)" + extensions + R"(}}],
  )" + members + R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
  "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
    const fs::path path = dir.path / "model.gltf";
    test::write_bytes(path.string(), text);
    return load_gltf(path.string());
}

double f0_of(double ior) {
    const double r = (ior - 1.0) / (ior + 1.0);
    return r * r;
}

TEST(GltfMaterialExtensions, IorSetsTheDielectricF0) {
    TempDir dir;
    for (double ior : {1.0, 1.33, 1.5, 2.42, 0.0}) {
        const Result<Scene> scene = load_material(dir, R"("KHR_materials_ior": {"ior": )" + std::to_string(ior) + "}");
        ASSERT_TRUE(scene.ok()) << ior << ": " << scene.error().message;
        EXPECT_NEAR(scene->materials[0].dielectric_f0, f0_of(ior), 1e-6) << ior;
        EXPECT_EQ(scene->materials[0].specular_factor, 1.0f);
        EXPECT_TRUE(scene->warnings.empty()) << scene->warnings[0];
    }
    EXPECT_NEAR(f0_of(0.0), 1.0, 1e-12);  // the specular-glossiness conversion's ior
    // Absent: glTF's 1.5.
    const Result<Scene> plain = load_material(dir, R"("KHR_materials_ior": {})");
    ASSERT_TRUE(plain.ok()) << plain.error().message;
    EXPECT_NEAR(plain->materials[0].dielectric_f0, 0.04, 1e-7);
}

TEST(GltfMaterialExtensions, SpecularScalesTheLobeAndItsColourTheF0) {
    TempDir dir;
    const Result<Scene> half = load_material(dir, R"("KHR_materials_specular": {"specularFactor": 0.5})");
    ASSERT_TRUE(half.ok()) << half.error().message;
    EXPECT_EQ(half->materials[0].specular_factor, 0.5f);
    EXPECT_NEAR(half->materials[0].dielectric_f0, 0.04, 1e-7);
    // With ior: F0(ior) and the colour, which the shading multiplies and clamps per channel
    // (min(F0 x colour, 1): tests/gpu/gltf_features_test.cpp reads it back from the f0 view).
    const Result<Scene> coloured = load_material(
        dir, R"("KHR_materials_ior": {"ior": 1.33}, "KHR_materials_specular": {"specularColorFactor": [2, 1, 0.5], "specularFactor": 0.25})");
    ASSERT_TRUE(coloured.ok()) << coloured.error().message;
    EXPECT_NEAR(coloured->materials[0].dielectric_f0, f0_of(1.33), 1e-6);
    EXPECT_EQ(coloured->materials[0].specular_color, glm::vec3(2.0f, 1.0f, 0.5f));
    EXPECT_EQ(coloured->materials[0].specular_factor, 0.25f);
    EXPECT_TRUE(coloured->warnings.empty());
    const Result<Scene> off = load_material(dir, R"("KHR_materials_specular": {"specularFactor": 0})");
    ASSERT_TRUE(off.ok()) << off.error().message;
    EXPECT_EQ(off->materials[0].specular_factor, 0.0f);  // Lambert only
}

TEST(GltfMaterialExtensions, UnlitKeepsTheBaseColourAloneAndIsNoWarning) {
    TempDir dir;
    const Result<Scene> plain = load_material(dir, "");
    ASSERT_TRUE(plain.ok()) << plain.error().message;
    EXPECT_FALSE(plain->materials[0].unlit);
    const Result<Scene> scene = load_material(dir, R"("KHR_materials_unlit": {})");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->materials[0].unlit);
    EXPECT_EQ(scene->materials[0].emissive, glm::vec3(0.0f));  // the extension: base colour alone
    EXPECT_TRUE(scene->warnings.empty());
}

TEST(GltfMaterialExtensions, ClearcoatReadsItsFactors) {
    TempDir dir;
    const Result<Scene> plain = load_material(dir, "");
    ASSERT_TRUE(plain.ok()) << plain.error().message;
    EXPECT_EQ(plain->materials[0].clearcoat, 0.0f);
    const Result<Scene> absent = load_material(dir, R"("KHR_materials_clearcoat": {})");
    ASSERT_TRUE(absent.ok()) << absent.error().message;
    EXPECT_EQ(absent->materials[0].clearcoat, 0.0f);  // the extension's defaults: no layer
    EXPECT_EQ(absent->materials[0].clearcoat_roughness, 0.0f);
    const Result<Scene> coat =
        load_material(dir, R"("KHR_materials_clearcoat": {"clearcoatFactor": 0.75, "clearcoatRoughnessFactor": 0.3})");
    ASSERT_TRUE(coat.ok()) << coat.error().message;
    EXPECT_EQ(coat->materials[0].clearcoat, 0.75f);
    EXPECT_EQ(coat->materials[0].clearcoat_roughness, 0.3f);
    EXPECT_FALSE(coat->materials[0].clearcoat_texture.valid());
    EXPECT_TRUE(coat->warnings.empty());  // its textures are drawn (tests/gpu/gltf_features_test.cpp)
    // Unlit wins: no layer over a surface that is not lit.
    const Result<Scene> unlit =
        load_material(dir, R"("KHR_materials_clearcoat": {"clearcoatFactor": 1}, "KHR_materials_unlit": {})");
    ASSERT_TRUE(unlit.ok()) << unlit.error().message;
    EXPECT_EQ(unlit->materials[0].clearcoat, 0.0f);
}

// KHR_materials_iridescence's defaults (factor 0: no film; ior 1.3; 100 .. 400 nm) and values.
TEST(GltfMaterialExtensions, IridescenceReadsItsFactors) {
    TempDir dir;
    const Result<Scene> absent = load_material(dir, R"("KHR_materials_iridescence": {})");
    ASSERT_TRUE(absent.ok()) << absent.error().message;
    const Material& none = absent->materials[0];
    EXPECT_EQ(none.iridescence, 0.0f);
    EXPECT_EQ(none.iridescence_ior, 1.3f);
    EXPECT_EQ(none.iridescence_thickness_minimum, 100.0f);
    EXPECT_EQ(none.iridescence_thickness_maximum, 400.0f);
    const Result<Scene> film = load_material(dir, R"("KHR_materials_iridescence": {"iridescenceFactor": 0.7,
        "iridescenceIor": 1.8, "iridescenceThicknessMinimum": 200, "iridescenceThicknessMaximum": 1200})");
    ASSERT_TRUE(film.ok()) << film.error().message;
    const Material& m = film->materials[0];
    EXPECT_EQ(m.iridescence, 0.7f);
    EXPECT_EQ(m.iridescence_ior, 1.8f);
    EXPECT_EQ(m.iridescence_thickness_minimum, 200.0f);
    EXPECT_EQ(m.iridescence_thickness_maximum, 1200.0f);
    EXPECT_FALSE(m.iridescence_texture.valid());
    EXPECT_TRUE(film->warnings.empty());
    // The extension excludes unlit: an unlit surface has no film.
    const Result<Scene> unlit =
        load_material(dir, R"("KHR_materials_iridescence": {"iridescenceFactor": 1}, "KHR_materials_unlit": {})");
    ASSERT_TRUE(unlit.ok()) << unlit.error().message;
    EXPECT_EQ(unlit->materials[0].iridescence, 0.0f);
}

TEST(GltfMaterialExtensions, AnisotropyReadsItsFactors) {
    TempDir dir;
    const Result<Scene> absent = load_material(dir, R"("KHR_materials_anisotropy": {})");
    ASSERT_TRUE(absent.ok()) << absent.error().message;
    EXPECT_EQ(absent->materials[0].anisotropy, 0.0f);
    EXPECT_EQ(absent->materials[0].anisotropy_rotation, 0.0f);
    const Result<Scene> scene =
        load_material(dir, R"("KHR_materials_anisotropy": {"anisotropyStrength": 0.4, "anisotropyRotation": -2})");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->materials[0].anisotropy, 0.4f);
    EXPECT_EQ(scene->materials[0].anisotropy_rotation, -2.0f);
    EXPECT_TRUE(scene->materials[0].needs_tangents());
    EXPECT_TRUE(scene->warnings.empty());
}

// KHR_materials_sheen's defaults (colour black: no layer; roughness 0) and values; unlit
// (which the extension excludes) clears it.
TEST(GltfMaterialExtensions, SheenReadsItsFactors) {
    TempDir dir;
    const Result<Scene> plain = load_material(dir, "");
    ASSERT_TRUE(plain.ok()) << plain.error().message;
    EXPECT_FALSE(plain->materials[0].has_sheen());
    const Result<Scene> absent = load_material(dir, R"("KHR_materials_sheen": {})");
    ASSERT_TRUE(absent.ok()) << absent.error().message;
    EXPECT_EQ(absent->materials[0].sheen_color, glm::vec3(0.0f));
    EXPECT_EQ(absent->materials[0].sheen_roughness, 0.0f);
    EXPECT_FALSE(absent->materials[0].has_sheen());
    const Result<Scene> scene = load_material(
        dir, R"("KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.25, 0], "sheenRoughnessFactor": 0.35})");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& m = scene->materials[0];
    EXPECT_EQ(m.sheen_color, glm::vec3(0.9f, 0.25f, 0.0f));
    EXPECT_EQ(m.sheen_roughness, 0.35f);
    EXPECT_TRUE(m.has_sheen());
    EXPECT_FALSE(m.sheen_color_texture.valid());
    EXPECT_FALSE(m.sheen_roughness_texture.valid());
    EXPECT_TRUE(scene->warnings.empty()) << scene->warnings[0];
    // The material is a pure metal (glTF's default metallicFactor 1): only its sheen reads the
    // irradiance (facet/sheen.glsl), so the bake makes it for the sheen alone.
    EXPECT_FALSE(scene_needs(*plain).diffuse);
    EXPECT_TRUE(scene_needs(*scene).diffuse);
    const Result<Scene> unlit =
        load_material(dir, R"("KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1]}, "KHR_materials_unlit": {})");
    ASSERT_TRUE(unlit.ok()) << unlit.error().message;
    EXPECT_FALSE(unlit->materials[0].has_sheen());
}

// KHR_materials_transmission's default (factor 0: none) and KHR_materials_volume's (thickness 0:
// thin-walled; attenuation distance infinite and colour white: no attenuation), and values.
// The transmitted lobe reads the prefiltered levels of its own roughness, the surface's
// (glTF's default 1 here) times clamp(2 ior - 2, 0, 1) (facet/transmission.glsl): the bake
// must make them. ior 1.2: 0.4; ior 1.5 and above: the surface's own.
TEST(GltfMaterialExtensions, TransmissionNeedsTheLevelsOfItsLobe) {
    TempDir dir;
    const Result<Scene> low = load_material(dir, R"("KHR_materials_transmission": {"transmissionFactor": 1},
        "KHR_materials_ior": {"ior": 1.2})");
    ASSERT_TRUE(low.ok()) << low.error().message;
    EXPECT_NEAR(scene_needs(*low).min_roughness, 0.4f, 1e-5f);
    const Result<Scene> glass = load_material(dir, R"("KHR_materials_transmission": {"transmissionFactor": 1})");
    ASSERT_TRUE(glass.ok()) << glass.error().message;
    EXPECT_NEAR(scene_needs(*glass).min_roughness, 1.0f, 1e-5f);
    const Result<Scene> opaque = load_material(dir, R"("KHR_materials_ior": {"ior": 1.2})");
    ASSERT_TRUE(opaque.ok()) << opaque.error().message;
    EXPECT_NEAR(scene_needs(*opaque).min_roughness, 1.0f, 1e-5f);
}

TEST(GltfMaterialExtensions, TransmissionAndVolumeReadTheirFactors) {
    TempDir dir;
    const Result<Scene> plain = load_material(dir, "");
    ASSERT_TRUE(plain.ok()) << plain.error().message;
    const Result<Scene> absent = load_material(dir, R"("KHR_materials_transmission": {}, "KHR_materials_volume": {})");
    ASSERT_TRUE(absent.ok()) << absent.error().message;
    for (const Material& none : {plain->materials[0], absent->materials[0]}) {
        EXPECT_EQ(none.transmission, 0.0f);
        EXPECT_FALSE(none.has_transmission());
        EXPECT_EQ(none.thickness, 0.0f);
        EXPECT_TRUE(std::isinf(none.attenuation_distance) && none.attenuation_distance > 0.0f);
        EXPECT_EQ(none.attenuation_color, glm::vec3(1.0f));
        EXPECT_FALSE(none.transmission_texture.valid());
        EXPECT_FALSE(none.thickness_texture.valid());
    }
    EXPECT_TRUE(absent->warnings.empty()) << absent->warnings[0];
    const Result<Scene> scene = load_material(dir, R"("KHR_materials_transmission": {"transmissionFactor": 0.8},
        "KHR_materials_volume": {"thicknessFactor": 0.25, "attenuationDistance": 2.5,
                                 "attenuationColor": [0.9, 0.5, 0]})");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& m = scene->materials[0];
    EXPECT_EQ(m.transmission, 0.8f);
    EXPECT_TRUE(m.has_transmission());
    EXPECT_EQ(m.thickness, 0.25f);
    EXPECT_EQ(m.attenuation_distance, 2.5f);
    EXPECT_EQ(m.attenuation_color, glm::vec3(0.9f, 0.5f, 0.0f));
    EXPECT_FALSE(m.transmission_texture.valid());
    EXPECT_FALSE(m.thickness_texture.valid());
    EXPECT_TRUE(scene->warnings.empty()) << scene->warnings[0];  // both read: neither is warned about
    // The volume alone is read as given; without transmission nothing crosses it (scene.h).
    const Result<Scene> volume = load_material(dir, R"("KHR_materials_volume": {"thicknessFactor": 3})");
    ASSERT_TRUE(volume.ok()) << volume.error().message;
    EXPECT_EQ(volume->materials[0].thickness, 3.0f);
    EXPECT_FALSE(volume->materials[0].has_transmission());
    // The edges of the ranges: factor 1, colour 0 and 1, a positive distance far below any unit.
    const Result<Scene> edges = load_material(dir, R"("KHR_materials_transmission": {"transmissionFactor": 1},
        "KHR_materials_volume": {"attenuationDistance": 1e-30, "attenuationColor": [0, 1, 0]})");
    ASSERT_TRUE(edges.ok()) << edges.error().message;
    EXPECT_EQ(edges->materials[0].transmission, 1.0f);
    EXPECT_EQ(edges->materials[0].attenuation_distance, 1e-30f);
    EXPECT_EQ(edges->materials[0].attenuation_color, glm::vec3(0.0f, 1.0f, 0.0f));
}

// One 2x2 PNG (data uri) as texture 0, for the extensions' textureInfo members.
const char* kOneTexture = R"("textures": [{"source": 0}],
  "images": [{"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAYAAABytg0kAAAACW9GRnMAAAAAAAAAAADaKrbOAAAAFUlEQVQImWNgUPXKn7LzHjOTBhQAACxUBE+BIpn8AAAAAElFTkSuQmCC"}],
  )";

// Both textures are textureInfo: texCoord and KHR_texture_transform (its matrix and its
// overriding texCoord) as on the core textures.
TEST(GltfMaterialExtensions, TransmissionAndThicknessTexturesTakeTexCoordAndTransform) {
    TempDir dir;
    const Result<Scene> scene = load_material(dir, R"("KHR_materials_transmission": {"transmissionFactor": 1,
            "transmissionTexture": {"index": 0, "texCoord": 1}},
        "KHR_materials_volume": {"thicknessFactor": 0.5, "thicknessTexture": {"index": 0, "extensions":
            {"KHR_texture_transform": {"offset": [0.5, 0.25], "rotation": 0.5, "scale": [2, 3], "texCoord": 1}}}})",
                                              kOneTexture);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->warnings.empty()) << scene->warnings[0];
    const Material& m = scene->materials[0];
    ASSERT_TRUE(m.transmission_texture.valid());
    EXPECT_EQ(m.transmission_texture.image, 0);
    EXPECT_EQ(m.transmission_texture.uv_set, 1u);
    EXPECT_FALSE(m.transmission_texture.transformed());
    ASSERT_TRUE(m.thickness_texture.valid());
    EXPECT_EQ(m.thickness_texture.image, 0);
    EXPECT_EQ(m.thickness_texture.uv_set, 1u);  // the transform's texCoord overrides the default 0
    // The extension's matrix: translation x rotation x scale.
    const double c = std::cos(0.5), s = std::sin(0.5);
    const double expected[6] = {c * 2, s * 2, -s * 3, c * 3, 0.5, 0.25};
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(m.thickness_texture.uv_transform[size_t(k)], expected[k], 1e-6) << k;
    // Only TEXCOORD_0 and _1 exist on vertices.
    const Result<Scene> refused = load_material(
        dir, R"("KHR_materials_transmission": {"transmissionTexture": {"index": 0, "texCoord": 2}})", kOneTexture);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().message,
              (dir.path / "model.gltf").string() +
                  ": material 'glass': KHR_materials_transmission: transmissionTexture uses TEXCOORD_2; only "
                  "TEXCOORD_0 and TEXCOORD_1 are supported");
}

// The extensions exclude unlit: an unlit surface transmits nothing and has no volume.
TEST(GltfMaterialExtensions, UnlitClearsTransmissionAndVolume) {
    TempDir dir;
    const Result<Scene> unlit = load_material(dir, R"("KHR_materials_transmission": {"transmissionFactor": 1,
            "transmissionTexture": {"index": 0}},
        "KHR_materials_volume": {"thicknessFactor": 2, "thicknessTexture": {"index": 0}, "attenuationDistance": 0.5,
                                 "attenuationColor": [0.5, 0.5, 0.5]},
        "KHR_materials_unlit": {})",
                                              kOneTexture);
    ASSERT_TRUE(unlit.ok()) << unlit.error().message;
    const Material& m = unlit->materials[0];
    EXPECT_TRUE(m.unlit);
    EXPECT_FALSE(m.has_transmission());
    EXPECT_EQ(m.transmission, 0.0f);
    EXPECT_FALSE(m.transmission_texture.valid());
    EXPECT_EQ(m.thickness, 0.0f);
    EXPECT_FALSE(m.thickness_texture.valid());
    EXPECT_TRUE(std::isinf(m.attenuation_distance));
    EXPECT_EQ(m.attenuation_color, glm::vec3(1.0f));
}

TEST(GltfMaterialExtensions, InvalidValuesAreErrorsNamingTheMaterial) {
    TempDir dir;
    const std::string file = (dir.path / "model.gltf").string();
    const std::pair<const char*, const char*> cases[] = {
        {R"("KHR_materials_ior": {"ior": 0.5})",
         "material 'glass': KHR_materials_ior.ior 0.5 is neither 0 nor at least 1 (an index of refraction)"},
        {R"("KHR_materials_ior": {"ior": -2})",
         "material 'glass': KHR_materials_ior.ior -2 is neither 0 nor at least 1 (an index of refraction)"},
        {R"("KHR_materials_ior": {"ior": "glass"})", "material 'glass': KHR_materials_ior.ior must be a finite number"},
        {R"("KHR_materials_specular": {"specularFactor": 1.5})",
         "material 'glass': KHR_materials_specular.specularFactor 1.5 is outside [0, 1]"},
        {R"("KHR_materials_specular": {"specularColorFactor": [1, 1]})",
         "material 'glass': KHR_materials_specular.specularColorFactor must have 3 numbers"},
        {R"("KHR_materials_specular": {"specularColorFactor": [1, -1, 1]})",
         "material 'glass': KHR_materials_specular.specularColorFactor must have 3 finite numbers >= 0"},
        {R"("KHR_materials_specular": {"specularTexture": {"index": 0}})",
         "material 'glass': KHR_materials_specular: specularTexture texture 0 out of range (0 textures)"},
        {R"("KHR_materials_specular": {"specularColorTexture": [0]})",
         "material 'glass': KHR_materials_specular.specularColorTexture must be an object"},
        {R"("KHR_materials_iridescence": {"iridescenceFactor": 1.5})",
         "material 'glass': KHR_materials_iridescence.iridescenceFactor 1.5 is outside [0, 1]"},
        {R"("KHR_materials_iridescence": {"iridescenceIor": 0.5})",
         "material 'glass': KHR_materials_iridescence.iridescenceIor 0.5 is below 1 (an index of refraction)"},
        {R"("KHR_materials_iridescence": {"iridescenceThicknessMaximum": -5})",
         "material 'glass': KHR_materials_iridescence.iridescenceThicknessMaximum -5 is outside [0, 1e6] (nanometres)"},
        {R"("KHR_materials_iridescence": {"iridescenceThicknessMinimum": "thin"})",
         "material 'glass': KHR_materials_iridescence.iridescenceThicknessMinimum must be a finite number"},
        {R"("KHR_materials_iridescence": {"iridescenceTexture": {"index": 2}})",
         "material 'glass': KHR_materials_iridescence: iridescenceTexture texture 2 out of range (0 textures)"},
        {R"("KHR_materials_anisotropy": {"anisotropyStrength": -0.1})",
         "material 'glass': KHR_materials_anisotropy.anisotropyStrength -0.1 is outside [0, 1]"},
        {R"("KHR_materials_anisotropy": {"anisotropyRotation": [1]})",
         "material 'glass': KHR_materials_anisotropy.anisotropyRotation must be a finite number"},
        {R"("KHR_materials_sheen": {"sheenColorFactor": [1, 1.5, 0]})",
         "material 'glass': KHR_materials_sheen.sheenColorFactor 1.5 is outside [0, 1]"},
        {R"("KHR_materials_sheen": {"sheenColorFactor": [1, 1]})",
         "material 'glass': KHR_materials_sheen.sheenColorFactor must have 3 numbers"},
        {R"("KHR_materials_sheen": {"sheenColorFactor": [1, "red", 1]})",
         "material 'glass': KHR_materials_sheen.sheenColorFactor must have 3 finite numbers"},
        {R"("KHR_materials_sheen": {"sheenRoughnessFactor": -0.2})",
         "material 'glass': KHR_materials_sheen.sheenRoughnessFactor -0.2 is outside [0, 1]"},
        {R"("KHR_materials_sheen": {"sheenColorTexture": {"index": 1}})",
         "material 'glass': KHR_materials_sheen: sheenColorTexture texture 1 out of range (0 textures)"},
        {R"("KHR_materials_sheen": {"sheenRoughnessTexture": {"index": 0, "texCoord": "one"}})",
         "material 'glass': KHR_materials_sheen.sheenRoughnessTexture.texCoord must be an integer"},
        {R"("KHR_materials_transmission": {"transmissionFactor": 1.5})",
         "material 'glass': KHR_materials_transmission.transmissionFactor 1.5 is outside [0, 1]"},
        {R"("KHR_materials_transmission": {"transmissionFactor": -0.25})",
         "material 'glass': KHR_materials_transmission.transmissionFactor -0.25 is outside [0, 1]"},
        {R"("KHR_materials_transmission": {"transmissionFactor": "half"})",
         "material 'glass': KHR_materials_transmission.transmissionFactor must be a finite number"},
        {R"("KHR_materials_transmission": {"transmissionTexture": {"index": 0}})",
         "material 'glass': KHR_materials_transmission: transmissionTexture texture 0 out of range (0 textures)"},
        {R"("KHR_materials_volume": {"thicknessFactor": -1})",
         "material 'glass': KHR_materials_volume.thicknessFactor -1 is negative"},
        {R"("KHR_materials_volume": {"thicknessFactor": 1e39})",
         "material 'glass': KHR_materials_volume.thicknessFactor 1e+39 is too large for floats"},
        {R"("KHR_materials_volume": {"thicknessFactor": [1]})",
         "material 'glass': KHR_materials_volume.thicknessFactor must be a finite number"},
        {R"("KHR_materials_volume": {"thicknessTexture": {"index": "zero"}})",
         "material 'glass': KHR_materials_volume.thicknessTexture.index must be an integer"},
        {R"("KHR_materials_volume": {"attenuationDistance": 0})",
         "material 'glass': KHR_materials_volume.attenuationDistance 0 is not positive"},
        {R"("KHR_materials_volume": {"attenuationDistance": -2})",
         "material 'glass': KHR_materials_volume.attenuationDistance -2 is not positive"},
        {R"("KHR_materials_volume": {"attenuationDistance": "far"})",
         "material 'glass': KHR_materials_volume.attenuationDistance must be a finite number"},
        {R"("KHR_materials_volume": {"attenuationDistance": 1e39})",
         "material 'glass': KHR_materials_volume.attenuationDistance 1e+39 is outside the range of floats"},
        {R"("KHR_materials_volume": {"attenuationDistance": 1e-50})",
         "material 'glass': KHR_materials_volume.attenuationDistance 1e-50 is outside the range of floats"},
        {R"("KHR_materials_volume": {"attenuationColor": [1, 1.5, 0]})",
         "material 'glass': KHR_materials_volume.attenuationColor 1.5 is outside [0, 1]"},
        {R"("KHR_materials_volume": {"attenuationColor": [-0.5, 1, 1]})",
         "material 'glass': KHR_materials_volume.attenuationColor -0.5 is outside [0, 1]"},
        {R"("KHR_materials_volume": {"attenuationColor": [1, 1]})",
         "material 'glass': KHR_materials_volume.attenuationColor must have 3 numbers"},
        {R"("KHR_materials_volume": {"attenuationColor": [1, 1, 1, 1]})",
         "material 'glass': KHR_materials_volume.attenuationColor must have 3 numbers"},
        {R"("KHR_materials_volume": {"attenuationColor": [1, "red", 1]})",
         "material 'glass': KHR_materials_volume.attenuationColor must have 3 finite numbers"},
        {R"("KHR_materials_clearcoat": {"clearcoatFactor": 2})",
         "material 'glass': KHR_materials_clearcoat.clearcoatFactor 2 is outside [0, 1]"},
        {R"("KHR_materials_clearcoat": {"clearcoatRoughnessFactor": -0.5})",
         "material 'glass': KHR_materials_clearcoat.clearcoatRoughnessFactor -0.5 is outside [0, 1]"},
        {R"("KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatTexture": {"index": 0}})",
         "material 'glass': KHR_materials_clearcoat: clearcoatTexture texture 0 out of range (0 textures)"},
        {R"("KHR_materials_clearcoat": {"clearcoatNormalTexture": {"index": "one"}})",
         "material 'glass': KHR_materials_clearcoat.clearcoatNormalTexture.index must be an integer"},
        {R"("KHR_materials_clearcoat": {"clearcoatRoughnessTexture": 3})",
         "material 'glass': KHR_materials_clearcoat.clearcoatRoughnessTexture must be an object"},
    };
    for (const auto& [extensions, message] : cases) {
        const Result<Scene> scene = load_material(dir, extensions);
        ASSERT_FALSE(scene.ok()) << extensions;
        EXPECT_EQ(scene.error().message, file + ": " + message) << extensions;
    }
}

}  // namespace
}  // namespace facet
