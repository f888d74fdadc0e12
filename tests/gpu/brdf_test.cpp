// The shared BRDF include (shaders/facet/brdf.glsl), evaluated on the GPU and checked against
// formulas written here independently in double precision, plus the GGX normalisation
// integral (the projected NDF integrates to 1) computed from the GPU's own values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <facet/gpu/pipeline.h>
#include <facet/gpu/resources.h>
#include <facet/gpu/transfer.h>
#include <facet/shader/compiler.h>
#include <facet/reference/final_image_truth.h>
#include "support/compute_probe.h"
#include "support/gpu_test.h"

namespace facet {
namespace {

struct BrdfInput {
    float NdotV, NdotL, NdotH, VdotH;
    float roughness, f0, pad0, pad1;
};
struct BrdfOutput {
    float D, F, F_rough, G_direct;
    float G_ibl, V_correlated, k_direct, k_ibl;
};
// std430 arrays of 8 floats in shaders/test/brdf_eval.comp: no padding on either side.
static_assert(sizeof(BrdfInput) == 32 && offsetof(BrdfInput, roughness) == 16);
static_assert(sizeof(BrdfOutput) == 32 && offsetof(BrdfOutput, G_ibl) == 16);

constexpr double pi = 3.14159265358979323846;

// Reference formulas (Walter et al. 2007; Schlick 1994; Karis 2013; Heitz 2014).
double ggx(double n_h, double r) {
    const double a = r * r, a2 = a * a;
    const double t = n_h * n_h * (a2 - 1.0) + 1.0;
    return a2 / (pi * t * t);
}
double schlick(double cos_theta, double f0) { return f0 + (1.0 - f0) * std::pow(1.0 - cos_theta, 5.0); }
double schlick_roughness(double cos_theta, double f0, double r) {
    return f0 + (std::max(1.0 - r, f0) - f0) * std::pow(1.0 - cos_theta, 5.0);
}
double g1(double n_x, double k) { return n_x / (n_x * (1.0 - k) + k); }
double smith_correlated_v(double n_v, double n_l, double a) {
    const double a2 = a * a;
    return 0.5 / (n_l * std::sqrt(n_v * n_v * (1.0 - a2) + a2) + n_v * std::sqrt(n_l * n_l * (1.0 - a2) + a2));
}

std::vector<BrdfOutput> evaluate(Context& context, const std::vector<BrdfInput>& inputs) {
    ShaderCompiler compiler;
    auto spirv = compiler.compile(ShaderStage::compute, "test/brdf_eval.comp");
    if (!spirv) {
        ADD_FAILURE() << spirv.error().message;
        return {};
    }
    auto built = Pipeline::compute(context, spirv->words, "brdf eval");
    if (!built) {
        ADD_FAILURE() << built.error().message;
        return {};
    }
    Pipeline pipeline = std::move(built).value();
    Buffer in = test::must(Buffer::create(context, inputs.size() * sizeof(BrdfInput), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                          MemoryUsage::upload, "brdf inputs"));
    Buffer out = test::must(Buffer::create(context, inputs.size() * sizeof(BrdfOutput),
                                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::readback, "brdf outputs"));
    std::memcpy(in.mapped(), inputs.data(), inputs.size() * sizeof(BrdfInput));
    test::must(in.flush());
    test::must(context.submit_and_wait([&](VkCommandBuffer cmd) {
        pipeline.bind(cmd);
        const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(in.handle()),
                                          DescriptorWrite::storage_buffer(out.handle())};
        pipeline.push_descriptors(cmd, writes);
        vkCmdDispatch(cmd, group_count(static_cast<uint32_t>(inputs.size()), pipeline.workgroup_size()[0]), 1, 1);
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    }));
    test::must(out.invalidate());
    std::vector<BrdfOutput> result(inputs.size());
    std::memcpy(result.data(), out.mapped(), result.size() * sizeof(BrdfOutput));
    return result;
}

void expect_close(double gpu, double ref, double rel, const std::string& what) {
    EXPECT_NEAR(gpu, ref, rel * std::max(1.0, std::abs(ref))) << what;
}

class BrdfTest : public test::GpuTest {};

TEST_F(BrdfTest, TermsMatchIndependentFormulas) {
    std::vector<BrdfInput> inputs;
    for (float r : {0.05f, 0.2f, 0.5f, 0.8f, 1.0f})
        for (float c : {0.05f, 0.3f, 0.7f, 1.0f})
            inputs.push_back({c, 1.1f - c, 0.2f + 0.8f * c, 0.5f * c + 0.25f, r, 0.04f + 0.9f * (1.0f - c), 0, 0});
    auto out = evaluate(ctx(), inputs);
    ASSERT_EQ(out.size(), inputs.size());
    for (size_t i = 0; i < inputs.size(); ++i) {
        const BrdfInput& x = inputs[i];
        const std::string at = "case " + std::to_string(i) + " roughness " + std::to_string(x.roughness);
        const double r = x.roughness;
        expect_close(out[i].D, ggx(x.NdotH, r), 2e-5, "D_GGX " + at);
        expect_close(out[i].F, schlick(x.VdotH, x.f0), 2e-6, "F_Schlick " + at);
        expect_close(out[i].F_rough, schlick_roughness(x.NdotV, x.f0, r), 2e-6, "F_SchlickRoughness " + at);
        const double kd = (r + 1) * (r + 1) / 8, ki = r * r / 2;
        expect_close(out[i].k_direct, kd, 1e-6, "k_direct " + at);
        expect_close(out[i].k_ibl, ki, 1e-6, "k_ibl " + at);
        expect_close(out[i].G_direct, g1(x.NdotV, kd) * g1(x.NdotL, kd), 2e-6, "G_Smith direct " + at);
        expect_close(out[i].G_ibl, g1(x.NdotV, ki) * g1(x.NdotL, ki), 2e-6, "G_Smith IBL " + at);
        expect_close(out[i].V_correlated, smith_correlated_v(x.NdotV, x.NdotL, r * r), 2e-5,
                     "V_SmithGGXCorrelated " + at);
    }
}

// The GGX NDF is normalised: the integral of D(h) (n.h) over the hemisphere is 1,
// i.e. 2 pi * integral_0^1 D(mu) mu dmu. Integrated from the shader's own values.
TEST_F(BrdfTest, GgxProjectedAreaIntegratesToOne) {
    const int n = 8192;
    for (float r : {0.3f, 0.6f, 1.0f}) {
        std::vector<BrdfInput> inputs;
        for (int i = 0; i < n; ++i) {
            const float mu = (i + 0.5f) / n;  // midpoint rule in mu = cos(theta_h)
            inputs.push_back({0.5f, 0.5f, mu, 0.5f, r, 0.04f, 0, 0});
        }
        auto out = evaluate(ctx(), inputs);
        ASSERT_EQ(out.size(), inputs.size());
        double integral = 0;
        for (int i = 0; i < n; ++i) integral += double(out[i].D) * inputs[i].NdotH / n;
        integral *= 2 * pi;
        EXPECT_NEAR(integral, 1.0, 1e-3) << "roughness " << r;
    }
}

// Where the formulas divide by zero (roughness 0 and 1e-4, n.v = 0 and 1e-6): finite,
// non-negative values.
TEST_F(BrdfTest, FiniteAtRoughnessZeroAndGrazingAngles) {
    std::vector<BrdfInput> inputs = {
        {1.0f, 1.0f, 1.0f, 1.0f, 0.0f, 0.04f, 0, 0}, {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.04f, 0, 0},
        {0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f, 0, 0},  {1e-6f, 1e-6f, 1.0f, 1e-6f, 0.0f, 0.5f, 0, 0},
        {1e-6f, 0.5f, 1.0f, 0.5f, 1e-4f, 0.04f, 0, 0}, {0.0f, 0.0f, 0.999f, 0.0f, 1e-4f, 1.0f, 0, 0},
    };
    auto out = evaluate(ctx(), inputs);
    ASSERT_EQ(out.size(), inputs.size());
    for (size_t i = 0; i < out.size(); ++i) {
        const float values[] = {out[i].D, out[i].F, out[i].F_rough, out[i].G_direct, out[i].G_ibl, out[i].V_correlated};
        for (float v : values) {
            EXPECT_TRUE(std::isfinite(v)) << "case " << i;
            EXPECT_GE(v, 0.0f) << "case " << i;
        }
    }
    EXPECT_EQ(out[1].G_ibl, 0.0f) << "no light at a grazing view";
}

// KHR_materials_iridescence's F_iridescence in shading.glsl (float) against the truth's
// double-precision thin_film_fresnel, written separately from the extension's equations:
// dielectric and metallic bases (a base whose index is below the film's in some channels
// and not others shifts those channels' phase), air and a clear coat outside, thin, thick
// and vanishing films, and total internal reflection (film less dense than the coat).
TEST_F(BrdfTest, IridescenceFresnelIsTheTruths) {
    struct Case {
        float outside, film, cos1, thickness;
        float base[3];
    };
    const Case cases[] = {{1.0f, 1.3f, 1.0f, 400.0f, {0.04f, 0.04f, 0.04f}},
                          {1.0f, 1.8f, 0.6f, 380.0f, {0.04f, 0.04f, 0.04f}},
                          {1.0f, 1.8f, 0.2f, 900.0f, {0.95f, 0.64f, 0.54f}},  // copper-like: mixed phases
                          {1.0f, 2.2f, 0.8f, 150.0f, {0.91f, 0.92f, 0.92f}},
                          {1.5f, 1.3f, 0.9f, 250.0f, {0.04f, 0.1f, 0.3f}},
                          {1.0f, 1.8f, 0.5f, 12.0f, {0.04f, 0.04f, 0.04f}},     // fading into the outside
                          {1.5f, 1.2f, 0.1f, 400.0f, {0.04f, 0.04f, 0.04f}}};  // total internal reflection
    std::string source = R"(#version 460
#include "facet/shading.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Out { float values[]; };
void main() {
)";
    for (size_t i = 0; i < std::size(cases); ++i) {
        const Case& c = cases[i];
        char line[256];
        std::snprintf(line, sizeof line,
                      "    { vec3 f = facet_iridescence_fresnel(%.9g, %.9g, %.9g, %.9g, vec3(%.9g, %.9g, %.9g));\n"
                      "      values[%zu] = f.r; values[%zu] = f.g; values[%zu] = f.b; }\n",
                      c.outside, c.film, c.cos1, c.thickness, c.base[0], c.base[1], c.base[2], 3 * i, 3 * i + 1, 3 * i + 2);
        source += line;
    }
    source += "}\n";
    const std::vector<float> values = test::run_compute_probe(ctx(), "iridescence_probe.comp", source, 3 * std::size(cases));
    ASSERT_EQ(values.size(), 3 * std::size(cases));
    for (size_t i = 0; i < std::size(cases); ++i) {
        const Case& c = cases[i];
        const test::Vec3 want = test::thin_film_fresnel(c.outside, c.film, c.cos1, c.thickness,
                                                        {c.base[0], c.base[1], c.base[2]});
        for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(values[3 * i + k], want[k], 2e-4) << "case " << i << " channel " << k;
    }
    // The total internal reflection case reflects everything.
    for (size_t k = 0; k < 3; ++k) EXPECT_EQ(values[3 * (std::size(cases) - 1) + k], 1.0f);
}

}  // namespace
}  // namespace facet
