// Prefiltered specular levels against brute-force double-precision integration of the
// same integrand (GGX lobe around n = v = R, weighted by n.l) over every texel.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <thread>

#include <facet/gpu/resources.h>
#include "ibl/environment_cube.h"
#include <facet/ibl/specular.h>
#include <facet/io/environment_image.h>
#include "support/gpu_test.h"
#include "support/ibl_gpu.h"
#include <facet/reference/ibl_reference.h>

namespace facet {
namespace {

using namespace test;

constexpr double pi = 3.14159265358979323846;

class SpecularTest : public GpuTest {
protected:
    CubeLevels bake(const Equirect& e, const SpecularSettings& s) {
        return run_ibl(ctx(), e, [&](RenderGraph& g, ProgramCache& programs, const Sampler& sampler, ImageHandle cube,
                                     ImageHandle equirect) {
            const ImageDesc env = g.resource(cube).image_desc;
            auto out = g.create_image("specular", environment_cube_desc(env.width, s.levels));
            auto written = add_specular_passes(g, programs, sampler, cube, out, s, equirect, run_ibl_equirect_sampler());
            EXPECT_TRUE(written) << (written ? "" : written.error().message);
            return *written;
        });
    }

    // Luminance of the truth at every texel centre of a level of face size n.
    std::vector<double> truth(const TexelTable& e, uint32_t n, float roughness) {
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
    EXPECT_EQ(specular_level_method(s, 0.0f), SpecularMethod::hybrid);  // level 0 is a copy whatever the method
    EXPECT_EQ(specular_level_method(s, 0.2f), SpecularMethod::hybrid);
    EXPECT_EQ(specular_level_method(s, 0.4f), SpecularMethod::hybrid);
    EXPECT_EQ(specular_level_method(s, 0.5f), SpecularMethod::convolve);
    EXPECT_EQ(specular_level_method(s, 0.6f), SpecularMethod::convolve);
    EXPECT_EQ(convolve_source_size(1.0f), 8u);
    EXPECT_EQ(convolve_source_size(0.4f), 16u);
}

TEST_F(SpecularTest, WhiteFurnaceIsOneOnEveryLevelForEveryMethod) {
    const Equirect white = uniform_sky(64, 32, 1.0f);
    for (auto m : {SpecularMethod::automatic, SpecularMethod::importance, SpecularMethod::filtered,
                   SpecularMethod::convolve, SpecularMethod::mips, SpecularMethod::hybrid}) {
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
    const TexelTable table(sky);
    for (uint32_t l = 1; l < levels; ++l) truths[l] = truth(table, 64 >> l, roughness[l]);
    struct Case {
        SpecularMethod method;
        double bound;
    };
    // automatic meets the 3% per level. The others show where they break on a sun
    // (the printout has the figures): filtered and importance sampling stay noisy at
    // 1024 samples (fireflies), mips are a box filter, not a GGX lobe.
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

// The default settings at bake scale: a 512x256 sun sky (cube 128^2, 6 levels, roughness
// 0, 0.2, ... 1), each level measured at 1500 random directions plus 500 within 10 degrees
// of the sun, against the truth over every texel. The target is 3% per level.
// Measured: levels 1-2 (roughness 0.2, 0.4, hybrid) 0.03% and 0.40% (filtered importance
// sampling at 1024 samples was 2.6% on level 1), the convolve levels 0.1-0.2%; the bound
// is 2% per level.
TEST_F(SpecularTest, DefaultsAtBakeScale) {
    const Equirect sky = sun_sky(512, 256, 5e4, 2.5, 30, 40);
    SpecularSettings s;  // defaults: automatic, 6 levels
    CubeLevels spec = bake(sky, s);
    ASSERT_EQ(spec.size, 128u);
    ASSERT_EQ(spec.levels.size(), 6u);
    const std::vector<float> roughness = specular_level_roughness(6);
    const Vec3 sun = equirect_direction(40.0 / 360 + 0.5, 0.5 - 30.0 / 180);
    std::mt19937 rng(11);
    std::normal_distribution<double> normal;
    std::vector<Vec3> directions;
    for (int i = 0; i < 2000; ++i) {
        Vec3 d{normal(rng), normal(rng), normal(rng)};
        if (i >= 1500)
            for (int c = 0; c < 3; ++c) d[c] = sun[c] + 0.1 * d[c];  // about 10 degrees around the sun
        const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (double& v : d) v /= len;
        directions.push_back(d);
    }
    const double bounds[] = {0, 0.02, 0.02, 0.02, 0.02, 0.02};
    const TexelTable table(sky);
    for (uint32_t l = 1; l < 6; ++l) {
        const uint32_t n = 128 >> l;
        double sum = 0, truth_sum = 0;
        for (const Vec3& d : directions) {
            uint32_t face;
            double fs, ft;
            select_cube_face(d, face, fs, ft);
            const uint32_t x = std::min(uint32_t(fs * n), n - 1), y = std::min(uint32_t(ft * n), n - 1);
            // Compare at the texel centre the GPU computed.
            const double truth = luminance(prefiltered(table, cube_texel_direction(face, x, y, n), roughness[l]));
            const double diff = luminance(spec.texel(l, face, x, y)) - truth;
            sum += diff * diff;
            truth_sum += truth;
        }
        const double err = std::sqrt(sum / directions.size()) / (truth_sum / directions.size());
        std::printf("bake scale, level %u (roughness %.1f, %s): relRMSE %.2f%%\n", l, roughness[l],
                    specular_method_name(specular_level_method(s, roughness[l])), 100 * err);
        EXPECT_LE(err, bounds[l]) << "level " << l;
    }
}

// The shared environments (256x128, cube 64^2, roughness 1/3, 2/3, 1), convolve levels
// listing the equirect's own texels, hybrid at roughness 1/3. Measured 0.31-1.29% (filtered
// importance sampling at roughness 1/3 was up to 2.66%): within the 3% target.
TEST_F(SpecularTest, SharedEnvironments) {
    for (const char* name : {"venice_sunset_1k.hdr", "royal_esplanade_1k.hdr", "studio_small_03_1k.hdr",
                             "empty_warehouse_01_1k.hdr"}) {
        auto env = load_environment(std::string(FACET_SHARED_DATA_DIR) + "/env/" + name);
        ASSERT_TRUE(env) << env.error().message;
        const Equirect e = downsample(Equirect{env->width, env->height, env->rgba}, 4);  // 256x128 -> cube 64
        CubeLevels spec = bake(e, with(SpecularMethod::automatic, 4));
        const std::vector<float> roughness = specular_level_roughness(4);
        const TexelTable table(e);
        for (uint32_t l = 1; l < 4; ++l) {
            const double err = level_error(truth(table, 64 >> l, roughness[l]), spec, l);
            std::printf("%s, level %u (roughness %.2f): relRMSE %.2f%%\n", name, l, roughness[l], 100 * err);
            EXPECT_LE(err, 0.03) << name << " level " << l;
        }
    }
}

// Where methods break: one hot texel, a black sky, a 3:1 input. Finite, non-negative,
// black stays black, and the hot texel's light is neither lost nor multiplied.
TEST_F(SpecularTest, HotTexelBlackSkyAndOddAspect) {
    Equirect hot = uniform_sky(128, 64, 0.0f);
    for (int c = 0; c < 3; ++c) hot.rgba[(size_t(20) * 128 + 37) * 4 + c] = 1e5f;
    Equirect wide = uniform_sky(96, 32, 0.25f);
    for (auto m : {SpecularMethod::automatic, SpecularMethod::importance, SpecularMethod::filtered,
                   SpecularMethod::convolve, SpecularMethod::mips, SpecularMethod::hybrid}) {
        for (const Equirect* e : {&hot, &wide}) {
            CubeLevels spec = bake(*e, with(m, 4));
            for (const auto& level : spec.levels)
                for (float v : level) ASSERT_TRUE(std::isfinite(v) && v >= 0) << specular_method_name(m);
        }
        CubeLevels black = bake(uniform_sky(64, 32, 0.0f), with(m, 3));
        for (const auto& level : black.levels)
            for (size_t i = 0; i < level.size(); ++i)
                if (i % 4 != 3) ASSERT_EQ(level[i], 0.0f) << specular_method_name(m);
    }
    // The roughest convolved level of the hot texel: its mean over the sphere, weighted by
    // solid angle, stays within 10% of the truth's (the light is spread, not lost).
    CubeLevels spec = bake(hot, with(SpecularMethod::automatic, 4));
    const TexelTable table(hot);
    const uint32_t n = spec.size >> 3;
    const std::vector<double> t = truth(table, n, 1.0f);
    double gpu_sum = 0, truth_sum = 0;
    size_t i = 0;
    for (uint32_t f = 0; f < 6; ++f)
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x, ++i) {
                gpu_sum += luminance(spec.texel(3, f, x, y));
                truth_sum += t[i];
            }
    EXPECT_NEAR(gpu_sum / truth_sum, 1.0, 0.1);
    // The hybrid level (roughness 1/3) of the hot texel: all of it is excess, summed
    // exactly, so each texel is within 2% of the truth.
    const uint32_t n1 = spec.size >> 1;
    const std::vector<double> t1 = truth(table, n1, 1.0f / 3);
    ASSERT_EQ(specular_level_method(SpecularSettings{}, 1.0f / 3), SpecularMethod::hybrid);
    double sum = 0, sum_truth = 0;
    i = 0;
    for (uint32_t f = 0; f < 6; ++f)
        for (uint32_t y = 0; y < n1; ++y)
            for (uint32_t x = 0; x < n1; ++x, ++i) {
                const double d = luminance(spec.texel(1, f, x, y)) - t1[i];
                sum += d * d;
                sum_truth += t1[i];
            }
    const double err = std::sqrt(sum / t1.size()) / (sum_truth / t1.size());
    std::printf("hot texel, hybrid level 1: relRMSE %.2f%%\n", 100 * err);
    EXPECT_LT(err, 0.02);
}

// The default bake (hybrid below roughness 0.5) at full scale, 1024 x 512 inputs, against
// the exact prefiltered integral over every texel: half the directions anywhere, half
// near the brightest texel, where the excess list and its coarse fallback (studio) count.
// Measured 2026-12-05 (128 samples): at most 1.40% (studio level 1, on the coarse
// fallback: its list is longer than 256 entries); sun skies 0.04-0.43%.
// Levels 1 and 2 of the default bake (the residual's part at half size, the excess exact)
// and the same with every part at the level's own size (--hybrid-full-size), each against
// the same brute-force truth: both within 2% on every sky, and the half size within 0.2
// points of the full size (its error was 0.03-1.36% against 0.04-1.40%).
TEST_F(SpecularTest, HybridLevelsAtFullScaleOnRealSkies) {
    std::vector<std::pair<std::string, Equirect>> envs;
    envs.push_back({"sun sky 0.53", sun_sky(1024, 512, 1e5, 0.53, 30, 40)});
    envs.push_back({"sun sky 2.5", sun_sky(1024, 512, 5e4, 2.5, 30, 40)});
    for (const char* name : {"venice_sunset_1k.hdr", "royal_esplanade_1k.hdr", "studio_small_03_1k.hdr",
                             "empty_warehouse_01_1k.hdr"}) {
        auto env = load_environment(std::string(FACET_SHARED_DATA_DIR) + "/env/" + name);
        envs.push_back({name, Equirect{env->width, env->height, env->rgba}});
    }
    for (auto& [name, e] : envs) {
        SpecularSettings s;
        SpecularSettings full = s;
        full.hybrid_half_size_residual = false;
        const CubeLevels spec = bake(e, s), spec_full = bake(e, full);
        const std::vector<float> roughness = specular_level_roughness(6);
        size_t brightest = 0;
        for (size_t i = 0; i < size_t(e.w) * e.h; ++i)
            if (luminance(&e.rgba[4 * i]) > luminance(&e.rgba[4 * brightest])) brightest = i;
        const Vec3 sun = equirect_direction((brightest % e.w + 0.5) / e.w, (brightest / e.w + 0.5) / e.h);
        std::mt19937 rng(11);
        std::normal_distribution<double> normal;
        std::vector<Vec3> directions;
        for (int i = 0; i < 1000; ++i) {
            Vec3 d{normal(rng), normal(rng), normal(rng)};
            if (i >= 500)
                for (int c = 0; c < 3; ++c) d[c] = sun[c] + 0.1 * d[c];
            const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (double& v : d) v /= len;
            directions.push_back(d);
        }
        const TexelTable table(e);
        for (uint32_t l = 1; l <= 2; ++l) {
            ASSERT_EQ(specular_level_method(s, roughness[l]), SpecularMethod::hybrid);
            const uint32_t n = spec.size >> l;
            ASSERT_TRUE(hybrid_residual_at_half_size(s, roughness[l], n)) << "level " << l;
            ASSERT_FALSE(hybrid_residual_at_half_size(full, roughness[l], n));
            std::vector<double> truth(directions.size()), got(directions.size()), got_full(directions.size());
            std::vector<std::thread> threads;
            for (int t = 0; t < 2; ++t)
                threads.emplace_back([&, t] {
                    for (size_t i = t; i < directions.size(); i += 2) {
                        uint32_t face;
                        double fs, ft;
                        select_cube_face(directions[i], face, fs, ft);
                        const uint32_t x = std::min(uint32_t(fs * n), n - 1), y = std::min(uint32_t(ft * n), n - 1);
                        truth[i] = luminance(prefiltered(table, cube_texel_direction(face, x, y, n), roughness[l]));
                        got[i] = luminance(spec.texel(l, face, x, y));
                        got_full[i] = luminance(spec_full.texel(l, face, x, y));
                    }
                });
            for (auto& t : threads) t.join();
            // relRMSE in % of a level's texels against the truth: all 1000, and the 500 near the sun.
            auto errors = [&](const std::vector<double>& level) {
                double sum = 0, truth_sum = 0, near = 0, near_truth = 0;
                for (size_t i = 0; i < directions.size(); ++i) {
                    const double d = level[i] - truth[i];
                    sum += d * d;
                    truth_sum += truth[i];
                    if (i >= 500) near += d * d, near_truth += truth[i];
                }
                return std::pair{100 * std::sqrt(sum / directions.size()) / (truth_sum / directions.size()),
                                 100 * std::sqrt(near / 500) / (near_truth / 500)};
            };
            const auto [all, close] = errors(got);
            const auto [all_full, close_full] = errors(got_full);
            std::printf("%s level %u: relRMSE %.2f%% (near the brightest texel %.2f%%); at full size %.2f%% (%.2f%%)\n",
                        name.c_str(), l, all, close, all_full, close_full);
            for (double e : {all, close, all_full, close_full}) EXPECT_LT(e, 2.0) << name << " level " << l;
            EXPECT_LT(all, all_full + 0.2) << name << " level " << l;
            EXPECT_LT(close, close_full + 0.2) << name << " level " << l;
        }
    }
}

TEST_F(SpecularTest, TinyInputsAndOneLevel) {
    CubeLevels one = bake(uniform_sky(64, 32, 0.5f), with(SpecularMethod::automatic, 1));
    ASSERT_EQ(one.levels.size(), 1u);
    for (size_t i = 0; i < one.levels[0].size(); ++i)
        if (i % 4 != 3) ASSERT_NEAR(one.levels[0][i], 0.5f, 1e-6f);
    for (auto [w, h] : {std::pair{1u, 1u}, {2u, 1u}}) {
        CubeLevels tiny = bake(uniform_sky(w, h, 0.5f), with(SpecularMethod::automatic, 1));
        for (size_t i = 0; i < tiny.levels[0].size(); ++i) {
            ASSERT_TRUE(std::isfinite(tiny.levels[0][i]));
            if (i % 4 != 3) EXPECT_NEAR(tiny.levels[0][i], 0.5f, 1e-6f) << w << "x" << h;
        }
    }
}

}  // namespace
}  // namespace facet
