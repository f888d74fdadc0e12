// include/facet/core/shared_constants.h is read by C++ and by GLSL: the values a shader
// sees (through the embedded "facet/shared_constants.h") equal the C++ ones rounded to
// float, and the C++ values are the defining ones (pi to double precision, Rec. 709's
// luminance weights, which sum to 1). The equirect mapping, written once on each side,
// agrees between them.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <facet/core/shared_constants.h>
#include "io/equirect.h"
#include "support/compute_probe.h"
#include "support/gpu_test.h"

namespace facet {
namespace {

static_assert(pi == std::numbers::pi);
static_assert(luminance(1.0, 1.0, 1.0) > 1.0 - 1e-15 && luminance(1.0, 1.0, 1.0) < 1.0 + 1e-15);

constexpr const char* probe = R"(#version 460
#include "facet/shared_constants.h"
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Out { float values[]; };
void main() {
    values[0] = facet_pi;
    values[1] = facet_luminance_r;
    values[2] = facet_luminance_g;
    values[3] = facet_luminance_b;
    values[4] = facet_luminance(vec3(0.25, 0.5, 2.0));
}
)";

class SharedConstantsTest : public test::GpuTest {};

TEST_F(SharedConstantsTest, GlslSeesTheCppValues) {
    auto values = test::run_compute_probe(ctx(), "shared_constants_probe.comp", probe, 5);
    ASSERT_EQ(values.size(), 5u);
    EXPECT_EQ(values[0], float(pi));
    EXPECT_EQ(values[1], float(luminance_r));
    EXPECT_EQ(values[2], float(luminance_g));
    EXPECT_EQ(values[3], float(luminance_b));
    EXPECT_EQ(values[1], 0.2126f);
    EXPECT_EQ(values[2], 0.7152f);
    EXPECT_EQ(values[3], 0.0722f);
    EXPECT_NEAR(values[4], luminance(0.25, 0.5, 2.0), 1e-6);
}

// The forward pass's pi is the shared one (facet/brdf.glsl's PI is an alias of it).
TEST_F(SharedConstantsTest, BrdfIncludeUsesTheSharedPi) {
    const char* source = R"(#version 460
#include "facet/brdf.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Out { float values[]; };
void main() { values[0] = PI; values[1] = D_GGX(1.0, 1.0); }
)";
    auto values = test::run_compute_probe(ctx(), "brdf_pi_probe.comp", source, 2);
    ASSERT_EQ(values.size(), 2u);
    EXPECT_EQ(values[0], float(pi));
    EXPECT_NEAR(values[1], 1.0 / pi, 1e-7);  // D at roughness 1 is uniform: 1 / pi
}

// The equirect mapping exists once in GLSL (shaders/ibl/equirect.glsl) and once in C++
// (engine/io/equirect.h): both give the same directions, image coordinates and texel
// solid angles, to float precision.
TEST_F(SharedConstantsTest, EquirectMappingIsTheSameInGlslAndCpp) {
    const char* source = R"(#version 460
#include "ibl/equirect.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Out { float values[]; };
const vec2 uvs[4] = vec2[](vec2(0.5, 0.5), vec2(0.75, 0.25), vec2(0.1, 0.9), vec2(0.33, 0.02));
const uint rows[4] = uint[](0u, 5u, 16u, 31u);
void main() {
    for (int i = 0; i < 4; ++i) {
        vec3 d = equirect_direction(uvs[i]);
        vec2 uv = equirect_uv(d);
        values[5 * i + 0] = d.x;
        values[5 * i + 1] = d.y;
        values[5 * i + 2] = d.z;
        values[5 * i + 3] = uv.x;
        values[5 * i + 4] = uv.y;
        values[20 + i] = equirect_texel_solid_angle(rows[i], uvec2(64u, 32u));
    }
}
)";
    auto values = test::run_compute_probe(ctx(), "equirect_probe.comp", source, 24);
    ASSERT_EQ(values.size(), 24u);
    const double uvs[4][2] = {{0.5, 0.5}, {0.75, 0.25}, {0.1, 0.9}, {0.33, 0.02}};
    const uint32_t rows[4] = {0, 5, 16, 31};
    for (int i = 0; i < 4; ++i) {
        const glm::dvec3 d = equirect_direction(uvs[i][0], uvs[i][1]);
        const glm::dvec2 uv = equirect_uv(d);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(values[5 * i + c], d[c], 2e-6) << "direction " << i;
        // asin and atan on the device are only as exact as Vulkan asks (lavapipe's asin is off
        // by about 1e-4); a convention that differs (a flipped axis, a half-texel shift of a
        // 1024-wide map) is off by far more.
        EXPECT_NEAR(values[5 * i + 3], uv.x, 3e-4) << "u " << i;
        EXPECT_NEAR(values[5 * i + 4], uv.y, 3e-4) << "v " << i;
        const double omega = equirect_texel_solid_angle(rows[i], 64, 32);
        EXPECT_NEAR(values[20 + i], omega, 1e-5 * omega) << "solid angle of row " << rows[i];
    }
}

}  // namespace
}  // namespace facet
