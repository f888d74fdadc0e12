// builtin:sky and builtin:white from the GPU, checked against design.md's equirect
// mapping and the sky model evaluated here in double precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/gpu/transfer.h>
#include <facet/ibl/procedural_sky.h>
#include <facet/shader/program_cache.h>
#include "ibl/environment_cube.h"
#include "support/gpu_test.h"
#include <facet/reference/ibl_reference.h>

namespace facet {
namespace {

constexpr double pi = 3.14159265358979323846;

class ProceduralSkyTest : public test::GpuTest {
protected:
    std::vector<float> generate(const ProceduralSky& sky, uint32_t w, uint32_t h) {
        ShaderCompiler compiler;
        ProgramCache programs(ctx(), compiler);
        RenderGraph g;
        ImageDesc desc;
        desc.width = w;
        desc.height = h;
        auto img = g.create_image("sky", desc);
        auto out = add_procedural_sky_pass(g, programs, sky, img);
        EXPECT_TRUE(out) << (out ? "" : out.error().message);
        g.export_image(*out, {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                              VK_ACCESS_2_TRANSFER_READ_BIT});
        CompiledGraph c = g.compile();
        auto run = test::must(run_graph(ctx(), c));
        auto bytes = test::must(read_image(ctx(), *run->transient_image(img), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
        std::vector<float> texels(bytes.size() / 4);
        std::memcpy(texels.data(), bytes.data(), bytes.size());
        return texels;
    }
};

// The sky's model in double precision (shaders/ibl/procedural_sky.glsl), green channel.
double sky_green(const ProceduralSky& sky, double x, double y, double z) {
    const double n = std::sqrt(x * x + y * y + z * z);
    x /= n, y /= n, z /= n;
    const auto s = sky.sun_direction();
    const double cos_sun = x * s[0] + y * s[1] + z * s[2];
    if (cos_sun >= std::cos(sky.sun_angular_radius_deg * pi / 180)) return sky.sun_radiance[1];
    const double h = sky.horizon_radiance[1];
    if (y < 0) return h + (sky.ground_radiance[1] - h) * std::clamp(-y / 0.05, 0.0, 1.0);
    return h + (sky.zenith_radiance[1] - h) * std::sqrt(y) + std::pow(std::max(cos_sun, 0.0), 64) * sky.sun_glow * h;
}

// The environment cube's level 0 made from the sky itself (procedural_sky_cube.comp, what a
// bake of builtin:sky uses) against the model averaged over each texel (16 x 16 taps, 48 x 48
// within 6 degrees of the sun): within 0.05% relative RMS away from the sun and the sun's
// power within 1%, both closer than the cube made from the sky's 256x128 equirect by 16
// bilinear lookups a texel, the way a file's cube is made.
TEST_F(ProceduralSkyTest, CubeFromTheSkyMatchesTheModel) {
    const uint32_t n = 64, taps = 16;
    ProceduralSky sky;
    ShaderCompiler compiler;
    ProgramCache programs(ctx(), compiler);
    auto level0 = [&](bool from_equirect) {
        RenderGraph g;
        ImageDesc desc;
        desc.width = 4 * n;
        desc.height = 2 * n;
        auto sampler = test::must(Sampler::create(ctx(), VK_FILTER_LINEAR, false, true, "equirect sampler"));
        auto cube = g.create_image("cube", environment_cube_desc(n, 1));
        auto made = from_equirect
                        ? add_environment_cube_passes(
                              g, programs, sampler, test::must(add_procedural_sky_pass(g, programs, sky, g.create_image("sky", desc))),
                              cube)
                        : add_procedural_sky_cube_pass(g, programs, sky, cube);
        EXPECT_TRUE(made) << (made ? "" : made.error().message);
        g.export_image(*made, {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                               VK_ACCESS_2_TRANSFER_READ_BIT});
        CompiledGraph c = g.compile();
        auto run = test::must(run_graph(ctx(), c));
        std::vector<float> texels(size_t(6) * n * n * 4);
        for (uint32_t f = 0; f < 6; ++f) {
            auto bytes =
                test::must(read_image(ctx(), *run->transient_image(cube), 0, f, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
            std::memcpy(texels.data() + size_t(f) * n * n * 4, bytes.data(), bytes.size());
        }
        return texels;
    };
    const std::vector<float> direct = level0(false), via_equirect = level0(true);
    const auto sun = sky.sun_direction();
    auto area = [](double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1)); };
    double sun_truth = 0, sun_direct = 0, sun_equirect = 0, err_direct = 0, err_equirect = 0, sum = 0;
    size_t count = 0;
    for (uint32_t f = 0; f < 6; ++f)
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x) {
                const double x0 = 2.0 * x / n - 1, x1 = 2.0 * (x + 1) / n - 1, y0 = 2.0 * y / n - 1, y1 = 2.0 * (y + 1) / n - 1;
                const test::Vec3 c = test::cube_texel_direction(f, x, y, n);
                const double cos_sun = c[0] * sun[0] + c[1] * sun[1] + c[2] * sun[2];
                const bool near_sun = cos_sun > std::cos(6.0 * pi / 180);
                // Finer near the sun than the shader's 16 x 16 there, and on another grid.
                const uint32_t t = near_sun ? 3 * taps : taps;
                double truth = 0;
                for (uint32_t j = 0; j < t; ++j)
                    for (uint32_t i = 0; i < t; ++i) {
                        // Tap (i, j) of the texel: the centre of texel (x t + i, y t + j) of a t-times finer face.
                        const test::Vec3 d = test::cube_texel_direction(f, x * t + i, y * t + j, n * t);
                        truth += sky_green(sky, d[0], d[1], d[2]);
                    }
                truth /= double(t) * t;
                const double solid_angle = area(x0, y0) - area(x0, y1) - area(x1, y0) + area(x1, y1);
                const size_t k = ((size_t(f) * n + y) * n + x) * 4 + 1;
                if (near_sun) {  // the sun's neighbourhood: its power
                    sun_truth += truth * solid_angle;
                    sun_direct += direct[k] * solid_angle;
                    sun_equirect += via_equirect[k] * solid_angle;
                    continue;
                }
                err_direct += (direct[k] - truth) * (direct[k] - truth);
                err_equirect += (via_equirect[k] - truth) * (via_equirect[k] - truth);
                sum += truth;
                ++count;
            }
    const double mean = sum / double(count);
    const double rms_direct = std::sqrt(err_direct / double(count)) / mean;
    const double rms_equirect = std::sqrt(err_equirect / double(count)) / mean;
    std::printf("away from the sun, relative RMS: from the sky %.5f%%, from its equirect %.5f%%; the sun's power: "
                "%+.3f%% and %+.3f%%\n",
                100 * rms_direct, 100 * rms_equirect, 100 * (sun_direct / sun_truth - 1),
                100 * (sun_equirect / sun_truth - 1));
    EXPECT_LT(rms_direct, 5e-4);
    EXPECT_LT(rms_direct, rms_equirect);
    EXPECT_NEAR(sun_direct / sun_truth, 1.0, 0.01);
    EXPECT_LT(std::abs(sun_direct / sun_truth - 1), std::abs(sun_equirect / sun_truth - 1));
}

// design.md: u = atan2(d.z, d.x) / 2pi + 0.5, v = asin(d.y) / pi + 0.5, v = 1 is row 0.
void texel_of(const std::array<float, 3>& d, uint32_t w, uint32_t h, int& x, int& y) {
    const double u = std::atan2(d[2], d[0]) / (2 * pi) + 0.5;
    const double v = std::asin(d[1]) / pi + 0.5;
    x = int(u * w);
    y = int((1.0 - v) * h);
}

TEST_F(ProceduralSkyTest, SunSitsWhereTheEquirectMappingPutsIt) {
    const uint32_t w = 512, h = 256;
    ProceduralSky sky;
    auto t = generate(sky, w, h);
    ASSERT_EQ(t.size(), size_t(w) * h * 4);
    size_t brightest = 0;
    for (size_t i = 0; i < size_t(w) * h; ++i)
        if (t[i * 4] > t[brightest * 4]) brightest = i;
    int x, y;
    texel_of(sky.sun_direction(), w, h, x, y);
    EXPECT_NEAR(int(brightest % w), x, 1);
    EXPECT_NEAR(int(brightest / w), y, 1);
    EXPECT_GT(t[brightest * 4], 1e3f);
}

// Each texel averages its area, so summing radiance x texel solid angle over the sun's
// neighbourhood gives the disk's power: L_sun * 2 pi (1 - cos r), within a few percent.
TEST_F(ProceduralSkyTest, SunPowerMatchesItsDisk) {
    const uint32_t w = 1024, h = 512;
    ProceduralSky sky;
    sky.sun_glow = 0;  // only the disk above the sky
    auto t = generate(sky, w, h);
    const auto s = sky.sun_direction();
    double power = 0;
    for (uint32_t y = 0; y < h; ++y) {
        const double theta0 = pi * (0.5 - double(y) / h), theta1 = pi * (0.5 - double(y + 1) / h);
        const double texel_solid_angle = (2 * pi / w) * (std::sin(theta0) - std::sin(theta1));
        for (uint32_t x = 0; x < w; ++x) {
            const double u = (x + 0.5) / w, v = (y + 0.5) / h;
            const double phi = (u - 0.5) * 2 * pi, theta = (0.5 - v) * pi;
            const double d[3] = {std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
            if (d[0] * s[0] + d[1] * s[1] + d[2] * s[2] < std::cos(3.0 * pi / 180)) continue;
            // Subtract the sky under the disk so only the sun's excess is summed.
            const double sky_under = t[(size_t(y) * w + x) * 4];
            power += std::max(0.0, sky_under - 1.5) * texel_solid_angle;
        }
    }
    const double r = sky.sun_angular_radius_deg * pi / 180;
    const double expected = sky.sun_radiance[0] * 2 * pi * (1 - std::cos(r));
    EXPECT_NEAR(power / expected, 1.0, 0.03) << "power " << power << " expected " << expected;
}

TEST_F(ProceduralSkyTest, SkyAndGroundFollowTheModel) {
    const uint32_t w = 256, h = 128;
    ProceduralSky sky;
    auto t = generate(sky, w, h);
    // Far from the sun and the horizon the 4x4 supersampling barely matters: compare
    // with the model at the texel centre. Zenith row, opposite the sun:
    const uint32_t x = 0, y = 0;
    const double theta = pi * (0.5 - (y + 0.5) / h);
    const double dy = std::sin(theta);
    for (int c = 0; c < 3; ++c) {
        const double expected = sky.horizon_radiance[c] + (sky.zenith_radiance[c] - sky.horizon_radiance[c]) * std::sqrt(dy);
        EXPECT_NEAR(t[(y * w + x) * 4 + c], expected, 0.01) << "channel " << c;
    }
    // Deep ground.
    const uint32_t ground_row = h - 5;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[(ground_row * w + 10) * 4 + c], sky.ground_radiance[c], 1e-5);
    for (float v : t) {
        ASSERT_TRUE(std::isfinite(v));
        ASSERT_GE(v, 0.0f);
    }
}

TEST_F(ProceduralSkyTest, WhiteIsExactlyOneEverywhere) {
    auto t = generate(ProceduralSky::white(), 64, 32);
    for (size_t i = 0; i < t.size(); ++i) ASSERT_EQ(t[i], 1.0f) << "texel component " << i;
}

}  // namespace
}  // namespace facet
