// include/facet/core/shared_constants.h is read by C++ and by GLSL: the values a shader
// sees (through the embedded "facet/shared_constants.h") equal the C++ ones rounded to
// float, and the C++ values are the defining ones (pi to double precision, Rec. 709's
// luminance weights, which sum to 1).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <facet/core/shared_constants.h>
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

}  // namespace
}  // namespace facet
