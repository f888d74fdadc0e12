#version 460
// Prefiltered specular radiance for one roughness by the thesis' GGX importance sampling
// (N Hammersley samples of h ~ D(h) (n.h), n = v = R, weights n.l). With FILTERED, each
// sample reads the environment's mip whose texels match the sample's solid angle
// (filtered importance sampling, Krivanek and Colbert 2008, GPU Gems 3 ch. 20):
// lod = 0.5 log2(Omega_s / Omega_p) + 1, Omega_s = 1 / (N pdf), Omega_p = texel solid angle.
#include "ibl/cube.glsl"
#include "ibl/sampling.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include "ibl/cube_faces_dispatch.glsl"  // after the local size: it reads gl_WorkGroupSize
layout(binding = 0) uniform samplerCube environment;
layout(binding = 1, rgba32f) uniform writeonly image2DArray level;

layout(push_constant) uniform Params {
    uint sample_count;
    float roughness;
    uint filtered;
    float source_size;  // face size of the environment's level 0
} params;

void main() {
    uint n = uint(imageSize(level).x);
    uvec3 id = cube_texel_group(n, 1u);
    if (id.x >= n || id.y >= n) return;
    vec3 N = normalize(cube_direction(id.z, (vec2(id.xy) + 0.5) / float(n)));
    vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangent_x = normalize(cross(up, N));
    vec3 tangent_y = cross(N, tangent_x);
    float texel_solid_angle = 4.0 * PI / (6.0 * params.source_size * params.source_size);
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    for (uint i = 0u; i < params.sample_count; ++i) {
        vec3 ht = importance_sample_ggx_tangent(hammersley(i, params.sample_count), params.roughness);
        vec3 H = ht.x * tangent_x + ht.y * tangent_y + ht.z * N;
        vec3 L = 2.0 * dot(N, H) * H - N;
        float NdotL = dot(N, L);
        if (NdotL <= 0.0) continue;
        float lod = 0.0;
        if (params.filtered != 0u) {
            // v = n, so v.h = n.h (and the density is D(h) / 4).
            float pdf = ggx_sample_pdf(ht.z, ht.z, params.roughness);
            float sample_solid_angle = 1.0 / (float(params.sample_count) * pdf + 1e-6);
            lod = max(0.5 * log2(sample_solid_angle / texel_solid_angle) + 1.0, 0.0);
        }
        sum += textureLod(environment, L, lod).rgb * NdotL;
        weight_sum += NdotL;
    }
    imageStore(level, ivec3(id), vec4(sum / max(weight_sum, 1e-30), 1.0));
}
