// The final image's truth (facet::reference, final_image_truth.h) against what is known
// independently: the furnace (a white surface under uniform light reflects its directional
// albedo, from the LUT's own quadrature), closed forms at normal incidence, reciprocity,
// the thesis truth the forward-render tests already use (tests/support/render_truth.cpp);
// and issue 13's per-group measurement (final_image_accuracy.h) on synthetic frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <facet/reference/final_image_accuracy.h>
#include <facet/reference/final_image_truth.h>
#include "support/render_truth.h"

namespace facet::test {
namespace {

constexpr double pi = 3.14159265358979323846;

Vec3 unit(double x, double y, double z) {
    const double l = std::sqrt(x * x + y * y + z * z);
    return {x / l, y / l, z / l};
}
// A view direction at n.v = c in the x-y plane around n = +Y.
Vec3 view_at(double c) { return {std::sqrt(1 - c * c), c, 0}; }

const TexelLights& uniform_light() {
    // 512 x 256: the narrowest lobe tested (roughness 0.3) spans several texels.
    static const TexelLights t = texel_lights(uniform_sky(512, 256, 1.0f));
    return t;
}

// Texel sums of smooth integrands over 512 x 256 texels: well within 0.5%.
constexpr double furnace_tolerance = 0.005;

TEST(FinalImageTruth, GltfWhiteMetalReflectsTheHeightCorrelatedAlbedo) {
    TruthMaterial white;
    white.metallic = 1;
    const Vec3 n{0, 1, 0};
    for (double r : {0.3, 0.5, 0.75, 1.0})
        for (double c : {0.35, 0.6, 0.95}) {
            white.roughness = r;
            const Ab ab = brdf_lut_reference(c, r, /*height_correlated=*/true);
            const Vec3 got = environment_truth(uniform_light(), BrdfModel::gltf, white, n, view_at(c));
            for (double channel : got) EXPECT_NEAR(channel, ab.a + ab.b, furnace_tolerance) << "r " << r << " n.v " << c;
        }
}

// KHR_materials_clearcoat's layer alone (over a surface that reflects nothing) under
// uniform light reflects its own directional albedo, 0.04 A + B of the LUT's quadrature at
// the layer's n.v and roughness; with the layer's normal tilted away from the surface's,
// the sum covers what lies above the layer's horizon and gives the same.
TEST(FinalImageTruth, ClearcoatAloneReflectsItsLayersAlbedoAboutItsOwnNormal) {
    TruthMaterial coated;
    coated.albedo = {0, 0, 0};
    coated.specular_weight = 0;  // the surface below: black, no specular lobe
    coated.clearcoat = 1;
    for (double r : {0.3, 0.6})
        for (double c : {0.5, 0.9}) {
            coated.clearcoat_roughness = r;
            const Ab ab = brdf_lut_reference(c, r, /*height_correlated=*/true);
            const Vec3 n{0, 1, 0};
            coated.clearcoat_normal = {0, 0, 0};  // the surface's
            const Vec3 got = environment_truth(uniform_light(), BrdfModel::gltf, coated, n, view_at(c));
            EXPECT_NEAR(got[0], 0.04 * ab.a + ab.b, furnace_tolerance) << "r " << r << " n.v " << c;
            // The layer's normal 40 degrees from the surface's, about the z axis, and the view
            // at n_c.v = c: the surface's normal plays no part.
            const double t = 40 * pi / 180;
            coated.clearcoat_normal = {-std::sin(t), std::cos(t), 0};
            const Vec3 v = unit(std::sqrt(1 - c * c) * std::cos(t) - c * std::sin(t),
                                std::sqrt(1 - c * c) * std::sin(t) + c * std::cos(t), 0);
            const Vec3 tilted = environment_truth(uniform_light(), BrdfModel::gltf, coated, n, v);
            EXPECT_NEAR(tilted[0], 0.04 * ab.a + ab.b, furnace_tolerance) << "tilted, r " << r << " n.v " << c;
            // Half the weight, half the light.
            coated.clearcoat = 0.5;
            coated.clearcoat_normal = {0, 0, 0};
            const Vec3 half = environment_truth(uniform_light(), BrdfModel::gltf, coated, n, view_at(c));
            EXPECT_NEAR(half[0], 0.5 * got[0], 1e-12);
            coated.clearcoat = 1;
        }
}

TEST(FinalImageTruth, ThesisWhiteMetalReflectsTheSchlickGgxAlbedo) {
    TruthMaterial white;
    white.metallic = 1;
    for (double r : {0.3, 0.6, 1.0})
        for (double c : {0.4, 0.9}) {
            white.roughness = r;
            const Ab ab = brdf_lut_reference(c, r, /*height_correlated=*/false);
            const Vec3 got = environment_truth(uniform_light(), BrdfModel::thesis, white, {0, 1, 0}, view_at(c));
            EXPECT_NEAR(got[0], ab.a + ab.b, furnace_tolerance) << "r " << r << " n.v " << c;
        }
}

// glTF's white dielectric: 1 - (the Fresnel-weighted diffuse loss) + the specular lobe,
// with the loss integrated here over l by its own quadrature and the lobe from the LUT
// (F0 A + B).
double gltf_white_dielectric_albedo(double n_v, double roughness) {
    const Vec3 v = view_at(n_v);
    const int nt = 512, np = 512;
    double fresnel_loss = 0;
    for (int i = 0; i < nt; ++i) {
        const double theta = (i + 0.5) / nt * pi / 2;
        for (int j = 0; j < np; ++j) {
            const double phi = (j + 0.5) / np * 2 * pi;
            const Vec3 l{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
            const Vec3 h = unit(l[0] + v[0], l[1] + v[1], l[2] + v[2]);
            const double v_h = v[0] * h[0] + v[1] * h[1] + v[2] * h[2];
            const double F = 0.04 + 0.96 * std::pow(1 - v_h, 5);
            fresnel_loss += F / pi * std::cos(theta) * std::sin(theta) * (pi / 2 / nt) * (2 * pi / np);
        }
    }
    const Ab ab = brdf_lut_reference(n_v, roughness, true);
    return 1 - fresnel_loss + 0.04 * ab.a + ab.b;
}

// The dielectric mix of both models weights diffuse and specular by F(v.h) per light
// direction, not by the lobe's albedo, so it is not energy conserving: at grazing views the
// specular lobe (F large) gains more than the diffuse loses (glTF, r 0.3, n.v 0.35: 1.086).
// Above n.v = 0.9 it stays within [0.9, 1].
TEST(FinalImageTruth, GltfWhiteDielectricInTheFurnace) {
    TruthMaterial white;  // albedo 1, metallic 0
    for (double r : {0.3, 0.6, 1.0})
        for (double c : {0.35, 0.9}) {
            white.roughness = r;
            const Vec3 got = environment_truth(uniform_light(), BrdfModel::gltf, white, {0, 1, 0}, view_at(c));
            const double want = gltf_white_dielectric_albedo(c, r);
            EXPECT_NEAR(got[0], want, furnace_tolerance) << "r " << r << " n.v " << c;
            if (c >= 0.9) {
                EXPECT_LE(got[0], 1.0 + furnace_tolerance);
                EXPECT_GE(got[0], 0.9);
            }
        }
}

// Single-scattering microfacet metals only lose energy; dielectrics (and mixes) facing
// the eye stay within 1 too (see above for grazing views).
TEST(FinalImageTruth, NeitherModelCreatesEnergyInTheFurnace) {
    for (BrdfModel model : {BrdfModel::gltf, BrdfModel::thesis})
        for (double metallic : {0.0, 0.5, 1.0})
            for (double r : {0.2, 0.5, 1.0})
                for (double c : {0.05, 0.3, 0.9, 1.0}) {
                    if (metallic < 1 && c < 0.9) continue;
                    TruthMaterial white;
                    white.metallic = metallic;
                    white.roughness = r;
                    const Vec3 got = environment_truth(uniform_light(), model, white, {0, 1, 0}, view_at(c));
                    EXPECT_LE(got[0], 1.0 + furnace_tolerance)
                        << brdf_model_name(model) << " metallic " << metallic << " r " << r << " n.v " << c;
                    EXPECT_GT(got[0], 0.0);
                }
}

TEST(FinalImageTruth, ClosedFormsAtNormalIncidence) {
    const Vec3 n{0, 0, 1};
    TruthMaterial m;
    m.roughness = 0.5;
    const double alpha = 0.25;
    // White metal, l = v = n: F = 1, D = 1/(pi alpha^2), V = 1/4 (G = 1): f = D/4.
    m.metallic = 1;
    const double mirror_peak = 1 / (pi * alpha * alpha) / 4;
    EXPECT_NEAR(brdf_cos(BrdfModel::gltf, m, n, n, n)[0], mirror_peak, 1e-12);
    EXPECT_NEAR(brdf_cos(BrdfModel::thesis, m, n, n, n)[0], mirror_peak, 1e-12);
    // White dielectric at normal incidence: (1 - 0.04)/pi + 0.04 D/4 in both models.
    m.metallic = 0;
    EXPECT_NEAR(brdf_cos(BrdfModel::gltf, m, n, n, n)[0], 0.96 / pi + 0.04 * mirror_peak, 1e-12);
    EXPECT_NEAR(brdf_cos(BrdfModel::thesis, m, n, n, n)[0], 0.96 / pi + 0.04 * mirror_peak, 1e-12);
    // Half metal: glTF mixes two whole BRDFs (diffuse (1 - 0.04)/2 / pi); the thesis mixes
    // F0 to 0.52 and kd = (1 - 0.52)(1 - 0.5) = 0.24. The specular parts agree (0.52 D/4).
    m.metallic = 0.5;
    EXPECT_NEAR(brdf_cos(BrdfModel::gltf, m, n, n, n)[0], 0.48 / pi + 0.52 * mirror_peak, 1e-12);
    EXPECT_NEAR(brdf_cos(BrdfModel::thesis, m, n, n, n)[0], 0.24 / pi + 0.52 * mirror_peak, 1e-12);
    // The specular weight scales glTF's dielectric Fresnel, and the diffuse takes the rest.
    m.metallic = 0;
    m.specular_weight = 0;
    EXPECT_NEAR(brdf_cos(BrdfModel::gltf, m, n, n, n)[0], 1 / pi, 1e-12);
    // Below the horizon: nothing.
    EXPECT_EQ(brdf_cos(BrdfModel::gltf, m, n, n, {0, 0, -1})[0], 0.0);
}

TEST(FinalImageTruth, ReciprocalAndTheModelsDifferWhereTheyShould) {
    const Vec3 n{0, 0, 1};
    const Vec3 v = unit(0.8, 0.1, 0.3), l = unit(-0.5, 0.4, 0.6);
    for (BrdfModel model : {BrdfModel::gltf, BrdfModel::thesis})
        for (double metallic : {0.0, 1.0}) {
            TruthMaterial m;
            m.albedo = {0.9, 0.5, 0.2};
            m.metallic = metallic;
            m.roughness = 0.4;
            // f(l, v) = f(v, l): f cos / n.l is symmetric.
            const Vec3 a = brdf_cos(model, m, n, v, l), b = brdf_cos(model, m, n, l, v);
            for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(a[c] / l[2], b[c] / v[2], 1e-12 * std::abs(a[c] / l[2]));
        }
    // Grazing mirror configuration (h = n): the Smith terms differ (height-correlated
    // against Schlick-GGX k = r^2/2), and only the thesis has a punctual k.
    TruthMaterial metal;
    metal.metallic = 1;
    metal.roughness = 0.5;
    const Vec3 vg{std::sqrt(1 - 0.04), 0, 0.2}, lg{-std::sqrt(1 - 0.04), 0, 0.2};
    const double gltf = brdf_cos(BrdfModel::gltf, metal, n, vg, lg)[0];
    const double thesis = brdf_cos(BrdfModel::thesis, metal, n, vg, lg)[0];
    EXPECT_GT(std::abs(gltf - thesis), 0.05 * gltf);
    EXPECT_EQ(brdf_cos(BrdfModel::gltf, metal, n, vg, lg, true)[0], gltf);
    EXPECT_NE(brdf_cos(BrdfModel::thesis, metal, n, vg, lg, true)[0], thesis);
    // Both at h = n, n.l = n.v = 0.2, alpha = 0.25: D = 1/(pi alpha^2), F = 1.
    const double a2 = 0.25 * 0.25, D = 1 / (pi * a2), k = 0.125, g1 = 0.2 / (0.2 * (1 - k) + k);
    EXPECT_NEAR(thesis, D * g1 * g1 / (4 * 0.2 * 0.2) * 0.2, 1e-9 * thesis);
    const double lambda = std::sqrt(0.04 * (1 - a2) + a2);
    EXPECT_NEAR(gltf, D * 0.5 / (2 * 0.2 * lambda) * 0.2, 1e-9 * gltf);
}


// environment_truth takes a shorter path for a material with no layer and no extension (its
// terms worked out once per point): it must sum what brdf_cos gives texel by texel, for both
// models, metals and dielectrics, coloured F0 and specular weights, roughness down to alpha's
// floor, grazing views and a light exactly opposite the view (no half vector).
TEST(FinalImageTruth, PlainMaterialsSumWhatBrdfCosGivesTexelByTexel) {
    TexelLights lights;
    uint32_t state = 12345;
    auto random = [&state] {
        state = state * 1664525u + 1013904223u;
        return (state >> 8) / double(1u << 24);
    };
    for (int i = 0; i < 4000; ++i) {
        const double z = 2 * random() - 1, phi = 2 * pi * random(), r = std::sqrt(1 - z * z);
        lights.dir.push_back({r * std::cos(phi), r * std::sin(phi), z});
        lights.power.push_back({random(), random(), random()});
    }
    int checked = 0;
    for (int k = 0; k < 48; ++k) {
        TruthMaterial m;
        m.albedo = {random(), random(), random()};
        m.metallic = k % 3 == 0 ? 0.0 : k % 3 == 1 ? 1.0 : random();
        m.roughness = k % 8 == 0 ? 0.0 : random();
        m.dielectric_f0 = 0.02 + 0.2 * random();
        m.specular_weight = random();
        m.specular_color = {0.5 + random(), 1.0, 0.5 + random()};
        const Vec3 n = unit(random() - 0.5, random() - 0.5, random() - 0.5);
        Vec3 v = unit(random() - 0.5, random() - 0.5, random() - 0.5);
        if (n[0] * v[0] + n[1] * v[1] + n[2] * v[2] < 0) v = {-v[0], -v[1], -v[2]};
        if (k % 6 == 5) v = unit(v[0] - n[0] * 0.999, v[1] - n[1] * 0.999, v[2] - n[2] * 0.999);  // grazing
        TexelLights with_opposite = lights;
        with_opposite.dir.push_back({-v[0], -v[1], -v[2]});
        with_opposite.power.push_back({1e3, 1e3, 1e3});
        for (BrdfModel model : {BrdfModel::gltf, BrdfModel::thesis}) {
            Vec3 expected{0, 0, 0};
            for (size_t i = 0; i < with_opposite.dir.size(); ++i) {
                const Vec3 f = brdf_cos(model, m, n, v, with_opposite.dir[i]);
                for (size_t c = 0; c < 3; ++c) expected[c] += f[c] * with_opposite.power[i][c];
            }
            const Vec3 got = environment_truth(with_opposite, model, m, n, v);
            // The same terms, rounded in another order: at alpha's floor (alpha^2 1e-8) D
            // magnifies n.h's last bits about 1e4-fold, so 1e-9, not 1e-15; a wrong term is
            // off by far more.
            for (size_t c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], expected[c], 1e-9 * std::abs(expected[c]) + 1e-300)
                    << brdf_model_name(model) << " material " << k << " channel " << c;
            checked += expected[0] > 0;
        }
    }
    EXPECT_GT(checked, 80);  // the sums are not all empty
}
// The thesis model against the truth tests/support/render_truth.cpp computes for the
// builtin:spheres grid (written separately, for the forward-render tests).
// KHR_materials_iridescence's F_iridescence: a film much thicker than the light's coherence
// length (1e5 nm: every interference term's Gaussian envelope is 0) reflects the incoherent
// sum of its two interfaces, R12 + T^2 R23 / (1 - R12 R23) (the Airy sum without phase),
// with Schlick's F at each interface: outside -> film at cos1, film -> base at the refracted
// cos2 (Snell), the base's index (1 + sqrt F0) / (1 - sqrt F0). A thin film (380 nm) differs
// from it by its interference, and colours the reflection.
TEST(FinalImageTruth, ThickFilmReflectsTheIncoherentSumOfItsInterfaces) {
    auto schlick = [](double r0, double c) { return r0 + (1 - r0) * std::pow(1 - c, 5); };
    const double film = 1.8;
    for (double cos1 : {1.0, 0.7, 0.3})
        for (double base_f0 : {0.04, 0.5}) {
            const double cos2 = std::sqrt(1 - (1 - cos1 * cos1) / (film * film));
            const double base_ior = (1 + std::sqrt(base_f0)) / (1 - std::sqrt(base_f0));
            const double R12 = schlick(std::pow((film - 1) / (film + 1), 2), cos1);
            const double R23 = schlick(std::pow((base_ior - film) / (base_ior + film), 2), cos2);
            const double incoherent = R12 + (1 - R12) * (1 - R12) * R23 / (1 - R12 * R23);
            const Vec3 thick = thin_film_fresnel(1.0, film, cos1, 1e5, {base_f0, base_f0, base_f0});
            for (double c : thick) EXPECT_NEAR(c, incoherent, 1e-9) << cos1 << " " << base_f0;
            const Vec3 thin = thin_film_fresnel(1.0, film, cos1, 380.0, {base_f0, base_f0, base_f0});
            EXPECT_GT(std::abs(thin[0] - incoherent) + std::abs(thin[2] - incoherent), 0.01) << cos1 << " " << base_f0;
            EXPECT_GT(std::abs(thin[0] - thin[2]), 0.005) << "a thin film colours the reflection";
        }
}

TEST(FinalImageTruth, ThesisMatchesTheSpheresTruth) {
    const Equirect env = sun_sky(128, 64, 200.0, 4.0, 35.0, 60.0);
    const TexelLights lights = texel_lights(env);
    const Vec3 eye{0.3, 0.8, 12.0};
    std::vector<float> normals, positions;
    std::vector<SphereSample> samples;
    uint32_t pixel = 0;
    for (int row = 0; row < 7; row += 3)
        for (int col = 2; col < 7; ++col)  // roughness 0 and 1/6 use other sums there
            for (const Vec3& nn : {unit(0.2, 0.3, 1.0), unit(-0.6, 0.1, 0.7), unit(0.1, -0.5, 0.8)}) {
                const double cx = (col - 3) * 2.5, cy = (row - 3) * 2.5;
                for (size_t c = 0; c < 3; ++c) normals.push_back(float(nn[c]));
                normals.push_back(1.0f);
                positions.insert(positions.end(), {float(cx + nn[0]), float(cy + nn[1]), float(nn[2]), 1.0f});
                samples.push_back({pixel++, row * 7 + col});
            }
    const SpheresTruth spheres = spheres_truth(env, eye, normals, positions, samples);
    for (size_t k = 0; k < samples.size(); ++k) {
        TruthMaterial m;
        m.albedo = {0.5, 0, 0};
        m.roughness = (samples[k].sphere % 7) / 6.0;
        m.metallic = (samples[k].sphere / 7) / 6.0;
        const size_t i = samples[k].pixel;
        // The same float inputs the spheres truth reads.
        const Vec3 n = unit(normals[i * 4], normals[i * 4 + 1], normals[i * 4 + 2]);
        const Vec3 v = unit(eye[0] - positions[i * 4], eye[1] - positions[i * 4 + 1], eye[2] - positions[i * 4 + 2]);
        const Vec3 got = environment_truth(lights, BrdfModel::thesis, m, n, v);
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], spheres.bilinear[k][c], 1e-9 * (1 + std::abs(spheres.bilinear[k][c])))
                << "sphere " << samples[k].sphere << " channel " << c;
    }
}

