#pragma once
// The light as the renderers upload it: the C++ side of shaders/render/packed_light.glsl's
// PackedLight (std430, four vec4), filled here once for the forward pass, the skybox and
// the reference pass. The asserts below fix the layout on this side;
// tests/cpu/gpu_layout_test.cpp compares it with the layout glslang gives each shader.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include <glm/glm.hpp>

#include <facet/ibl/light_extraction.h>
#include "render/glsl_literal.h"
#include <facet/scene/scene.h>

namespace facet {

struct LightData {
    glm::vec4 position_range;   // xyz position (metres), w range (0 = infinite); disk: 1 / (2 - 2 cos), 1 / (2 sin)
    glm::vec4 direction_type;   // xyz the direction the light travels, w the type (LightType, or 3: a disk)
    glm::vec4 color_intensity;  // rgb colour, a intensity (lux or candela; 1 for a disk's radiance)
    glm::vec4 cone;             // spot: the cone's scale and offset; disk: cos, radius, sin, solid angle
};
static_assert(sizeof(LightData) == 64, "PackedLight in shaders/render/packed_light.glsl: 4 x vec4");
static_assert(offsetof(LightData, position_range) == 0 && offsetof(LightData, direction_type) == 16 &&
              offsetof(LightData, color_intensity) == 32 && offsetof(LightData, cone) == 48,
              "PackedLight in shaders/render/packed_light.glsl");

// The value direction_type.w holds for a disk (after LightType's 0, 1, 2).
constexpr float kDiskLightType = 3.0f;

// A punctual light (KHR_lights_punctual). The spot cone is stored as the scale and offset
// of the cosine, so the shader's smooth falloff is one multiply-add:
// clamp(cos * scale + offset, 0, 1) is 0 at the outer cone and 1 at the inner one.
inline LightData light_data(const Light& l) {
    LightData d{};
    d.position_range = glm::vec4(l.position, l.range);
    d.direction_type = glm::vec4(glm::normalize(l.direction), float(int(l.type)));
    d.color_intensity = glm::vec4(l.color, l.intensity);
    const float cos_outer = std::cos(l.outer_cone), cos_inner = std::cos(l.inner_cone);
    const float scale = 1.0f / std::max(cos_inner - cos_outer, 1e-4f);
    d.cone = glm::vec4(scale, -cos_outer * scale, 0.0f, 0.0f);
    return d;
}

// A disk extracted from the environment: its light travels away from d.direction (unit
// here, so that the shaders need not normalise it). The cap's cosine, radius, sine, solid
// angle 2 pi (1 - cos) and the reciprocals the shading divides by are computed once here
// rather than per pixel.
inline LightData disk_data(const DiskLight& d) {
    LightData data{};
    data.direction_type = glm::vec4(-glm::normalize(d.direction), kDiskLightType);
    data.color_intensity = glm::vec4(d.radiance, 1.0f);
    const double theta = d.angular_radius;
    // 2 - 2 cos theta = 4 sin^2(theta / 2), without the cancellation of small caps (as
    // facet_make_disk_light in shaders/facet/shading.glsl).
    const double half = std::sin(0.5 * theta);
    data.cone = glm::vec4(float(std::cos(theta)), float(theta), float(std::sin(theta)),
                          float(4.0 * 3.14159265358979323846 * half * half));
    data.position_range = glm::vec4(float(1.0 / std::max(4.0 * half * half, 1e-12)),
                                    float(1.0 / std::max(2.0 * std::sin(theta), 1e-8)), 0.0f, 0.0f);
    return data;
}

// The light as a GLSL PackedLight constructor with every float written to round-trip
// (%.9g): the forward pass compiles its disks into the shader as constants.
inline std::string packed_light_literal(const LightData& d) {
    std::string out = "PackedLight(";
    const glm::vec4* parts[] = {&d.position_range, &d.direction_type, &d.color_intensity, &d.cone};
    for (int p = 0; p < 4; ++p) {
        out += p ? ", vec4(" : "vec4(";
        for (int c = 0; c < 4; ++c) out += (c ? ", " : "") + glsl_float_literal(double((*parts[p])[c]));
        out += ")";
    }
    return out + ")";
}

}  // namespace facet
