// The display transform on lavapipe against the operators written out here in double
// precision: none, Reinhard, exposure (the thesis' two), ACES (Narkowicz's fit) and
// Khronos PBR Neutral, then sRGB or a gamma power. Within one 8-bit level.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/graph/transfer_passes.h>
#include <facet/render/tonemap.h>
#include <facet/shader/program_cache.h>
#include "support/gpu_test.h"

namespace facet {
namespace {

struct Rgb {
    double r, g, b;
};

double srgb(double x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055; }

Rgb reference(Rgb c, Tonemap op) {
    auto each = [&](auto f) { return Rgb{f(c.r), f(c.g), f(c.b)}; };
    switch (op) {
    case Tonemap::reinhard: return each([](double x) { return x / (1 + x); });
    case Tonemap::exposure: return each([](double x) { return 1 - std::exp(-x); });
    case Tonemap::aces:
        // Narkowicz 2015: f(x) = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14) on 0.6 x.
        return each([](double x) {
            x *= 0.6;
            return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
        });
    case Tonemap::neutral: {
        // Khronos PBR Neutral (2024): black offset, then compression of the peak above
        // 0.76 towards 1 with desaturation 0.15.
        const double low = std::min({c.r, c.g, c.b});
        const double offset = low < 0.08 ? low - 6.25 * low * low : 0.04;
        Rgb x{c.r - offset, c.g - offset, c.b - offset};
        const double peak = std::max({x.r, x.g, x.b});
        const double start = 0.76, d = 0.24;
        if (peak < start) return x;
        const double new_peak = 1 - d * d / (peak + d - start);
        const double scale = new_peak / peak;
        const double g = 1 - 1 / (0.15 * (peak - new_peak) + 1);
        auto mix = [&](double v) { return v * scale * (1 - g) + new_peak * g; };
        return {mix(x.r), mix(x.g), mix(x.b)};
    }
    default: return c;
    }
}

class TonemapTest : public test::GpuTest {};

TEST_F(TonemapTest, EveryOperatorMatchesItsFormula) {
    ShaderCompiler compiler;
    ProgramCache programs(ctx(), compiler);
    Sampler nearest = test::must(Sampler::create(ctx(), VK_FILTER_NEAREST, false, false, "nearest"));
    // A ramp from 0 to 20 across x, different per channel and row, so that hue matters.
    const uint32_t w = 64, h = 4;
    std::vector<float> hdr(size_t(w) * h * 4);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float* p = &hdr[(size_t(y) * w + x) * 4];
            const float t = 20.0f * std::pow(float(x) / (w - 1), 3.0f);
            p[0] = t;
            p[1] = t * (0.25f + 0.25f * y);
            p[2] = t * 0.1f * y;
            p[3] = 1.0f;
        }
    Buffer staging =
        test::must(Buffer::create(ctx(), hdr.size() * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::upload, "ramp"));
    std::memcpy(staging.mapped(), hdr.data(), hdr.size() * 4);
    test::must(staging.flush());
    for (Tonemap op : {Tonemap::none, Tonemap::reinhard, Tonemap::exposure, Tonemap::aces, Tonemap::neutral})
        for (float gamma : {0.0f, 2.2f}) {
            const float exposure = 0.75f;
            RenderGraph g;
            ImageDesc desc;
            desc.width = w;
            desc.height = h;
            auto staged = g.import_buffer("ramp", {staging.handle(), staging.size(),
                                                   {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_HOST_BIT,
                                                    VK_ACCESS_2_HOST_WRITE_BIT}, {}});
            auto image = add_upload_pass(g, "upload", staged, g.create_image("hdr", desc));
            desc.format = VK_FORMAT_R8G8B8A8_UNORM;
            auto ldr = add_tonemap_pass(g, programs, nearest, image, g.create_image("ldr", desc), {exposure, op, gamma});
            ASSERT_TRUE(ldr) << ldr.error().message;
            g.export_image(*ldr, {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                  VK_ACCESS_2_TRANSFER_READ_BIT});
            CompiledGraph compiled = g.compile();
            auto run = test::must(run_graph(ctx(), compiled));
            auto bytes = test::must(read_image(ctx(), *run->transient_image(*ldr), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
            ASSERT_EQ(bytes.size(), size_t(w) * h * 4);
            int worst = 0;
            for (size_t i = 0; i < size_t(w) * h; ++i) {
                const float* p = &hdr[i * 4];
                const Rgb mapped = reference({p[0] * exposure, p[1] * exposure, p[2] * exposure}, op);
                const double channels[] = {mapped.r, mapped.g, mapped.b};
                for (int c = 0; c < 3; ++c) {
                    const double v = std::clamp(channels[c], 0.0, 1.0);
                    const double encoded = gamma > 0 ? std::pow(v, 1.0 / gamma) : srgb(v);
                    const int want = int(std::lround(encoded * 255.0));
                    const int got = int(std::to_integer<uint8_t>(bytes[i * 4 + size_t(c)]));
                    worst = std::max(worst, std::abs(got - want));
                }
            }
            EXPECT_LE(worst, 1) << tonemap_name(op) << " gamma " << gamma;
        }
}

TEST(TonemapNames, ParseAndPrintRoundTrip) {
    for (const char* name : {"none", "reinhard", "exposure", "aces", "neutral"}) {
        auto op = parse_tonemap(name);
        ASSERT_TRUE(op) << name;
        EXPECT_STREQ(tonemap_name(*op), name);
    }
    EXPECT_FALSE(parse_tonemap("filmic"));
}

}  // namespace
}  // namespace facet