// KHR_materials_sheen's lobe alone (over a material that reflects nothing) under uniform
// light: the texel sum of its D V (n.l) equals its directional albedo, which sheen_albedo
// integrates another way (over half vectors); the colour scales it per channel.
TEST(FinalImageTruth, SheenAloneReflectsItsDirectionalAlbedo) {
    TruthMaterial sheen;
    sheen.albedo = {0, 0, 0};
    sheen.specular_weight = 0;
    sheen.sheen_color = {1, 0.5, 0.25};
    for (double r : {0.3, 0.5, 1.0})
        for (double c : {0.3, 0.6, 0.95}) {
            sheen.sheen_roughness = r;
            const Vec3 got = environment_truth(uniform_light(), BrdfModel::gltf, sheen, {0, 1, 0}, view_at(c));
            const double e = sheen_albedo(c, r);
            for (size_t k = 0; k < 3; ++k)
                EXPECT_NEAR(got[k], sheen.sheen_color[k] * e, furnace_tolerance) << "r " << r << " n.v " << c;
        }
    // The lobe is a back- and forward-scattering one: brightest at grazing views.
    EXPECT_GT(sheen_albedo(0.2, 0.5), sheen_albedo(0.9, 0.5));
}

// The albedo scaling keeps the energy: a white sheen over a white Lambertian surface (no
// specular lobe) reflects at most 1 under uniform light, and more than the sheen alone.
TEST(FinalImageTruth, SheenOverWhiteLambertKeepsTheEnergy) {
    for (BrdfModel model : {BrdfModel::gltf, BrdfModel::thesis})
        for (double r : {0.4, 0.7, 1.0})
            for (double c : {0.3, 0.6, 0.95}) {
                TruthMaterial white;
                white.specular_weight = 0;
                white.sheen_color = {1, 1, 1};
                white.sheen_roughness = r;
                const Vec3 got = environment_truth(uniform_light(), model, white, {0, 1, 0}, view_at(c));
                EXPECT_LE(got[0], 1.0 + furnace_tolerance) << brdf_model_name(model) << " r " << r << " n.v " << c;
                EXPECT_GT(got[0], sheen_albedo(c, r) + 0.2) << brdf_model_name(model) << " r " << r << " n.v " << c;
            }
}

