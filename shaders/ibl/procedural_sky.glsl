#ifndef FACET_PROCEDURAL_SKY_GLSL
#define FACET_PROCEDURAL_SKY_GLSL
// builtin:sky's radiance, shared by procedural_sky.comp (the equirect) and
// procedural_sky_cube.comp (the environment cube's level 0 straight from the sky):
// the push-constant block (engine/ibl/procedural_sky.cpp's SkyParams) and the model.

layout(push_constant) uniform Params {
    vec4 sun_direction_cos_radius;  // xyz: unit direction to the sun; w: cos(angular radius)
    vec4 sun_radiance_glow;         // rgb: radiance inside the disk; a: halo strength
    vec4 zenith_radiance;           // rgb; w: procedural_sky_cube.comp's reach around the sun (a cosine)
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

// The ground (below) and the sky (above) at sine of latitude s, for sky_radiance.
vec3 sky_ground(float s) {
    return mix(params.horizon_radiance.rgb, params.ground_radiance.rgb, clamp(-s / 0.05, 0.0, 1.0));
}
vec3 sky_open(float s) {
    return mix(params.horizon_radiance.rgb, params.zenith_radiance.rgb, sqrt(max(s, 0.0)));
}

#endif
