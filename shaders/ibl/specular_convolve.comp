#version 460
// Prefiltered specular radiance for one roughness (split sum, n = v = R; Karis 2013):
// P(R) = integral L(l) w(l) dl / integral w(l) dl with w(l) = D(h) (n.l) / 4 for n.l > 0,
// h = normalize(n + l), which is the limit of the thesis' importance-sampled estimate.
// Here it is a deterministic sum over the entries of a texel list (cube_texels.comp):
// no noise, no fireflies from a sun, exact for a uniform sky. Used for rough levels,
// where a small source level resolves the lobe.
#include "facet/brdf.glsl"
#include "ibl/cube.glsl"

// Each invocation makes TEXELS texels side by side in x (FACET_CONVOLVE_TEXELS: 8 on a
// CPU device, 1 elsewhere; add_specular_passes dispatches accordingly), so that each
// entry read from the list (lane by lane on lavapipe) serves all of them.
#ifndef FACET_CONVOLVE_TEXELS
#define FACET_CONVOLVE_TEXELS 1
#endif
const uint TEXELS = FACET_CONVOLVE_TEXELS;

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include "ibl/cube_faces_dispatch.glsl"  // after the local size: it reads gl_WorkGroupSize
#include "ibl/list_lanes.glsl"
layout(std430, binding = 0) readonly buffer Texels { vec4 texels[]; };
layout(binding = 1, rgba32f) uniform writeonly image2DArray level;

layout(push_constant) uniform Params {
    uint texel_count;
    float roughness;
} params;

void main() {
    uint n = uint(imageSize(level).x);
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
    uint count = params.texel_count;
    for (uint base = 0u; base < count; base += LIST_STEP) {
        uint lane = list_index(base, count);
        vec4 lane_direction = texels[2u * lane], lane_radiance = texels[2u * lane + 1u];
        for (uint j = 0u; j < list_chunk(base, count); ++j) {
            vec3 l = list_entry(lane_direction, j).xyz;
            vec4 radiance_solid_angle = list_entry(lane_radiance, j);
            for (uint k = 0u; k < TEXELS; ++k) {
                float NdotL = dot(normal[k], l);
                vec3 h = normalize(normal[k] + l);
                // Below the horizon the weight is 0 (a select, not a branch: lavapipe runs both).
                float w = NdotL > 0.0 ? D_GGX(dot(normal[k], h), params.roughness) * NdotL : 0.0;
                sum[k] += w * radiance_solid_angle.rgb;
                weight_sum[k] += w * radiance_solid_angle.w;
            }
        }
    }
    if (!inside) return;
    for (uint k = 0u; k < TEXELS; ++k)
        if (x0 + k < n)
            imageStore(level, ivec3(x0 + k, id.y, id.z), vec4(sum[k] / max(weight_sum[k], 1e-30), 1.0));
}
