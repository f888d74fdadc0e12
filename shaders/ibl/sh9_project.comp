#version 460
// SH9 projection, step 1: each workgroup sums L(w) Y_i(w) dw over its 64 entries of the
// texel list (cube_texels.comp) and writes 9 partial sums.
#include "ibl/sh9.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Texels { vec4 texels[]; };
layout(std430, binding = 1) writeonly buffer Partials { vec4 partials[]; };  // 9 per group

layout(push_constant) uniform Params {
    uint texel_count;
} params;

shared vec3 sums[64][9];

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint local = gl_LocalInvocationID.x;
    float y[9];
    vec3 radiance_solid_angle = vec3(0.0);
    vec3 d = vec3(0.0, 0.0, 1.0);
    if (i < params.texel_count) {
        d = texels[2u * i].xyz;
        radiance_solid_angle = texels[2u * i + 1u].rgb;
    }
    sh9_basis(d, y);
    for (int k = 0; k < 9; ++k) sums[local][k] = radiance_solid_angle * y[k];
    barrier();
    // Tree reduction over the group (fixed order: identical results run to run).
    for (uint stride = 32u; stride > 0u; stride >>= 1u) {
        if (local < stride)
            for (int k = 0; k < 9; ++k) sums[local][k] += sums[local + stride][k];
        barrier();
    }
    if (local == 0u)
        for (int k = 0; k < 9; ++k) partials[gl_WorkGroupID.x * 9u + uint(k)] = vec4(sums[0][k], 0.0);
}
