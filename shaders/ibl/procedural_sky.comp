#version 460
// builtin:sky, a procedural sky with a small, very bright sun: the high-dynamic-range
// case where sampling-based bakes fail (the sun is ~4e4 times the sky). Written as an
// equirectangular RGBA32F image; each texel averages 4x4 directions across its area so
// the sun's disk covers texels by its true fraction (no aliasing of a one-texel sun).
#include "ibl/equirect.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform writeonly image2D out_sky;

layout(push_constant) uniform Params {
    vec4 sun_direction_cos_radius;  // xyz: unit direction to the sun; w: cos(angular radius)
    vec4 sun_radiance_glow;         // rgb: radiance inside the disk; a: halo strength
    vec4 zenith_radiance;           // rgb
    vec4 horizon_radiance;          // rgb
    vec4 ground_radiance;           // rgb
} params;

// Radiance in direction d; `below` and `above` are its row's ground and sky (they depend on
// d.y alone, so main() makes them once per row of taps). Branch-free: lavapipe runs both
// sides of a branch for a mixed SIMD row, so every lane computes each case and selects.
vec3 sky_radiance(vec3 d, vec3 below, vec3 above) {
    vec3 sun = params.sun_direction_cos_radius.xyz;
    float cos_sun = dot(d, sun);
    // Forward-scattering glow around the sun (a smooth lobe, not a second light).
    float glow = max(cos_sun, 0.0);  // its 64th power, by six squarings
    glow *= glow;
    glow *= glow;
    glow *= glow;
    glow *= glow;
    glow *= glow;
    glow *= glow;
    vec3 open_sky = d.y < 0.0 ? below : above + glow * params.sun_radiance_glow.a * params.horizon_radiance.rgb;
    return cos_sun >= params.sun_direction_cos_radius.w ? params.sun_radiance_glow.rgb : open_sky;
}

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
        vec3 below = mix(params.horizon_radiance.rgb, params.ground_radiance.rgb, clamp(-s / 0.05, 0.0, 1.0));
        vec3 above = mix(params.horizon_radiance.rgb, params.zenith_radiance.rgb, sqrt(max(s, 0.0)));
        for (int i = 0; i < 4; ++i)
            sum += sky_radiance(vec3(c * longitude_sin_cos[i].y, s, c * longitude_sin_cos[i].x), below, above);
    }
    imageStore(out_sky, texel, vec4(sum / 16.0, 1.0));
}
