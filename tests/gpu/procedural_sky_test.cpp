// builtin:sky and builtin:white from the GPU, checked against design.md's equirect
// mapping and the sky model evaluated here in double precision.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/gpu/transfer.h>
#include <facet/ibl/procedural_sky.h>
#include <facet/shader/program_cache.h>
#include "support/gpu_test.h"

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