// The shaders' fits (shaders/facet/sheen_albedo.glsl, written by scripts/make_sheen_albedo.py
// from a quadrature of its own: per roughness row j / 16 a polynomial of sqrt(n.v) in log
// space, the exponents blended linearly in r) against the truth's integral, where the value
// is at most 1.5, n.v from 0.0088 and roughness from 0.25 (the tests' domain): the sheen's
// albedo E within 0.015 or 3% of it, and M, the cosine-weighted mean over n.l of
// min(1, max(E(n.v), E(n.l))) (the environment's diffuse scaling), within 0.02 (measured: 0.016, 0.017).
std::vector<std::vector<double>> sheen_fit_rows(const std::string& prefix) {
    std::ifstream file(std::string(FACET_SOURCE_DIR) + "/shaders/facet/sheen_albedo.glsl");
    std::vector<std::vector<double>> rows;  // j, c0 .. c5
    for (std::string line; std::getline(file, line);) {
        if (line.rfind("#define " + prefix, 0) != 0) continue;
        const size_t at = line.find("FACET_SHEEN_ROW(");
        if (at == std::string::npos) continue;
        std::stringstream items(line.substr(at + 16));
        std::vector<double> row;
        for (std::string item; std::getline(items, item, ',');) row.push_back(std::stod(item));
        if (row.size() == 7) rows.push_back(row);
    }
    return rows;
}

