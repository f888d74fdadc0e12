#version 460
// Diffuse irradiance E(n) / pi by direct convolution: a sum over every texel of a small
// level of the environment cube, each weighted by max(0, n . w) and its solid angle.
// `convolve`: the exact Lambert kernel, E/pi = 1/pi * integral L max(0, n . w) dw. Each
// entry (a block of level-0 texels, see cube_texels.comp) is taken as a spherical cap
// around its radiance-weighted direction, and the clamped cosine is integrated over that
// cap in closed form, also where n's horizon cuts it (Snyder 1996, as given in Lagarde
// and de Rousiers 2014, "Moving Frostbite to PBR", sphere lights). FACET_NARROW_CAPS
// (every cap of the list narrower than 0.2 rad: all but a tiny input's): a cap cut by the
// horizon as a flat disk instead, within 6e-4 of the exact form at that width and far
// cheaper on lavapipe, which runs both sides of a branch (a bake's convolution 70 -> 40 ms).
// `blur` (the thesis' cheap alternative): a normalised spherical Gaussian of width sigma
// instead of the cosine; right for a uniform sky, a blur of it otherwise.
#include "facet/shared_constants.h"
#include "ibl/cube.glsl"

// Each invocation makes TEXELS texels side by side in x (FACET_IRRADIANCE_TEXELS: 8 on a
// CPU device, 1 elsewhere; add_irradiance_passes dispatches accordingly), so that each
// entry read from the list (lane by lane on lavapipe) serves all of them.
#ifndef FACET_IRRADIANCE_TEXELS
#define FACET_IRRADIANCE_TEXELS 1
#endif
const uint TEXELS = FACET_IRRADIANCE_TEXELS;

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include "ibl/cube_faces_dispatch.glsl"  // after the local size: it reads gl_WorkGroupSize
#include "ibl/list_lanes.glsl"
layout(std430, binding = 0) readonly buffer Texels { vec4 texels[]; };
layout(binding = 1, rgba32f) uniform writeonly image2DArray irradiance;

layout(push_constant) uniform Params {
    uint texel_count;
    uint gaussian;     // 0: cosine (convolve), 1: Gaussian (blur)
    float sigma;       // Gaussian width in radians (blur)
} params;

// Integral of max(0, n . w) over a cap of angular radius sigma whose axis makes angle
// theta with n, divided by pi sin^2(sigma) (so that it is cos(theta) when fully visible).
float clipped_cap_cosine(float cos_theta, float sin2_sigma) {
    if (cos_theta * cos_theta > sin2_sigma) return max(cos_theta, 0.0);
    float sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    float x = sqrt(max(1.0 / sin2_sigma - 1.0, 0.0));
    float y = clamp(-x * cos_theta / max(sin_theta, 1e-7), -1.0, 1.0);
    float sin_theta_sqrt_y = sin_theta * sqrt(1.0 - y * y);
    float e = (cos_theta * acos(y) - x * sin_theta_sqrt_y) * sin2_sigma + atan(sin_theta_sqrt_y, x);
    return max(e, 0.0) / (facet_pi * sin2_sigma);
}

// The same for a narrow cap (sin2_sigma small) taken as a flat disk of radius
// s = sin(sigma) across the horizon: with t = cos(theta) / s, the integral of
// max(0, t + y) over the unit disk divided by pi, times s, is s (t / 2 + G(t)) for
// |t| < 1, G(t) = (t asin(t) + sqrt(1 - t^2)(2 + t^2) / 3) / pi, here a polynomial in t^2
// fitted to it (within 3.2e-5 on [-1, 1]; scripts/fit_flat_cap.py): asin and sqrt per
// entry and normal cost as much as the exact form's branch.
float flat_cap_cosine(float cos_theta, float s, float inverse_s) {
    float t = clamp(cos_theta * inverse_s, -1.0, 1.0);
    float u = t * t;
    float g = 0.21223815 + u * (0.31747305 + u * (-0.02315098 + u * -0.00652821));
    return abs(t) < 1.0 ? s * (0.5 * t + g) : max(cos_theta, 0.0);
}

void main() {
    uint n = uint(imageSize(irradiance).x);
    uvec3 id = cube_texel_group(n, TEXELS);
    uint x0 = id.x;
    bool inside = x0 < n && id.y < n;  // the others read the list with their subgroup, then stop
    vec3 normal[TEXELS], sum[TEXELS];
    float weight_sum[TEXELS];
    for (uint k = 0u; k < TEXELS; ++k) {
        normal[k] = normalize(cube_direction(id.z, (vec2(x0 + k, id.y) + 0.5) / float(n)));
        sum[k] = vec3(0.0);
        weight_sum[k] = 0.0;
    }
    float inv_sigma2 = 1.0 / max(params.sigma * params.sigma, 1e-6);
    uint count = params.texel_count;
    for (uint base = 0u; base < count; base += LIST_STEP) {
        uint lane = list_index(base, count);
        vec4 lane_direction = texels[2u * lane], lane_radiance = texels[2u * lane + 1u];
        for (uint j = 0u; j < list_chunk(base, count); ++j) {
            vec4 direction_spread = list_entry(lane_direction, j);
            vec4 radiance_solid_angle_and_solid_angle = list_entry(lane_radiance, j);
            vec3 radiance_solid_angle = radiance_solid_angle_and_solid_angle.rgb;
            float sin2_sigma = max(direction_spread.w, 1e-12);
#ifdef FACET_NARROW_CAPS
            float s = sqrt(sin2_sigma);
            float inverse_s = 1.0 / s;
#endif
            for (uint k = 0u; k < TEXELS; ++k) {
                float c = dot(normal[k], direction_spread.xyz);
#ifdef FACET_NARROW_CAPS
                float w = flat_cap_cosine(c, s, inverse_s);
#else
                float w = params.gaussian == 0u ? clipped_cap_cosine(c, sin2_sigma) : exp((c - 1.0) * inv_sigma2);
#endif
                sum[k] += w * radiance_solid_angle;
                weight_sum[k] += w * radiance_solid_angle_and_solid_angle.w;
            }
        }
    }
    if (!inside) return;
    // Normalised by the discrete kernel's own integral over the sphere (which tends to pi
    // for the clamped cosine), so a uniform sky is exact at any resolution.
    for (uint k = 0u; k < TEXELS; ++k)
        if (x0 + k < n)
            imageStore(irradiance, ivec3(x0 + k, id.y, id.z), vec4(sum[k] / max(weight_sum[k], 1e-30), 1.0));
}
