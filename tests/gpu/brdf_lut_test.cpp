// The split-sum LUT against a dense deterministic quadrature in double precision,
// written here from the definition: A + B F0 = integral of f_spec(v, l) (n.l) dl.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/gpu/transfer.h>
#include <facet/ibl/brdf_lut.h>
#include <facet/shader/program_cache.h>
#include "support/gpu_test.h"
#include <facet/reference/ibl_reference.h>

namespace facet {
namespace {

constexpr double pi = 3.14159265358979323846;

class BrdfLutTest : public test::GpuTest {
protected:
    std::vector<float> bake(const BrdfLutSettings& settings) {
        ShaderCompiler compiler;
        ProgramCache programs(ctx(), compiler);
        RenderGraph g;
        ImageDesc desc;
        desc.width = desc.height = settings.size;
        auto lut = g.create_image("brdf lut", desc);
        auto out = add_brdf_lut_passes(g, programs, settings, lut);
        EXPECT_TRUE(out);
        g.export_image(*out, {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                              VK_ACCESS_2_TRANSFER_READ_BIT});
        CompiledGraph c = g.compile();
        auto run = test::must(run_graph(ctx(), c));
        auto bytes = test::must(read_image(ctx(), *run->transient_image(lut), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
        std::vector<float> t(bytes.size() / 4);
        std::memcpy(t.data(), bytes.data(), bytes.size());
        return t;
    }

    void check_against_reference(const BrdfLutSettings& settings, double bound) {
        auto t = bake(settings);
        const uint32_t n = settings.size;
        ASSERT_EQ(t.size(), size_t(n) * n * 4);
        for (float v : t) ASSERT_TRUE(std::isfinite(v));
        double worst = 0;
        uint32_t worst_x = 0, worst_y = 0;
        // Every 8th texel in each direction plus the edges (n.v and roughness near 0 and 1).
        std::vector<uint32_t> picks;
        for (uint32_t i = 0; i < n; i += 8) picks.push_back(i);
        picks.push_back(n - 1);
        for (uint32_t y : picks)
            for (uint32_t x : picks) {
                const test::Ab ref = test::brdf_lut_reference((x + 0.5) / n, (y + 0.5) / n,
                                         settings.brdf == BrdfModel::gltf);
                const float* texel = &t[(size_t(y) * n + x) * 4];
                const double err = std::max(std::abs(texel[0] - ref.a), std::abs(texel[1] - ref.b));
                if (err > worst) {
                    worst = err;
                    worst_x = x;
                    worst_y = y;
                }
            }
        RecordProperty("max_abs_error", std::to_string(worst));
        EXPECT_LE(worst, bound) << "worst at x " << worst_x << " y " << worst_y;
        std::printf("LUT %ux%u, %u samples, %s: max abs error %.2e (x %u, y %u)\n", n, n, settings.sample_count,
                    settings.brdf == BrdfModel::gltf ? "glTF (height-correlated)" : "thesis (Schlick-GGX)",
                    worst, worst_x, worst_y);
    }
};

// The defaults (128^2, 2048 samples, glTF's model) against the bound of 2e-3.
TEST_F(BrdfLutTest, GltfModelMatchesQuadrature) { check_against_reference(BrdfLutSettings{}, 2e-3); }

TEST_F(BrdfLutTest, ThesisModelMatchesQuadrature) {
    BrdfLutSettings settings;
    settings.brdf = BrdfModel::thesis;
    check_against_reference(settings, 2e-3);
}

// Fourth channel: W(n.v) = integral over the hemisphere of (1 - v.h)^5 (n.l) / pi, the
// diffuse lobe's mean Fresnel weight (h = normalize(v + l), no roughness), against a
// midpoint quadrature in (theta, phi) here; equal along every row.
TEST_F(BrdfLutTest, FourthChannelIsTheDiffuseFresnelWeight) {
    const uint32_t n = 32;
    auto t = bake({n, 1024, BrdfModel::gltf});
    for (uint32_t x = 0; x < n; x += 5) {
        const double mu = (x + 0.5) / n, sv = std::sqrt(1 - mu * mu);
        double w = 0;
        const int steps = 400;
        for (int i = 0; i < steps; ++i)
            for (int j = 0; j < 2 * steps; ++j) {
                const double theta = (i + 0.5) / steps * M_PI / 2, phi = (j + 0.5) / (2 * steps) * 2 * M_PI;
                const double l[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
                double h[3] = {l[0] + sv, l[1], l[2] + mu};
                const double len = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                const double vh = (h[0] * sv + h[2] * mu) / len;
                w += std::pow(1 - vh, 5) * std::cos(theta) / M_PI * std::sin(theta) * (M_PI / 2 / steps) *
                     (2 * M_PI / (2 * steps));
            }
        for (uint32_t y : {0u, n / 2, n - 1})
            EXPECT_NEAR(t[(size_t(y) * n + x) * 4 + 3], w, 2e-3) << "n.v " << mu << " row " << y;
    }
}

// Third channel: E_avg = 2 * integral E(mu) mu dmu with E = A + B, per roughness row.
TEST_F(BrdfLutTest, EnergyChannelIsTheRowsAverageAlbedo) {
    const uint32_t n = 64;
    auto t = bake({n, 512, BrdfModel::thesis});
    for (uint32_t y : {0u, n / 2, n - 1}) {
        double sum = 0;
        for (uint32_t x = 0; x < n; ++x) {
            const float* texel = &t[(size_t(y) * n + x) * 4];
            sum += (texel[0] + texel[1]) * (x + 0.5) / n;
        }
        const double e_avg = 2 * sum / n;
        for (uint32_t x = 0; x < n; x += 7) EXPECT_NEAR(t[(size_t(y) * n + x) * 4 + 2], e_avg, 1e-5) << "row " << y;
        EXPECT_LE(e_avg, 1.0 + 1e-4);
        EXPECT_GT(e_avg, 0.3);
    }
    // Smooth surfaces lose no energy to single scattering; rough ones do.
    EXPECT_NEAR(t[2], 1.0, 0.02);
    EXPECT_LT(t[(size_t(n - 1) * n) * 4 + 2], 0.9);
}

}  // namespace
}  // namespace facet
