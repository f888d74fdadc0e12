#version 460
// SH9 projection, step 3: E(n) / pi = sum_i A_l w_l L_i Y_i(n) / pi into the cube.
#include "ibl/sh9.glsl"
#include "ibl/cube.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(std430, binding = 0) readonly buffer Coefficients { vec4 coefficients[]; };
layout(binding = 1, rgba32f) uniform writeonly image2DArray irradiance;

void main() {
    uint n = uint(imageSize(irradiance).x);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    vec3 normal = normalize(cube_direction(id.z, (vec2(id.xy) + 0.5) / float(n)));
    float y[9];
    sh9_basis(normal, y);
    float h = coefficients[9].x;
    vec3 e = vec3(0.0);
    for (int k = 0; k < 9; ++k) {
        int l = sh9_band(k);
        e += SH9_BAND_FACTOR[l] * sh9_window(l, h) * coefficients[k].rgb * y[k];
    }
    // Windowed, the minimum is >= 0 on the reduce pass's test directions; between them a
    // trace below 0 may remain, and unwindowed the ringing is the user's choice: either
    // way radiance is never stored negative.
    imageStore(irradiance, ivec3(id), vec4(max(e / facet_pi, vec3(0.0)), 1.0));
}