double sheen_fit(const std::vector<std::vector<double>>& rows, double mu, double r) {
    const double s = std::sqrt(std::clamp(mu, 1e-3, 1.0)), y = r * 16;
    double weights = 0, exponent = 0;  // the coefficients blended linearly in r, one exp
    for (const std::vector<double>& c : rows) {
        const double w = std::max(1 - std::abs(y - c[0]), 0.0);
        exponent += w * (c[1] + s * (c[2] + s * (c[3] + s * (c[4] + s * (c[5] + s * c[6])))));
        weights += w;
    }
    return weights * std::exp(exponent / std::max(weights, 1e-6));
}

TEST(FinalImageTruth, ShadersSheenAlbedoFitsMatchTheTruth) {
    const auto albedo_rows = sheen_fit_rows("FACET_SHEEN_ROWS_"), mean_rows = sheen_fit_rows("FACET_SHEEN_MEAN_ROWS_");
    ASSERT_EQ(albedo_rows.size(), 16u);
    ASSERT_EQ(mean_rows.size(), 16u);
    int compared = 0;
    double worst = 0, worst_mean = 0;
    for (int j = 8; j <= 32; ++j)
        for (int i = 3; i <= 32; ++i) {
            const double r = j / 32.0, mu = i * i / 1024.0;
            const double want = sheen_albedo(mu, r), got = sheen_fit(albedo_rows, mu, r);
            if (want > 1.5) continue;
            EXPECT_NEAR(got, want, std::max(0.015, 0.03 * want)) << "r " << r << " n.v " << mu;
            worst = std::max(worst, std::abs(got - want));
            // M by the midpoint rule in x = sqrt(n.l) (2 t dt = 4 x^3 dx).
            double mean = 0;
            for (int k = 0; k < 256; ++k) {
                const double x = (k + 0.5) / 256;
                mean += std::max(std::min(want, 1.0), std::min(sheen_albedo(x * x, r), 1.0)) * 4 * x * x * x / 256;
            }
            const double got_mean = sheen_fit(mean_rows, mu, r);
            EXPECT_NEAR(got_mean, mean, 0.02) << "r " << r << " n.v " << mu;
            worst_mean = std::max(worst_mean, std::abs(got_mean - mean));
            ++compared;
        }
    std::printf("sheen fits: %d points, worst absolute distance to the truth: E %.4f, M %.4f\n", compared, worst,
                worst_mean);
    EXPECT_GT(compared, 600);
}

