// Issue 13's per-group measurement (facet::reference, final_image_accuracy.h) on
// synthetic frames whose error is known: a render equal to the truth except +10% in one
// group, plus pixels the measurement must leave out.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <facet/reference/final_image_accuracy.h>

namespace facet::test {
namespace {

struct Frame {
    uint32_t w, h;
    std::vector<float> hdr, normal, position, basecolor, metallic, roughness;
    FinalImageViews views() const { return {w, h, hdr, normal, position, basecolor, metallic, roughness}; }
};

TEST(FinalImageAccuracy, TenPercentInOneGroupAndNothingElsewhere) {
    const Equirect env = sun_sky(64, 32, 50.0, 6.0, 40.0, 20.0);
    const TexelLights lights = texel_lights(env);
    const Vec3 eye{0, 0, 1000};  // far along +z: n.v = n.z
    Frame f{40, 24};
    const size_t count = size_t(f.w) * f.h;
    for (auto* image : {&f.hdr, &f.normal, &f.position, &f.basecolor, &f.metallic, &f.roughness})
        image->assign(count * 4, 0.0f);
    const double bands[] = {0.25, 0.5, 0.7, 0.95};
    for (uint32_t y = 0; y < f.h; ++y)
        for (uint32_t x = 0; x < f.w; ++x) {
            const size_t i = size_t(y) * f.w + x;
            // Columns: 8 groups of 4 (band, metal), then 4 left-out kinds of 2 columns.
            const uint32_t g = x / 4;
            double roughness = g < 8 ? bands[g / 2] : 0.5, metallic = g < 8 ? double(g % 2) : 0.0;
            double tilt = 0.2 * std::sin(0.7 * y + x);  // n.v between ~0.98 and 1
            bool covered = true;
            if (g == 8) roughness = 0.15;   // too smooth
            if (g == 9) tilt = 1.2;         // n.v = cos(1.2) = 0.36: kept
            if (g == 9 && x % 2) tilt = 1.3;  // n.v = 0.27: left out
            if (g == 10) covered = false;
            const Vec3 n{std::sin(tilt), 0, std::cos(tilt)};
            const float albedo[3] = {0.8f, 0.6f, 0.3f};
            for (int c = 0; c < 3; ++c) {
                f.normal[i * 4 + c] = float(n[size_t(c)]);
                f.basecolor[i * 4 + c] = albedo[c];
                f.metallic[i * 4 + c] = float(metallic);
                f.roughness[i * 4 + c] = float(roughness);
            }
            f.position[i * 4] = float(x) * 0.01f;
            f.position[i * 4 + 1] = float(y) * 0.01f;
            for (auto* image : {&f.normal, &f.position, &f.basecolor, &f.metallic, &f.roughness, &f.hdr})
                (*image)[i * 4 + 3] = covered ? 1.0f : 0.0f;
            // The truth of the views' material (as the measurement reads it, in float).
            TruthMaterial m;
            m.albedo = {albedo[0], albedo[1], albedo[2]};
            m.metallic = f.metallic[i * 4];
            m.roughness = f.roughness[i * 4];
            const Vec3 nf{f.normal[i * 4], f.normal[i * 4 + 1], f.normal[i * 4 + 2]};
            const double px = f.position[i * 4], py = f.position[i * 4 + 1];
            const double len = std::sqrt(px * px + py * py + 1000.0 * 1000.0);
            const Vec3 v{-px / len, -py / len, 1000.0 / len};
            const double nlen = std::sqrt(nf[0] * nf[0] + nf[1] * nf[1] + nf[2] * nf[2]);
            const Vec3 t = environment_truth(lights, BrdfModel::gltf, m, {nf[0] / nlen, nf[1] / nlen, nf[2] / nlen}, v);
            // +10% in group 3 ([0.4,0.6) metal); garbage where the pixel must be left out.
            const double scale = g == 3 ? 1.1 : (g == 8 || g == 10 || (g == 9 && x % 2)) ? 7.0 : 1.0;
            for (int c = 0; c < 3; ++c) f.hdr[i * 4 + c] = float(t[size_t(c)] * scale);
        }
    AccuracySettings settings;
    settings.threads = 2;
    const FinalImageAccuracy a = final_image_accuracy(f.views(), eye, lights, BrdfModel::gltf, settings);
    SCOPED_TRACE(format_accuracy_table(a));
    for (int g = 0; g < 8; ++g) {
        const GroupError& e = a.groups[size_t(g)];
        // 4 columns x 24 rows per group; group 2 ([0.4,0.6) dielectric) also gets the 48
        // kept n.v = 0.36 pixels of columns 36 and 38.
        EXPECT_EQ(e.pixels, g == 2 ? 4u * 24 + 48 : 4u * 24) << group_name(e);
        if (g == 3) {
            EXPECT_NEAR(e.mean_rel, 0.1, 1e-5);
            EXPECT_NEAR(e.max_rel, 0.1, 1e-5);
            EXPECT_NEAR(e.mean_signed, 0.1, 1e-5);
        } else {
            EXPECT_LT(e.mean_rel, 1e-5) << group_name(e);
            EXPECT_LT(e.max_rel, 1e-5) << group_name(e);
        }
    }
    EXPECT_EQ(a.worst, 3);
    EXPECT_NEAR(a.worst_mean_rel, 0.1, 1e-5);
    EXPECT_EQ(a.pixels, 8u * 4 * 24 + 48);

    // A budget spreads over the eligible pixels and still measures the same errors.
    settings.max_pixels = 100;
    const FinalImageAccuracy b = final_image_accuracy(f.views(), eye, lights, BrdfModel::gltf, settings);
    EXPECT_EQ(b.pixels, 100u);
    for (const GroupError& e : b.groups) EXPECT_GT(e.pixels, 5u) << group_name(e);
    EXPECT_NEAR(b.groups[3].mean_rel, 0.1, 1e-5);
    // Measured against the other model, the same frame is off everywhere.
    const FinalImageAccuracy c = final_image_accuracy(f.views(), eye, lights, BrdfModel::thesis, settings);
    EXPECT_GT(c.groups[7].mean_rel, 1e-3);
}

TEST(FinalImageAccuracy, RejectsImagesOfTheWrongSize) {
    std::vector<float> small(3 * 4, 0.0f), right(2 * 2 * 4, 0.0f);
    FinalImageViews v{2, 2, right, right, right, right, right, small};
    EXPECT_THROW(final_image_accuracy(v, {0, 0, 1}, uniform_sky(8, 4, 1.0f), BrdfModel::gltf), std::invalid_argument);
}

}  // namespace
}  // namespace facet::test
