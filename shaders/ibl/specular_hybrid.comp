#version 460
// Prefiltered specular radiance for one roughness (split sum, n = v = R), the hybrid way:
// P(R) = integral L w dl / W with w(l) = D(h) (n.l), W = integral w dl, and L split into
// a residual of low dynamic range (the environment clamped at T; its mips) and the excess
// above T (specular_excess.comp). The residual's part by filtered importance sampling
// (Krivanek and Colbert 2008) with a few samples, the excess's exactly, entry by entry:
// E_j w(l_j) / W. A sun then costs one entry instead of a thousand samples.
// Each invocation makes TEXELS texels side by side in x (FACET_HYBRID_TEXELS; 8 on a CPU
// device, 1 elsewhere; add_specular_passes dispatches accordingly): every sample and entry
// read from the buffers serves all of them (lavapipe reads a buffer lane by lane: level 1
// in about half the time); a GPU keeps one texel per invocation, and its parallelism.
#include "ibl/cube.glsl"
#include "facet/brdf.glsl"

// `part` (a push constant, so that one pipeline does all three): 0, the whole level; 1, the
// residual's part alone, into a cube of half the level's face size (the lobe spans several
// of its texels); 2, the excess's part plus the residual's read bilinearly (seamless) from
// part 1's cube, `half_residual`. Every binding is given whatever the part.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include "ibl/cube_faces_dispatch.glsl"  // after the local size: it reads gl_WorkGroupSize
#include "ibl/list_lanes.glsl"
layout(binding = 0) uniform samplerCube residual;
layout(std430, binding = 1) readonly buffer List {
    uint count;
    uint pad0, pad1, pad2;
    vec4 entries[];
} list;
layout(binding = 2, rgba32f) uniform writeonly image2DArray level;
// The filtered samples, the same for every texel (n = v): l in the tangent frame of n
// (z along n, so n.l = z) and the mip that matches its solid angle; made on the host.
layout(std430, binding = 3) readonly buffer Samples { vec4 samples[]; };
// The same excess in blocks twice as wide, read when `list` has more than most_entries.
layout(std430, binding = 4) readonly buffer Coarse {
    uint count;
    uint pad0, pad1, pad2;
    vec4 entries[];
} coarse;
layout(binding = 5) uniform samplerCube half_residual;

#ifndef FACET_HYBRID_TEXELS
#define FACET_HYBRID_TEXELS 1
#endif
const uint TEXELS = FACET_HYBRID_TEXELS;

layout(push_constant) uniform Params {
    uint sample_count;
    float roughness;
    float inverse_sample_weight;  // 1 / sum of the samples' n.l
    float inverse_weight;         // 1 / W
    uint most_entries;
    uint part;
} params;

void main() {
    uint n = uint(imageSize(level).x);
    uvec3 id = cube_texel_group(n, TEXELS);
    uint x0 = id.x;
    bool inside = x0 < n && id.y < n;  // the others read the lists with their subgroup, then stop
    vec3 N[TEXELS], tangent_x[TEXELS], tangent_y[TEXELS], sum[TEXELS], excess[TEXELS];
    for (uint k = 0u; k < TEXELS; ++k) {
        N[k] = normalize(cube_direction(id.z, (vec2(x0 + k, id.y) + 0.5) / float(n)));
        vec3 up = abs(N[k].z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
        tangent_x[k] = normalize(cross(up, N[k]));
        tangent_y[k] = cross(N[k], tangent_x[k]);
        sum[k] = vec3(0.0);
        excess[k] = vec3(0.0);
    }
    if (params.part == 2u) {
        for (uint k = 0u; k < TEXELS; ++k) sum[k] = textureLod(half_residual, N[k], 0.0).rgb;
    } else {
        for (uint base = 0u; base < params.sample_count; base += LIST_STEP) {
            vec4 lane_sample = samples[list_index(base, params.sample_count)];
            for (uint j = 0u; j < list_chunk(base, params.sample_count); ++j) {
                vec4 t = list_entry(lane_sample, j);
                for (uint k = 0u; k < TEXELS; ++k) {
                    vec3 L = t.x * tangent_x[k] + t.y * tangent_y[k] + t.z * N[k];
                    sum[k] += textureLod(residual, L, t.w).rgb * t.z;
                }
            }
        }
        for (uint k = 0u; k < TEXELS; ++k) sum[k] *= params.inverse_sample_weight;
    }
    if (params.part == 1u) {
        for (uint k = 0u; k < TEXELS; ++k)
            if (inside && x0 + k < n) imageStore(level, ivec3(x0 + k, id.y, id.z), vec4(sum[k], 1.0));
        return;
    }
    // D(h) (n.l) with (n.h)^2 = (1 + n.l) / 2 for h = normalize(n + l): no normalisation
    // per entry; the constant alpha^2 / pi is applied once, with 1 / W.
    float alpha = max(params.roughness * params.roughness, MIN_ALPHA);
    float a2_minus_1 = alpha * alpha - 1.0;
    if (list.count <= params.most_entries) {
        uint count = list.count;
        for (uint base = 0u; base < count; base += LIST_STEP) {
            uint lane = list_index(base, count);
            vec4 lane_direction = list.entries[2u * lane], lane_excess = list.entries[2u * lane + 1u];
            for (uint j = 0u; j < list_chunk(base, count); ++j) {
                vec3 l = list_entry(lane_direction, j).xyz, e = list_entry(lane_excess, j).rgb;
                for (uint k = 0u; k < TEXELS; ++k) {
                    float NdotL = max(dot(N[k], l), 0.0);
                    float d = (0.5 + 0.5 * NdotL) * a2_minus_1 + 1.0;
                    excess[k] += e * (NdotL / (d * d));
                }
            }
        }
    } else {
        uint count = coarse.count;
        for (uint base = 0u; base < count; base += LIST_STEP) {
            uint lane = list_index(base, count);
            vec4 lane_direction = coarse.entries[2u * lane], lane_excess = coarse.entries[2u * lane + 1u];
            for (uint j = 0u; j < list_chunk(base, count); ++j) {
                vec3 l = list_entry(lane_direction, j).xyz, e = list_entry(lane_excess, j).rgb;
                for (uint k = 0u; k < TEXELS; ++k) {
                    float NdotL = max(dot(N[k], l), 0.0);
                    float d = (0.5 + 0.5 * NdotL) * a2_minus_1 + 1.0;
                    excess[k] += e * (NdotL / (d * d));
                }
            }
        }
    }
    float excess_scale = alpha * alpha / PI * params.inverse_weight;
    if (!inside) return;
    for (uint k = 0u; k < TEXELS; ++k)
        if (x0 + k < n)
            imageStore(level, ivec3(x0 + k, id.y, id.z), vec4(sum[k] + excess[k] * excess_scale, 1.0));
}
