// No baked value is stored as Inf because it exceeds RGBA16F (65504): an environment with
// a 2e5 sun keeps its outputs finite (the ones that need it in RGBA32F, said in the
// metadata and bake.json) and the sun's power, against the CPU truth (facet::reference).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <facet/gpu/transfer.h>
#include <facet/ibl/baked_environment.h>
#include <facet/io/ktx2.h>
#include <facet/reference/ibl_reference.h>
#include <facet/shader/program_cache.h>
#include "support/gpu_test.h"
#include "support/output_files.h"

namespace facet {
namespace {

// Every level of an output as floats, whatever its storage format.
std::vector<std::vector<float>> texels(Context& context, const Image& image) {
    std::vector<std::vector<float>> out;
    const ImageDesc& d = image.desc();
    const bool half = d.format == VK_FORMAT_R16G16B16A16_SFLOAT;
    for (uint32_t m = 0; m < d.mip_levels; ++m) {
        std::vector<float> level;
        for (uint32_t layer = 0; layer < d.array_layers; ++layer) {
            auto bytes = test::must(read_image(context, image, m, layer, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
            const size_t n = bytes.size() / (half ? 2 : 4);
            for (size_t i = 0; i < n; ++i) {
                if (half) {
                    uint16_t h;
                    std::memcpy(&h, bytes.data() + i * 2, 2);
                    level.push_back(half_to_float(h));
                } else {
                    float f;
                    std::memcpy(&f, bytes.data() + i * 4, 4);
                    level.push_back(f);
                }
            }
        }
        out.push_back(std::move(level));
    }
    return out;
}

// Solid angle of texel (x, y) of an n x n cube face, from the area element of the face
// plane at distance 1: the integral of (1 + u^2 + v^2)^-3/2 is atan(uv / sqrt(1 + u^2 + v^2)).
double cube_texel_solid_angle(uint32_t x, uint32_t y, uint32_t n) {
    auto f = [](double u, double v) { return std::atan2(u * v, std::sqrt(u * u + v * v + 1)); };
    const double u0 = 2.0 * x / n - 1, u1 = 2.0 * (x + 1) / n - 1, v0 = 2.0 * y / n - 1, v1 = 2.0 * (y + 1) / n - 1;
    return f(u1, v1) - f(u0, v1) - f(u1, v0) + f(u0, v0);
}

// Red channel's integral over the sphere: sum of L dw.
double cube_power(const std::vector<float>& level, uint32_t n) {
    double sum = 0;
    for (uint32_t face = 0; face < 6; ++face)
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x)
                sum += level[((size_t(face) * n + y) * n + x) * 4] * cube_texel_solid_angle(x, y, n);
    return sum;
}

double equirect_power(const test::Equirect& e) {
    double sum = 0;
    for (uint32_t y = 0; y < e.h; ++y)
        for (uint32_t x = 0; x < e.w; ++x) sum += e.at(x, y)[0] * test::equirect_texel_solid_angle(y, e.w, e.h);
    return sum;
}

class BakeOverflow : public test::GpuTest {};

TEST_F(BakeOverflow, ASunBeyondHalfFloatStaysFiniteAndKeepsItsPower) {
    // A 2e5 sun, 4 degrees across: about 97% of the environment's power.
    const test::Equirect sky = test::sun_sky(256, 128, 2e5, 4.0, 35.0, 60.0);
    float peak = 0;
    for (float v : sky.rgba) peak = std::max(peak, v);
    ASSERT_GT(peak, 65504.0f) << "the test's sun must exceed RGBA16F";
    EnvironmentSource source;
    source.name = "sun 2e5";
    source.image.rgba = sky.rgba;
    source.image.width = source.width = source.image.source_width = source.source_width = sky.w;
    source.image.height = source.height = source.image.source_height = source.source_height = sky.h;
    source.content_hash = "sun2e5";
    BakeSettings settings;  // RGBA16F asked for
    settings.ibl.irradiance.size = 16;
    settings.ibl.specular.sample_count = 256;
    settings.ibl.lut.size = 16;
    settings.ibl.lut.sample_count = 64;
    ShaderCompiler compiler;
    ProgramCache programs(ctx(), compiler);
    auto baked = bake_environment(ctx(), programs, source, settings);
    ASSERT_TRUE(baked) << baked.error().message;
    const BakeMetadata& meta = baked->metadata();
    EXPECT_EQ(meta.specular_format, VK_FORMAT_R32G32B32A32_SFLOAT);
    EXPECT_EQ(meta.cube_format, VK_FORMAT_R32G32B32A32_SFLOAT);
    EXPECT_EQ(meta.irradiance_format, VK_FORMAT_R16G16B16A16_SFLOAT) << "irradiance fits: stays RGBA16F";
    EXPECT_EQ(meta.lut_format, VK_FORMAT_R16G16B16A16_SFLOAT);
    ASSERT_EQ(meta.format_notes.size(), 2u);
    EXPECT_NE(meta.format_notes[0].find("65504"), std::string::npos) << meta.format_notes[0];

    // Every stored texel of every output is finite.
    for (const Image* image : {&baked->environment(), &baked->cube(), baked->specular(), baked->irradiance(), baked->lut()}) {
        ASSERT_NE(image, nullptr);
        size_t bad = 0;
        for (const auto& level : texels(ctx(), *image))
            for (float v : level) bad += !std::isfinite(v);
        EXPECT_EQ(bad, 0u) << "format " << image->desc().format;
    }
    // The sun's power: specular level 0 (roughness 0, the environment) against the input.
    const auto specular = texels(ctx(), *baked->specular());
    const double want = equirect_power(sky), got = cube_power(specular[0], baked->specular()->desc().width);
    std::printf("power: input %.2f, specular level 0 %.2f (peak input %.4g)\n", want, got, double(peak));
    EXPECT_NEAR(got, want, 0.02 * want) << "specular level 0 holds the environment's power within 2%";
    // Irradiance towards the sun and away from it, against the brute-force truth
    // (the convolve method's documented bound is 2%; 3% here).
    const auto irradiance = texels(ctx(), *baked->irradiance());
    const uint32_t n = baked->irradiance()->desc().width;
    for (auto [face, x, y] : {std::array<uint32_t, 3>{2, 8, 8}, {3, 8, 8}, {0, 4, 5}}) {
        const test::Vec3 dir = test::cube_texel_direction(face, x, y, n);
        const test::Vec3 truth = test::irradiance_over_pi(sky, dir);
        const float got_r = irradiance[0][((size_t(face) * n + y) * n + x) * 4];
        std::printf("irradiance face %u: %.4f, truth %.4f\n", face, double(got_r), truth[0]);
        EXPECT_NEAR(got_r, truth[0], 0.03 * truth[0] + 1e-3) << "face " << face;
    }

    // The files: specular.ktx2 in RGBA32F, every value finite; bake.json says why.
    test::TempDir dir("bake_overflow");
    ASSERT_TRUE(baked->save(dir.path.string()));
    auto ktx = read_ktx2((dir / "specular.ktx2").string());
    ASSERT_TRUE(ktx) << ktx.error().message;
    EXPECT_EQ(ktx->format, VK_FORMAT_R32G32B32A32_SFLOAT);
    for (const auto& level : ktx->level_data)
        for (size_t i = 0; i < level.size() / 4; ++i) {
            float v;
            std::memcpy(&v, level.data() + i * 4, 4);
            ASSERT_TRUE(std::isfinite(v));
        }
    std::ifstream json(dir / "bake.json");
    std::stringstream text;
    text << json.rdbuf();
    EXPECT_NE(text.str().find("specular kept in R32G32B32A32_SFLOAT"), std::string::npos) << text.str();
}

TEST_F(BakeOverflow, Rgba32fOnRequestAndRgba16fWhereItFits) {
    const test::Equirect sky = test::sun_sky(64, 32, 100.0, 8.0, 30.0, 0.0);
    EnvironmentSource source;
    source.name = "sun 100";
    source.image.rgba = sky.rgba;
    source.image.width = source.width = source.image.source_width = source.source_width = sky.w;
    source.image.height = source.height = source.image.source_height = source.source_height = sky.h;
    source.content_hash = "sun100";
    BakeSettings settings;
    settings.ibl.irradiance.size = 8;
    settings.ibl.lut.size = 8;
    settings.ibl.lut.sample_count = 16;
    settings.ibl.specular.sample_count = 64;
    ShaderCompiler compiler;
    ProgramCache programs(ctx(), compiler);
    auto half = bake_environment(ctx(), programs, source, settings);
    ASSERT_TRUE(half) << half.error().message;
    EXPECT_EQ(half->specular()->desc().format, VK_FORMAT_R16G16B16A16_SFLOAT);
    EXPECT_TRUE(half->metadata().format_notes.empty());
    settings.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    auto full = bake_environment(ctx(), programs, source, settings);
    ASSERT_TRUE(full) << full.error().message;
    for (const Image* image : {&full->cube(), full->specular(), full->irradiance(), full->lut()})
        EXPECT_EQ(image->desc().format, VK_FORMAT_R32G32B32A32_SFLOAT);
    EXPECT_NE(half->metadata().bake_key, full->metadata().bake_key) << "the format is part of the key";
    settings.format = VK_FORMAT_R8G8B8A8_UNORM;
    auto bad = bake_environment(ctx(), programs, source, settings);
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find("format"), std::string::npos);
}

}  // namespace
}  // namespace facet
