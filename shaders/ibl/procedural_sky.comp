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

vec3 sky_radiance(vec3 d) {
    vec3 sun = params.sun_direction_cos_radius.xyz;
    float cos_sun = dot(d, sun);
    if (cos_sun >= params.sun_direction_cos_radius.w) return params.sun_radiance_glow.rgb;
    if (d.y < 0.0) {
        // Ground, fading into the horizon over a few degrees.
        float t = clamp(-d.y / 0.05, 0.0, 1.0);
        return mix(params.horizon_radiance.rgb, params.ground_radiance.rgb, t);
    }
    vec3 sky = mix(params.horizon_radiance.rgb, params.zenith_radiance.rgb, sqrt(d.y));
    // Forward-scattering glow around the sun (a smooth lobe, not a second light).
    float glow = pow(max(cos_sun, 0.0), 64.0);
    return sky + glow * params.sun_radiance_glow.a * params.horizon_radiance.rgb;
}

void main() {
    ivec2 size = imageSize(out_sky);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, size))) return;
    vec3 sum = vec3(0.0);
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            vec2 uv = (vec2(texel) + (vec2(i, j) + 0.5) / 4.0) / vec2(size);
            sum += sky_radiance(equirect_direction(uv));
        }
    }
    imageStore(out_sky, texel, vec4(sum / 16.0, 1.0));
}