// KHR_materials_transmission. A white dielectric that gives all its diffuse to the
// transmission (ior 1.5: the transmitted lobe has the reflected one's roughness) splits each
// pair of directions mirrored through the surface into F D V (n.l) above and (1 - F) D V
// (n.l') below, so under uniform light it returns what a white metal (F = 1) returns: the
// same lobe's sum, both models, anisotropic too (the reflection's path for l'). About n = +Y
// the texels below mirror those above, so the quadratures cancel; about a tilted normal they
// do not, and the lobe's own quadrature error (r 0.2 spans few texels) is what is left.
TEST(FinalImageTruth, TransmittingWhiteDielectricReturnsWhatAWhiteMetalDoes) {
    double worst_up = 0, worst_tilted = 0;
    const Vec3 tilted = unit(0.3, 0.9, 0.2), side = unit(0.9, -0.3, 0.0);  // side . tilted = 0
    for (BrdfModel model : {BrdfModel::gltf, BrdfModel::thesis})
        for (double anisotropy : {0.0, 0.6})
            for (double r : {0.2, 0.5, 0.9})
                for (double c : {0.1, 0.4, 0.9, 1.0})
                    for (bool up : {true, false}) {
                        TruthMaterial dielectric, metal;
                        dielectric.transmission = 1;
                        metal.metallic = 1;
                        for (TruthMaterial* m : {&dielectric, &metal}) {
                            m->roughness = r;
                            m->anisotropy = anisotropy;
                        }
                        const Vec3 n = up ? Vec3{0, 1, 0} : tilted;
                        const Vec3 v = up ? view_at(c)
                                          : unit(std::sqrt(1 - c * c) * side[0] + c * n[0],
                                                 std::sqrt(1 - c * c) * side[1] + c * n[1],
                                                 std::sqrt(1 - c * c) * side[2] + c * n[2]);
                        const Vec3 got = environment_truth(uniform_light(), model, dielectric, n, v);
                        const Vec3 want = environment_truth(uniform_light(), model, metal, n, v);
                        for (size_t k = 0; k < 3; ++k) {
                            EXPECT_NEAR(got[k], want[k], 1e-3 * want[k])
                                << brdf_model_name(model) << (up ? " n +Y" : " n tilted") << " anisotropy "
                                << anisotropy << " r " << r << " n.v " << c;
                            double& worst = up ? worst_up : worst_tilted;
                            worst = std::max(worst, std::abs(got[k] - want[k]) / want[k]);
                        }
                    }
    std::printf("transmitting white dielectric against white metal, worst relative difference: n +Y %.2e, "
                "tilted %.2e\n",
                worst_up, worst_tilted);
}

