#version 460
// SH9 projection, step 2: one invocation adds the partial sums (in a fixed order), then
// chooses the window. Unwindowed, 9 coefficients of a sunny sky ring: the irradiance
// they give goes negative opposite the sun. With windowing on, band l is scaled by the
// Hanning-type factor (1 + cos(pi l / (2 h))) / 2 (Sloan 2008, "Stupid Spherical Harmonics
// Tricks"), with the smallest h in [1, 64] (by bisection) for which the irradiance is
// non-negative at a set of test directions; h = 64 barely changes a smooth sky.
#include "ibl/sh9.glsl"
#include "ibl/cube.glsl"

layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer Partials { vec4 partials[]; };
layout(std430, binding = 1) writeonly buffer Coefficients { vec4 coefficients[]; };  // 9 + 1 (window)

layout(push_constant) uniform Params {
    uint group_count;
    uint windowing;
} params;

float min_irradiance(vec3 L[9], float h) {
    float lowest = 1e30;
    for (uint face = 0u; face < 6u; ++face)
        for (uint j = 0u; j < 16u; ++j)
            for (uint i = 0u; i < 16u; ++i) {
                vec3 n = normalize(cube_direction(face, (vec2(i, j) + 0.5) / 16.0));
                float y[9];
                sh9_basis(n, y);
                vec3 e = vec3(0.0);
                for (int k = 0; k < 9; ++k) {
                    int l = sh9_band(k);
                    e += SH9_BAND_FACTOR[l] * sh9_window(l, h) * L[k] * y[k];
                }
                lowest = min(lowest, min(e.r, min(e.g, e.b)));
            }
    return lowest;
}

void main() {
    vec3 L[9];
    for (int k = 0; k < 9; ++k) L[k] = vec3(0.0);
    for (uint g = 0u; g < params.group_count; ++g)
        for (int k = 0; k < 9; ++k) L[k] += partials[g * 9u + uint(k)].rgb;
    float h = 0.0;  // 0: no window
    if (params.windowing != 0u && min_irradiance(L, 0.0) < 0.0) {
        float lo = 1.0, hi = 64.0;  // h = 1 flattens band 2 entirely: never negative
        if (min_irradiance(L, hi) >= 0.0) {
            h = hi;
        } else {
            for (int step = 0; step < 20; ++step) {
                float mid = 0.5 * (lo + hi);
                if (min_irradiance(L, mid) >= 0.0) lo = mid; else hi = mid;
            }
            h = lo;
        }
    }
    for (int k = 0; k < 9; ++k) coefficients[k] = vec4(L[k], 0.0);
    coefficients[9] = vec4(h, 0.0, 0.0, 0.0);
}
