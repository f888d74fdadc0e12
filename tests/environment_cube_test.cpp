// Equirect -> cube and its mip chain, against the Vulkan spec's face selection (written
// here in the forward direction) and the power of the input integrated in double.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "graph/compiled_graph.h"
#include "graph/graph_run.h"
#include "graph/transfer_passes.h"
#include "gpu/transfer.h"
#include "ibl/environment_cube.h"
#include "io/environment_image.h"
#include "shader/program_cache.h"
#include "support/gpu_test.h"

namespace facet {
namespace {

constexpr double pi = 3.14159265358979323846;

struct Equirect {
    uint32_t w, h;
    std::vector<float> rgba;
};

struct Cube {
    uint32_t size, mips;
    std::vector<std::vector<float>> levels;  // [mip][face][y][x][4]
    const float* texel(uint32_t mip, uint32_t face, uint32_t x, uint32_t y) const {
        const uint32_t n = std::max(1u, size >> mip);
        return &levels[mip][((size_t(face) * n + y) * n + x) * 4];
    }
};

std::array<double, 3> equirect_direction(double u, double v_image) {
    const double phi = (u - 0.5) * 2 * pi, theta = (0.5 - v_image) * pi;
    return {std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
}

// Vulkan spec, "Cube Map Face Selection and Transformations": face and (s, t) of d.
void select_face(const std::array<double, 3>& d, uint32_t& face, double& s, double& t) {
    const double ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
    double sc, tc, ma;
    if (ax >= ay && ax >= az) {
        face = d[0] >= 0 ? 0 : 1;
        sc = d[0] >= 0 ? -d[2] : d[2];
        tc = -d[1];
        ma = ax;
    } else if (ay >= az) {
        face = d[1] >= 0 ? 2 : 3;
        sc = d[0];
        tc = d[1] >= 0 ? d[2] : -d[2];
        ma = ay;
    } else {
        face = d[2] >= 0 ? 4 : 5;
        sc = d[2] >= 0 ? d[0] : -d[0];
        tc = -d[1];
        ma = az;
    }
    s = 0.5 * (sc / ma + 1);
    t = 0.5 * (tc / ma + 1);
}

double face_area(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1)); }
double texel_solid_angle(uint32_t x, uint32_t y, uint32_t n) {
    const double x0 = 2.0 * x / n - 1, x1 = 2.0 * (x + 1) / n - 1, y0 = 2.0 * y / n - 1, y1 = 2.0 * (y + 1) / n - 1;
    return face_area(x0, y0) - face_area(x0, y1) - face_area(x1, y0) + face_area(x1, y1);
}

double equirect_power(const Equirect& e, int c) {
    double sum = 0;
    for (uint32_t y = 0; y < e.h; ++y) {
        const double t0 = pi * (0.5 - double(y) / e.h), t1 = pi * (0.5 - double(y + 1) / e.h);
        const double dw = (2 * pi / e.w) * (std::sin(t0) - std::sin(t1));
        for (uint32_t x = 0; x < e.w; ++x) sum += e.rgba[(size_t(y) * e.w + x) * 4 + c] * dw;
    }
    return sum;
}

double cube_power(const Cube& cube, uint32_t mip, int c) {
    const uint32_t n = std::max(1u, cube.size >> mip);
    double sum = 0;
    for (uint32_t f = 0; f < 6; ++f)
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x) sum += cube.texel(mip, f, x, y)[c] * texel_solid_angle(x, y, n);
    return sum;
}

