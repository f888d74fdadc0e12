#version 460
// Prefiltered specular radiance for one roughness (split sum, n = v = R), the hybrid way:
// P(R) = integral L w dl / W with w(l) = D(h) (n.l), W = integral w dl, and L split into
// a residual of low dynamic range (the environment clamped at T; its mips) and the excess
// above T (specular_excess.comp). The residual's part by filtered importance sampling
// (Krivanek and Colbert 2008) with a few samples, the excess's exactly, entry by entry:
// E_j w(l_j) / W. A sun then costs one entry instead of a thousand samples.
#include "ibl/cube.glsl"
#include "facet/brdf.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
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

layout(push_constant) uniform Params {
    uint sample_count;
    float roughness;
    float inverse_sample_weight;  // 1 / sum of the samples' n.l
    float inverse_weight;         // 1 / W
    uint most_entries;
} params;

void main() {
    uint n = uint(imageSize(level).x);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    vec3 N = normalize(cube_direction(id.z, (vec2(id.xy) + 0.5) / float(n)));
    vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangent_x = normalize(cross(up, N));
    vec3 tangent_y = cross(N, tangent_x);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < params.sample_count; ++i) {
        vec4 t = samples[i];
        vec3 L = t.x * tangent_x + t.y * tangent_y + t.z * N;
        sum += textureLod(residual, L, t.w).rgb * t.z;
    }
    vec3 result = sum * params.inverse_sample_weight;
    // D(h) (n.l) with (n.h)^2 = (1 + n.l) / 2 for h = normalize(n + l): no normalisation
    // per entry; the constant alpha^2 / pi is applied once, with 1 / W.
    float alpha = max(params.roughness * params.roughness, MIN_ALPHA);
    float a2_minus_1 = alpha * alpha - 1.0;
    vec3 excess = vec3(0.0);
    if (list.count <= params.most_entries) {
        for (uint j = 0u; j < list.count; ++j) {
            float NdotL = max(dot(N, list.entries[2u * j].xyz), 0.0);
            float d = (0.5 + 0.5 * NdotL) * a2_minus_1 + 1.0;
            excess += list.entries[2u * j + 1u].rgb * (NdotL / (d * d));
        }
    } else {
        for (uint j = 0u; j < coarse.count; ++j) {
            float NdotL = max(dot(N, coarse.entries[2u * j].xyz), 0.0);
            float d = (0.5 + 0.5 * NdotL) * a2_minus_1 + 1.0;
            excess += coarse.entries[2u * j + 1u].rgb * (NdotL / (d * d));
        }
    }
    excess *= alpha * alpha / PI;
    imageStore(level, ivec3(id), vec4(result + excess * params.inverse_weight, 1.0));
}