// The transmission's weight enters linearly everywhere (the diffuse's (1 - T), the
// transmitted lobe's T): T 0.5 returns the mean of T 0 and T 1, per direction and under a
// sky whose sun lies behind the surface (plain, and under every other layer).
TEST(FinalImageTruth, TransmissionIsLinearInItsWeight) {
    const TexelLights sky = texel_lights(sun_sky(128, 64, 200.0, 4.0, 35.0, 60.0));
    const Vec3 n = unit(-0.41, 0.2, -0.71);             // the sun (0.41, 0.57, 0.71) behind it
    const Vec3 views[] = {unit(-0.5, -0.3, -0.8), n};  // nearly straight through to the sun, and along n
    const Vec3 lights[] = {unit(0.41, 0.57, 0.71), unit(0.3, -0.2, 0.6), unit(-0.5, 0.4, -0.3), unit(0.7, 0.7, -0.1)};
    double worst = 0;
    for (BrdfModel model : {BrdfModel::gltf, BrdfModel::thesis})
        for (bool layered : {false, true}) {
            TruthMaterial m;
            m.albedo = {0.9, 0.5, 0.2};
            m.metallic = 0.3;
            m.roughness = 0.4;
            m.specular_weight = 0.7;
            m.specular_color = {1, 0.8, 0.6};
            if (layered) {
                m.clearcoat = 0.6;
                m.clearcoat_roughness = 0.2;
                m.sheen_color = {0.5, 0.4, 0.3};
                m.sheen_roughness = 0.5;
                m.iridescence = 0.7;
                m.iridescence_thickness = 400;
                m.anisotropy = 0.5;
            }
            auto at = [&](double t, auto&& f) {
                m.transmission = t;
                return f();
            };
            auto check = [&](auto&& f, const char* what) {
                const Vec3 zero = at(0.0, f), half = at(0.5, f), one = at(1.0, f);
                for (size_t k = 0; k < 3; ++k) {
                    const double mean = 0.5 * (zero[k] + one[k]);
                    EXPECT_NEAR(half[k], mean, 1e-9 * (1 + std::abs(mean)))
                        << brdf_model_name(model) << (layered ? " layered " : " plain ") << what;
                    worst = std::max(worst, std::abs(half[k] - mean) / (1 + std::abs(mean)));
                }
                return one;
            };
            for (const Vec3& v : views) {
                const Vec3 one = check([&] { return environment_truth(sky, model, m, n, v); }, "environment");
                const Vec3 zero = at(0.0, [&] { return environment_truth(sky, model, m, n, v); });
                if (&v == &views[0]) EXPECT_GT(one[0], 1.5 * zero[0]) << "the sun shines through";
                for (const Vec3& l : lights) {
                    check([&] { return brdf_cos(model, m, n, v, l); }, "brdf_cos");
                    check([&] { return brdf_cos(model, m, n, v, l, true); }, "brdf_cos punctual");
                }
            }
        }
    std::printf("transmission 0.5 against the mean of 0 and 1: worst %.1e (relative to 1 + value)\n", worst);
}