class EnvironmentCubeTest : public test::GpuTest {
protected:
    Cube bake(const Equirect& e) {
        ShaderCompiler compiler;
        ProgramCache programs(ctx(), compiler);
        Sampler sampler(ctx(), VK_FILTER_LINEAR, false, true, "equirect");
        Buffer staging(ctx(), e.rgba.size() * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::upload, "staging");
        std::memcpy(staging.mapped(), e.rgba.data(), e.rgba.size() * 4);
        staging.flush();
        RenderGraph g;
        ImageDesc ed;
        ed.width = e.w;
        ed.height = e.h;
        auto equirect = g.create_image("equirect", ed);
        auto texels = g.import_buffer("texels", {staging.handle(), staging.size(),
                                                 {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_HOST_BIT,
                                                  VK_ACCESS_2_HOST_WRITE_BIT}, {}});
        equirect = add_upload_pass(g, "upload", texels, equirect);
        Cube cube;
        cube.size = cube_size_for(e.h);
        cube.mips = full_mip_count(cube.size);
        auto cube_image = g.create_image("cube", environment_cube_desc(cube.size, cube.mips));
        auto out = add_environment_cube_passes(g, programs, sampler, equirect, cube_image);
        EXPECT_TRUE(out);
        g.export_image(*out, {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                              VK_ACCESS_2_TRANSFER_READ_BIT});
        CompiledGraph c = g.compile();
        auto run = run_graph(ctx(), c);
        for (uint32_t m = 0; m < cube.mips; ++m) {
            std::vector<float> level;
            for (uint32_t f = 0; f < 6; ++f) {
                auto bytes = read_image(ctx(), *run->transient_image(cube_image), m, f,
                                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
                const size_t old = level.size();
                level.resize(old + bytes.size() / 4);
                std::memcpy(level.data() + old, bytes.data(), bytes.size());
            }
            cube.levels.push_back(std::move(level));
        }
        return cube;
    }
};

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
    Cube cube = bake(direction_colored(256, 128));
    ASSERT_EQ(cube.size, 64u);
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        std::array<double, 3> d{normal(rng), normal(rng), normal(rng)};
        const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (double& v : d) v /= len;
        uint32_t face;
        double s, t;
        select_face(d, face, s, t);
        const uint32_t x = std::min(uint32_t(s * cube.size), cube.size - 1);
        const uint32_t y = std::min(uint32_t(t * cube.size), cube.size - 1);
        const float* texel = cube.texel(0, face, x, y);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(texel[c] - (0.5 + 0.5 * d[c])));
    }
    // One 64^2 texel spans up to ~1.8 degrees: the colour changes by < 0.02 across it.
    EXPECT_LT(worst, 0.02);
}

TEST_F(EnvironmentCubeTest, EveryLevelKeepsThePowerOfTheInput) {
    auto env = load_environment(std::string(FACET_SHARED_DATA_DIR) + "/env/venice_sunset_1k.hdr");
    ASSERT_TRUE(env) << env.error().message;
    Equirect e{env->width, env->height, env->rgba};
    Cube cube = bake(e);
    ASSERT_EQ(cube.size, 256u);
    ASSERT_EQ(cube.mips, 9u);
    for (int c = 0; c < 3; ++c) {
        const double input = equirect_power(e, c);
        const double level0 = cube_power(cube, 0, c);
        EXPECT_NEAR(level0 / input, 1.0, 2e-3) << "channel " << c;
        std::printf("venice channel %d: cube/equirect power %.6f, mip 8 / mip 0 %.8f\n", c, level0 / input,
                    cube_power(cube, cube.mips - 1, c) / level0);
        for (uint32_t m = 1; m < cube.mips; ++m)
            EXPECT_NEAR(cube_power(cube, m, c) / level0, 1.0, 1e-5) << "mip " << m << " channel " << c;
    }
}

TEST_F(EnvironmentCubeTest, ASunKeepsItsPower) {
    // A sky of 1 with one texel of 5e4: the cube must not lose or multiply the sun.
    Equirect e{512, 256, std::vector<float>(512 * 256 * 4, 1.0f)};
    for (uint32_t c = 0; c < 3; ++c) e.rgba[(size_t(70) * 512 + 300) * 4 + c] = 5e4f;
    Cube cube = bake(e);
    const double input = equirect_power(e, 0), output = cube_power(cube, 0, 0);
    EXPECT_NEAR(output / input, 1.0, 5e-3);
    std::printf("one-texel sun of 5e4: cube/equirect power %.6f\n", output / input);
}

TEST_F(EnvironmentCubeTest, TinyAndOddInputsGiveFiniteCubes) {
    for (auto [w, h] : {std::pair{1u, 1u}, {2u, 1u}, {6u, 2u}, {3u, 1u}}) {
        Equirect e{w, h, std::vector<float>(size_t(w) * h * 4, 0.75f)};
        Cube cube = bake(e);
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
