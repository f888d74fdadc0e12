#version 460
// builtin:sky, a procedural sky with a small, very bright sun: the high-dynamic-range
// case where sampling-based bakes fail (the sun is ~4e4 times the sky). Written as an
// equirectangular RGBA32F image; each texel averages 4x4 directions across its area so
// the sun's disk covers texels by its true fraction (no aliasing of a one-texel sun).
#include "ibl/equirect.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform writeonly image2D out_sky;

#include "ibl/procedural_sky.glsl"

void main() {
    ivec2 size = imageSize(out_sky);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, size))) return;
    // The 4 x 4 directions are equirect_direction's, with each row's latitude and each
    // column's longitude evaluated once (8 sine-cosine pairs per texel, not 32).
    vec2 longitude_sin_cos[4];
    for (int i = 0; i < 4; ++i) {
        float u = (float(texel.x) + (float(i) + 0.5) / 4.0) / float(size.x);
        float phi = (u - 0.5) * 2.0 * facet_pi;
        longitude_sin_cos[i] = vec2(sin(phi), cos(phi));
    }
    vec3 sum = vec3(0.0);
    for (int j = 0; j < 4; ++j) {
        float v = (float(texel.y) + (float(j) + 0.5) / 4.0) / float(size.y);
        float theta = (0.5 - v) * facet_pi;
        float c = cos(theta), s = sin(theta);
        // Ground, fading into the horizon over a few degrees; the sky from horizon to zenith.
        vec3 below = sky_ground(s), above = sky_open(s);
        for (int i = 0; i < 4; ++i)
            sum += sky_radiance(vec3(c * longitude_sin_cos[i].y, s, c * longitude_sin_cos[i].x), below, above);
    }
    imageStore(out_sky, texel, vec4(sum / 16.0, 1.0));
}