// A light straight behind the surface (l = -v): mirrored, l' reflects v about n, so h = n,
// D = 1 / (pi alpha_T^2) and, at v = n, V = G / (4 n.l' n.v) = 1/4 in both models; F at
// v.h = 1 is F0. So f |n.l| = (1 - metallic) T albedo kd_T / (4 pi alpha_T^2).
TEST(FinalImageTruth, LightStraightBehindTheSurface) {
    const Vec3 n{0, 0, 1}, behind{0, 0, -1};
    TruthMaterial m;
    m.albedo = {0.8, 0.5, 0.2};
    m.metallic = 0.25;
    m.transmission = 0.7;
    m.roughness = 0.6;
    m.specular_weight = 0.8;
    m.specular_color = {1, 0.5, 0.25};
    // glTF, ior 1.5: r_T = r; kd_T = 1 - w max3(min(0.04 x colour, 1)) = 1 - 0.8 x 0.04.
    {
        const double alpha = 0.6 * 0.6, dv = 1 / (4 * pi * alpha * alpha);
        const Vec3 got = brdf_cos(BrdfModel::gltf, m, n, n, behind);
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], 0.75 * 0.7 * m.albedo[c] * (1 - 0.8 * 0.04) * dv, 1e-12 * got[c]) << c;
        // The sheen dims it by its view side's albedo scaling, the coat by 1 - c Fc(1) (Fc = 0.04);
        // neither adds a lobe below the surface.
        TruthMaterial layered = m;
        layered.clearcoat = 0.5;
        layered.clearcoat_roughness = 0.3;
        layered.sheen_color = {0.6, 0.3, 0.1};
        layered.sheen_roughness = 0.5;
        const double sheen = 1 - 0.6 * std::min(sheen_albedo(1.0, 0.5), 1.0);
        const Vec3 dimmed = brdf_cos(BrdfModel::gltf, layered, n, n, behind);
        for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(dimmed[c], got[c] * (1 - 0.5 * 0.04) * sheen, 1e-12 * got[c]) << c;
        // Seen at n.v = 0.6: V = 0.5 / (2 n.v sqrt((n.v)^2 (1 - alpha^2) + alpha^2)), times n.l' = n.v,
        // Fd = Schlick(0.04 x colour, 0.6) (its largest: the red one's 0.04).
        const Vec3 v{0.8, 0, 0.6}, l{-0.8, 0, -0.6};
        const double fd = 0.04 + 0.96 * std::pow(0.4, 5), a2 = alpha * alpha;
        const double oblique = 1 / (pi * a2) * 0.5 / (2 * 0.6 * std::sqrt(0.36 * (1 - a2) + a2)) * 0.6;
        const Vec3 seen = brdf_cos(BrdfModel::gltf, m, n, v, l);
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(seen[c], 0.75 * 0.7 * m.albedo[c] * (1 - 0.8 * fd) * oblique, 1e-12 * seen[c]) << c;
    }
    // The thesis, ior 1.33: r_T = r clamp(2 x 1.33 - 2, 0, 1) = 0.66 r; F0 = mix(F0 x colour,
    // albedo, metallic) per channel, w' = mix(0.8, 1, 0.25) = 0.85, kd_T = 1 - w' F0; G = 1 for
    // either k.
    {
        m.dielectric_f0 = std::pow((1.33 - 1) / (1.33 + 1), 2);
        const double r_t = 0.6 * 0.66, alpha = r_t * r_t, dv = 1 / (4 * pi * alpha * alpha);
        for (bool punctual : {false, true}) {
            const Vec3 got = brdf_cos(BrdfModel::thesis, m, n, n, behind, punctual);
            for (size_t c = 0; c < 3; ++c) {
                const double f0 = 0.75 * m.dielectric_f0 * m.specular_color[c] + 0.25 * m.albedo[c];
                EXPECT_NEAR(got[c], 0.75 * 0.7 * m.albedo[c] * (1 - 0.85 * f0) * dv, 1e-12 * got[c]) << c;
            }
        }
    }
}

