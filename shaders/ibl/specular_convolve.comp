#version 460
// Prefiltered specular radiance for one roughness (split sum, n = v = R; Karis 2013):
// P(R) = integral L(l) w(l) dl / integral w(l) dl with w(l) = D(h) (n.l) / 4 for n.l > 0,
// h = normalize(n + l), which is the limit of the thesis' importance-sampled estimate.
// Here it is a deterministic sum over the entries of a texel list (cube_texels.comp):
// no noise, no fireflies from a sun, exact for a uniform sky. Used for rough levels,
// where a small source level resolves the lobe.
#include "facet/brdf.glsl"
#include "ibl/cube.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(std430, binding = 0) readonly buffer Texels { vec4 texels[]; };
layout(binding = 1, rgba32f) uniform writeonly image2DArray level;

layout(push_constant) uniform Params {
    uint texel_count;
    float roughness;
} params;

void main() {
    uint n = uint(imageSize(level).x);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    vec3 normal = normalize(cube_direction(id.z, (vec2(id.xy) + 0.5) / float(n)));
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    for (uint i = 0u; i < params.texel_count; ++i) {
        vec3 l = texels[2u * i].xyz;
        vec4 radiance_solid_angle = texels[2u * i + 1u];
        float NdotL = dot(normal, l);
        if (NdotL <= 0.0) continue;
        vec3 h = normalize(normal + l);
        float w = D_GGX(dot(normal, h), params.roughness) * NdotL;
        sum += w * radiance_solid_angle.rgb;
        weight_sum += w * radiance_solid_angle.w;
    }
    imageStore(level, ivec3(id), vec4(sum / max(weight_sum, 1e-30), 1.0));
}
