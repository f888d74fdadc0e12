// Equirect -> cube and its mip chain, against the Vulkan spec's face selection (written
// in tests/support in the forward direction) and the power of the input in double.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ibl/environment_cube.h"
#include <facet/io/environment_image.h>
#include "support/gpu_test.h"
#include "support/ibl_gpu.h"
#include <facet/reference/ibl_reference.h>

namespace facet {
namespace {

using namespace test;

double face_area(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1)); }
double texel_solid_angle(uint32_t x, uint32_t y, uint32_t n) {
    const double x0 = 2.0 * x / n - 1, x1 = 2.0 * (x + 1) / n - 1, y0 = 2.0 * y / n - 1, y1 = 2.0 * (y + 1) / n - 1;
    return face_area(x0, y0) - face_area(x0, y1) - face_area(x1, y0) + face_area(x1, y1);
}

double equirect_power(const Equirect& e, int c) {
    double sum = 0;
    for (uint32_t y = 0; y < e.h; ++y)
        for (uint32_t x = 0; x < e.w; ++x) sum += e.at(x, y)[c] * equirect_texel_solid_angle(y, e.w, e.h);
    return sum;
}

double cube_power(const CubeLevels& cube, uint32_t mip, int c) {
    const uint32_t n = std::max(1u, cube.size >> mip);
    double sum = 0;
    for (uint32_t f = 0; f < 6; ++f)
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x) sum += cube.texel(mip, f, x, y)[c] * texel_solid_angle(x, y, n);
    return sum;
}

class EnvironmentCubeTest : public GpuTest {};

// A smooth function of direction: each colour channel is one coordinate.
Equirect direction_colored(uint32_t w, uint32_t h) {
    Equirect e{w, h, std::vector<float>(size_t(w) * h * 4)};
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            auto d = equirect_direction((x + 0.5) / w, (y + 0.5) / h);
            float* t = &e.rgba[(size_t(y) * w + x) * 4];
            for (int c = 0; c < 3; ++c) t[c] = float(0.5 + 0.5 * d[c]);
            t[3] = 1;
        }
    return e;
}

TEST_F(EnvironmentCubeTest, SamplingTheCubeAtDReturnsTheEquirectAtD) {
    CubeLevels cube = run_ibl(ctx(), direction_colored(256, 128));
    ASSERT_EQ(cube.size, 64u);
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        Vec3 d{normal(rng), normal(rng), normal(rng)};
        const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (double& v : d) v /= len;
        uint32_t face;
        double s, t;
        select_cube_face(d, face, s, t);
        const uint32_t x = std::min(uint32_t(s * cube.size), cube.size - 1);
        const uint32_t y = std::min(uint32_t(t * cube.size), cube.size - 1);
        const float* texel = cube.texel(0, face, x, y);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(texel[c] - (0.5 + 0.5 * d[c])));
    }
    // One 64^2 texel spans up to ~1.8 degrees: the colour changes by < 0.02 across it.
    EXPECT_LT(worst, 0.02);
    // Every level, texel by texel (face edges included: a level that mixed faces or
    // flipped one would be off there): the mean of a linear function over a texel is close
    // to its value at the centre, within the function's change across the texel.
    for (uint32_t m = 1; m + 2 < cube.levels.size(); ++m) {
        const uint32_t n = cube.size >> m;
        double level_worst = 0;
        for (uint32_t f = 0; f < 6; ++f)
            for (uint32_t y = 0; y < n; ++y)
                for (uint32_t x = 0; x < n; ++x) {
                    const Vec3 d = cube_texel_direction(f, x, y, n);
                    for (int c = 0; c < 3; ++c)
                        level_worst = std::max(level_worst, std::abs(cube.texel(m, f, x, y)[c] - (0.5 + 0.5 * d[c])));
                }
        EXPECT_LT(level_worst, 0.6 * 3.14159265 / (2 * n)) << "mip " << m;  // half a texel's angle
    }
}

TEST_F(EnvironmentCubeTest, EveryLevelKeepsThePowerOfTheInput) {
    auto env = load_environment(std::string(FACET_SHARED_DATA_DIR) + "/env/venice_sunset_1k.hdr");
    ASSERT_TRUE(env) << env.error().message;
    Equirect e{env->width, env->height, env->rgba};
    CubeLevels cube = run_ibl(ctx(), e);
    ASSERT_EQ(cube.size, 256u);
    ASSERT_EQ(cube.levels.size(), 9u);
    for (int c = 0; c < 3; ++c) {
        const double input = equirect_power(e, c);
        const double level0 = cube_power(cube, 0, c);
        EXPECT_NEAR(level0 / input, 1.0, 2e-3) << "channel " << c;
        std::printf("venice channel %d: cube/equirect power %.6f, mip 8 / mip 0 %.8f\n", c, level0 / input,
                    cube_power(cube, 8, c) / level0);
        for (uint32_t m = 1; m < cube.levels.size(); ++m)
            EXPECT_NEAR(cube_power(cube, m, c) / level0, 1.0, 1e-5) << "mip " << m << " channel " << c;
    }
}

TEST_F(EnvironmentCubeTest, ASunKeepsItsPower) {
    // A sky of 1 with one texel of 5e4: the cube must not lose or multiply the sun, wherever
    // it falls (a face's middle, a face's edge or corner, near a pole, on the u seam).
    // 4 x 4 bilinear taps per cube texel integrate a one-texel sun to within 0.51% away from
    // the poles (5e-3 where it fell first: row 70, column 300); within about 3 degrees of a
    // pole the equirect's texels are much narrower than the taps' spacing and a sun may lose
    // 2.5% (row 3). Only specular level 0 and the background read the cube's level 0: every
    // other level and the irradiance read the input itself.
    struct Sun {
        uint32_t row, column;
        double tolerance;
    };
    const Sun suns[] = {{70, 300, 5e-3}, {128, 0, 1e-2},  {10, 77, 1e-2},  {200, 450, 1e-2},
                        {127, 128, 1e-2}, {64, 64, 1e-2}, {85, 191, 1e-2}, {3, 511, 3e-2}};
    for (const Sun& sun : suns) {
        Equirect e = uniform_sky(512, 256, 1.0f);
        for (uint32_t c = 0; c < 3; ++c) e.rgba[(size_t(sun.row) * 512 + sun.column) * 4 + c] = 5e4f;
        CubeLevels cube = run_ibl(ctx(), e);
        const double input = equirect_power(e, 0), output = cube_power(cube, 0, 0);
        EXPECT_NEAR(output / input, 1.0, sun.tolerance) << "sun at row " << sun.row << ", column " << sun.column;
        std::printf("one-texel sun of 5e4 at row %u, column %u: cube/equirect power %.6f\n", sun.row, sun.column,
                    output / input);
    }
}

TEST_F(EnvironmentCubeTest, TinyAndOddInputsGiveFiniteCubes) {
    for (auto [w, h] : {std::pair{1u, 1u}, {2u, 1u}, {6u, 2u}, {3u, 1u}}) {
        CubeLevels cube = run_ibl(ctx(), uniform_sky(w, h, 0.75f));
        EXPECT_EQ(cube.size, 1u);
        for (const auto& level : cube.levels)
            for (size_t i = 0; i < level.size(); ++i) {
                ASSERT_TRUE(std::isfinite(level[i]));
                if (i % 4 != 3) EXPECT_NEAR(level[i], 0.75f, 1e-5f) << w << "x" << h;  // RGB; alpha is 1
            }
    }
}

}  // namespace
}  // namespace facet
