// The split-sum LUT against a dense deterministic quadrature in double precision,
// written here from the definition: A + B F0 = integral of f_spec(v, l) (n.l) dl.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "graph/compiled_graph.h"
#include "graph/graph_run.h"
#include "gpu/transfer.h"
#include "ibl/brdf_lut.h"
#include "shader/program_cache.h"
#include "support/gpu_test.h"

namespace facet {
namespace {

constexpr double pi = 3.14159265358979323846;

struct Ab {
    double a, b;
};

// In half-vector space, dl = 4 (v.h) dh, so with f = D G F / (4 n.l n.v):
//   A = integral D(h) G(v,l) (1 - Fc) (v.h) / (n.v) dh over n.l > 0, B likewise with Fc.
// The (theta_h, phi) plane is mapped by u = GGX's CDF in theta_h so the grid follows the
// lobe, and u = 1 - s^2 so the weight's (1 - u)^(-1/2) growth at the horizon is removed.
Ab reference(double n_v, double roughness, bool height_correlated) {
    const double alpha = std::max(roughness * roughness, 1e-4), a2 = alpha * alpha;
    const double k = roughness * roughness / 2;
    const double vx = std::sqrt(1 - n_v * n_v), vz = n_v;
    const int nu = 1024, nphi = 256;
    double a = 0, b = 0;
    for (int i = 0; i < nu; ++i) {
        const double s = (i + 0.5) / nu, u = 1 - s * s, jacobian = 2 * s;
        const double cos_t = std::sqrt((1 - u) / (1 + (a2 - 1) * u)), sin_t = std::sqrt(1 - cos_t * cos_t);
        for (int j = 0; j < nphi; ++j) {
            const double phi = 2 * pi * (j + 0.5) / nphi;
            const double hx = sin_t * std::cos(phi), hz = cos_t;
            const double v_h = vx * hx + vz * hz;
            const double l_z = 2 * v_h * hz - vz;
            if (l_z <= 0 || v_h <= 0) continue;
            double g_vis;  // G (v.h) / ((n.h) (n.v)), the weight per sample of density D (n.h)
            if (height_correlated) {
                const double vis = 0.5 / (l_z * std::sqrt(n_v * n_v * (1 - a2) + a2) +
                                          n_v * std::sqrt(l_z * l_z * (1 - a2) + a2));
                g_vis = 4 * vis * l_z * v_h / hz;
            } else {
                const double g = (n_v / (n_v * (1 - k) + k)) * (l_z / (l_z * (1 - k) + k));
                g_vis = g * v_h / (hz * n_v);
            }
            const double fc = std::pow(1 - v_h, 5);
            a += (1 - fc) * g_vis * jacobian;
            b += fc * g_vis * jacobian;
        }
    }
    return {a / (nu * nphi), b / (nu * nphi)};
}

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
        auto run = run_graph(ctx(), c);
        auto bytes = read_image(ctx(), *run->transient_image(lut), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
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
                const Ab ref = reference((x + 0.5) / n, (y + 0.5) / n,
                                         settings.visibility == LutVisibility::height_correlated);
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
                    settings.visibility == LutVisibility::height_correlated ? "height-correlated" : "Schlick-GGX",
                    worst, worst_x, worst_y);
    }
};

// The defaults (128^2, 2048 samples) against the bound of 2e-3.
TEST_F(BrdfLutTest, SchlickGgxMatchesQuadrature) { check_against_reference(BrdfLutSettings{}, 2e-3); }

TEST_F(BrdfLutTest, HeightCorrelatedMatchesQuadrature) {
    BrdfLutSettings settings;
    settings.visibility = LutVisibility::height_correlated;
    check_against_reference(settings, 2e-3);
}

// Third channel: E_avg = 2 * integral E(mu) mu dmu with E = A + B, per roughness row.
TEST_F(BrdfLutTest, EnergyChannelIsTheRowsAverageAlbedo) {
    const uint32_t n = 64;
    auto t = bake({n, 512, LutVisibility::smith_schlick_ggx});
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
