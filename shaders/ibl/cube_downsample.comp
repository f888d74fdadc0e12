#version 460
// Cube mip m from mip m - 1: each texel is the mean radiance over its solid angle, i.e.
// the solid-angle-weighted mean of its four parents on the same face. Every level then
// integrates to the same power as level 0, and no texel mixes faces, so no seams arise
// (seamless cube filtering does the rest at sampling time).
#include "ibl/cube.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0, rgba32f) uniform readonly image2DArray parent;
layout(binding = 1, rgba32f) uniform writeonly image2DArray child;

void main() {
    uint n = uint(imageSize(child).x);
    uint parent_n = uint(imageSize(parent).x);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint j = 0u; j < 2u; ++j) {
        for (uint i = 0u; i < 2u; ++i) {
            uvec2 p = min(id.xy * 2u + uvec2(i, j), uvec2(parent_n - 1u));
            float w = cube_texel_solid_angle(p, parent_n);
            sum += w * imageLoad(parent, ivec3(p, id.z)).rgb;
            weight += w;
        }
    }
    imageStore(child, ivec3(id), vec4(sum / weight, 1.0));
}
