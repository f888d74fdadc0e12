// Prefiltered specular levels against brute-force double-precision integration of the
// same integrand (GGX lobe around n = v = R, weighted by n.l) over every texel.
#include <gtest/gtest.h>

#include <cmath>

#include "gpu/resources.h"
#include "ibl/environment_cube.h"
#include "ibl/specular.h"
#include "support/gpu_test.h"
#include "support/ibl_gpu.h"
#include "support/ibl_reference.h"

namespace facet {
namespace {

using namespace test;

constexpr double pi = 3.14159265358979323846;

// P(R) = sum L w dw / sum w dw, w = D(h) (n.l), h = normalize(n + l), over every texel.
Vec3 prefiltered(const Equirect& e, const Vec3& n, double roughness) {
    const double alpha = std::max(roughness * roughness, 1e-4), a2 = alpha * alpha;
    Vec3 sum{0, 0, 0};
    double weight = 0;
    for (uint32_t y = 0; y < e.h; ++y) {
        const double dw = equirect_texel_solid_angle(y, e.w, e.h);
        for (uint32_t x = 0; x < e.w; ++x) {
            const Vec3 l = equirect_direction((x + 0.5) / e.w, (y + 0.5) / e.h);
            const double n_l = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
            if (n_l <= 0) continue;
            // n.h for h = normalize(n + l): sqrt((1 + n.l) / 2).
            const double n_h = std::sqrt((1 + n_l) / 2);
            const double t = n_h * n_h * (a2 - 1) + 1;
            const double w = a2 / (pi * t * t) * n_l * dw;
            const float* L = e.at(x, y);
            for (int c = 0; c < 3; ++c) sum[c] += w * L[c];
            weight += w;
        }
    }
    return {sum[0] / weight, sum[1] / weight, sum[2] / weight};
}

class SpecularTest : public GpuTest {
protected:
    CubeLevels bake(const Equirect& e, const SpecularSettings& s) {
        return run_ibl(ctx(), e, [&](RenderGraph& g, ProgramCache& programs, const Sampler& sampler, ImageHandle cube) {
            const ImageDesc env = g.resource(cube).image_desc;
            auto out = g.create_image("specular", environment_cube_desc(env.width, s.levels));
            auto written = add_specular_passes(g, programs, sampler, cube, out, s);
            EXPECT_TRUE(written) << (written ? "" : written.error().message);
            return *written;
        });
    }

    // Luminance of the truth at every texel centre of a level of face size n.
    std::vector<double> truth(const Equirect& e, uint32_t n, float roughness) {
        std::vector<double> t;
        for (uint32_t f = 0; f < 6; ++f)
            for (uint32_t y = 0; y < n; ++y)
                for (uint32_t x = 0; x < n; ++x)
                    t.push_back(luminance(prefiltered(e, cube_texel_direction(f, x, y, n), roughness)));
        return t;
    }

    // relRMSE = RMS(Y - Y_true) / mean(Y_true) over the level's texel centres.
    double level_error(const std::vector<double>& truth, const CubeLevels& spec, uint32_t level) {
        const uint32_t n = std::max(1u, spec.size >> level);
        double sum = 0, truth_sum = 0;
        size_t i = 0;
        for (uint32_t f = 0; f < 6; ++f)
            for (uint32_t y = 0; y < n; ++y)
                for (uint32_t x = 0; x < n; ++x, ++i) {
                    const double diff = luminance(spec.texel(level, f, x, y)) - truth[i];
                    sum += diff * diff;
                    truth_sum += truth[i];
                }
        return std::sqrt(sum / i) / (truth_sum / i);
    }
};

SpecularSettings with(SpecularMethod method, uint32_t levels) {
    SpecularSettings s;
    s.method = method;
    s.levels = levels;
    return s;
}

TEST(SpecularLevels, RoughnessPerLevelAndMethodChoice) {
    EXPECT_EQ(specular_level_roughness(6), (std::vector<float>{0.0f, 0.2f, 0.4f, 0.6f, 0.8f, 1.0f}));
    SpecularSettings s;
    EXPECT_EQ(specular_level_method(s, 0.2f), SpecularMethod::filtered);
    EXPECT_EQ(specular_level_method(s, 0.6f), SpecularMethod::convolve);
    EXPECT_EQ(convolve_source_size(1.0f), 8u);
    EXPECT_EQ(convolve_source_size(0.4f), 32u);
}

TEST_F(SpecularTest, WhiteFurnaceIsOneOnEveryLevelForEveryMethod) {
    const Equirect white = uniform_sky(64, 32, 1.0f);
    for (auto m : {SpecularMethod::automatic, SpecularMethod::importance, SpecularMethod::filtered,
                   SpecularMethod::convolve, SpecularMethod::mips}) {
        CubeLevels spec = bake(white, with(m, 5));
        ASSERT_EQ(spec.levels.size(), 5u);
        for (uint32_t l = 0; l < spec.levels.size(); ++l)
            for (size_t i = 0; i < spec.levels[l].size(); ++i)
                if (i % 4 != 3) ASSERT_NEAR(spec.levels[l][i], 1.0f, 1e-3f) << specular_method_name(m) << " level " << l;
    }
}

TEST_F(SpecularTest, LevelsOnASunnySky) {
    const Equirect sky = sun_sky(256, 128, 5e4, 2.5, 30, 40);  // cube 64^2, levels 64 .. 8
    const uint32_t levels = 4;                                // roughness 0, 1/3, 2/3, 1
    const std::vector<float> roughness = specular_level_roughness(levels);
    std::vector<std::vector<double>> truths(levels);
    for (uint32_t l = 1; l < levels; ++l) truths[l] = truth(sky, 64 >> l, roughness[l]);
    struct Case {
        SpecularMethod method;
        double bound;
    };
    // automatic meets the 3% per level. The others show where they break on a sun:
    // measured filtered 14-23% (256 samples), importance up to 320% (fireflies), mips up to
    // 1840% (a box filter is not a GGX lobe).
    for (Case c : {Case{SpecularMethod::automatic, 0.03}, Case{SpecularMethod::filtered, 0.3},
                   Case{SpecularMethod::importance, 5.0}, Case{SpecularMethod::mips, 25.0}}) {
        CubeLevels spec = bake(sky, with(c.method, levels));
        for (uint32_t l = 1; l < levels; ++l) {
            const double err = level_error(truths[l], spec, l);
            std::printf("sun sky, %s, level %u (roughness %.2f): relRMSE %.2f%%\n", specular_method_name(c.method), l,
                        roughness[l], 100 * err);
            EXPECT_LE(err, c.bound) << specular_method_name(c.method) << " level " << l;
        }
        for (const auto& level : spec.levels)
            for (float v : level) ASSERT_TRUE(std::isfinite(v) && v >= 0) << specular_method_name(c.method);
    }
}

TEST_F(SpecularTest, TinyInputsAndOneLevel) {
    CubeLevels one = bake(uniform_sky(64, 32, 0.5f), with(SpecularMethod::automatic, 1));
    ASSERT_EQ(one.levels.size(), 1u);
    for (size_t i = 0; i < one.levels[0].size(); ++i)
        if (i % 4 != 3) ASSERT_NEAR(one.levels[0][i], 0.5f, 1e-6f);
    CubeLevels tiny = bake(uniform_sky(2, 1, 0.5f), with(SpecularMethod::automatic, 1));
    for (float v : tiny.levels[0]) ASSERT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace facet