// ior 1 (dielectric_f0 0): the transmitted lobe is mirror-sharp whatever the roughness,
// alpha at the reflection's floor 1e-4: straight through (l = -v) D V (n.l') = kd_T / (4 pi
// 1e-8 n.v) at h = n; 10 degrees off it, next to nothing. The reflection keeps its roughness.
TEST(FinalImageTruth, IorOneMakesTheTransmissionMirrorSharp) {
    TruthMaterial m;
    m.dielectric_f0 = 0;
    m.roughness = 0.5;
    m.transmission = 1;
    const Vec3 n{0, 1, 0};
    for (BrdfModel model : {BrdfModel::gltf, BrdfModel::thesis})
        for (double c : {1.0, 0.5}) {
            const Vec3 v = view_at(c), through{-v[0], -v[1], -v[2]};
            // glTF's V at h = n: 0.5 / (2 n.v sqrt((n.v)^2 (1 - a2) + a2)); the thesis' G (k = r_T^2/2 = 0) is 1.
            const double a2 = 1e-8, kd = 1 - std::pow(1 - c, 5);  // F0 0: Schlick = (1 - v.h)^5
            const double v_term =
                model == BrdfModel::gltf ? 0.5 / (2 * c * std::sqrt(c * c * (1 - a2) + a2)) : 1 / (4 * c * c);
            const double peak = kd / (pi * a2) * v_term * c;
            EXPECT_NEAR(brdf_cos(model, m, n, v, through)[0], peak, 1e-9 * peak)
                << brdf_model_name(model) << " n.v " << c;
            EXPECT_GT(peak, 1e6);
            const double t = 10 * pi / 180;  // l turned 10 degrees about z
            const Vec3 off{through[0] * std::cos(t) - through[1] * std::sin(t),
                           through[0] * std::sin(t) + through[1] * std::cos(t), 0};
            const double beside = brdf_cos(model, m, n, v, off)[0];
            EXPECT_LT(beside, 1e-4) << brdf_model_name(model) << " n.v " << c;
            EXPECT_GT(beside, 0.0);
            std::printf("ior 1, %s, n.v %.1f: straight through %.4g, 10 degrees off %.3g\n", brdf_model_name(model), c,
                        peak, beside);
            // The reflection at its mirror direction: the roughness 0.5 lobe's (1 / (pi 0.0625)) x V, not the floor's.
            const Vec3 mirror{-v[0], v[1], 0};
            EXPECT_LT(brdf_cos(model, m, n, v, mirror)[0], 10.0);
        }
}

// No NaN, infinity or negative value from the transmission at the edges: roughness 0, 1e-4
// and 1; n.v 0 and 1e-6; l exactly in the surface's plane (0 there) and in every direction
// of a grid; ior 1, 1.5 and infinite (F0 1); plain and under every layer, both models, both
// k. Below the surface a material that transmits nothing gives exactly 0.
TEST(FinalImageTruth, TransmissionIsFiniteAndNonNegativeAtTheEdges) {
    const Vec3 n{0, 1, 0};
    std::vector<Vec3> directions;
    for (int i = 0; i <= 12; ++i)  // theta from 0 to pi, the plane itself at i = 6
        for (int j = 0; j < 16; ++j) {
            const double theta = i * pi / 12, phi = j * 2 * pi / 16;
            directions.push_back(
                {std::sin(theta) * std::cos(phi), i == 6 ? 0.0 : std::cos(theta), std::sin(theta) * std::sin(phi)});
        }
    int evaluated = 0;
    for (BrdfModel model : {BrdfModel::gltf, BrdfModel::thesis})
        for (double r : {0.0, 1e-4, 1.0})
            for (double f0 : {0.0, 0.04, 1.0})
                for (double c : {0.0, 1e-6, 0.5, 1.0})
                    for (bool layered : {false, true})
                        for (bool punctual : {false, true}) {
                            TruthMaterial m;
                            m.albedo = {1, 0.5, 0};
                            m.metallic = 0.5;
                            m.roughness = r;
                            m.dielectric_f0 = f0;
                            m.transmission = 1;
                            if (layered) {
                                m.clearcoat = 1;
                                m.sheen_color = {1, 1, 1};
                                m.sheen_roughness = 0.5;
                                m.iridescence = 1;
                                m.iridescence_thickness = 300;
                                m.anisotropy = 1;
                            }
                            const Vec3 v = view_at(c);
                            std::vector<Vec3> ls = directions;
                            // Straight through, the mirror direction, v itself, and in the plane.
                            ls.insert(ls.end(),
                                      {Vec3{-v[0], -v[1], -v[2]}, Vec3{-v[0], v[1], 0}, v, Vec3{-v[0], 0, 0}});
                            for (const Vec3& l : ls) {
                                TruthMaterial opaque = m;
                                opaque.transmission = 0;
                                const Vec3 f = brdf_cos(model, m, n, v, l, punctual);
                                const Vec3 f_opaque = brdf_cos(model, opaque, n, v, l, punctual);
                                for (size_t k = 0; k < 3; ++k) {
                                    ASSERT_TRUE(std::isfinite(f[k]) && f[k] >= 0)
                                        << brdf_model_name(model) << " r " << r << " F0 " << f0 << " n.v " << c
                                        << (layered ? " layered" : " plain") << " l " << l[0] << " " << l[1] << " "
                                        << l[2] << ": " << f[k];
                                    if (l[1] == 0) EXPECT_EQ(f[k], 0.0) << "in the plane";
                                    if (l[1] < 0) EXPECT_EQ(f_opaque[k], 0.0) << "below, transmitting nothing";
                                }
                                ++evaluated;
                            }
                        }
    std::printf("transmission at the edges: %d evaluations, all finite and non-negative\n", evaluated);
}

}  // namespace
}  // namespace facet::test
