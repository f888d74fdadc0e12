#version 460
// One entry per block of level-0 texels (a texel of a coarser level): the block's
// radiance times solid angle (exact: the sum over its children), its radiance-weighted
// mean direction, and the angular radius of a cap with the same spread. A sun inside the
// block is then placed where it is, not at the block's centre, and keeps a point-like
// spread, so the convolution over a few thousand entries matches one over every texel.
#include "facet/shared_constants.h"
#include "ibl/cube.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0, rgba32f) uniform readonly image2DArray level0;
layout(std430, binding = 1) writeonly buffer Texels { vec4 texels[]; };  // 2 per entry

layout(push_constant) uniform Params {
    uint block;  // 2^level: children per side
} params;

void main() {
    uint n0 = uint(imageSize(level0).x);
    uint n = max(n0 / params.block, 1u);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    vec3 radiance_solid_angle = vec3(0.0);
    vec3 weighted_direction = vec3(0.0);
    float weight = 0.0;
    for (uint j = 0u; j < params.block; ++j) {
        for (uint i = 0u; i < params.block; ++i) {
            uvec2 child = id.xy * params.block + uvec2(i, j);
            float solid_angle = cube_texel_solid_angle(child, n0);
            vec3 d = normalize(cube_direction(id.z, (vec2(child) + 0.5) / float(n0)));
            vec3 radiance = imageLoad(level0, ivec3(child, id.z)).rgb;
            radiance_solid_angle += radiance * solid_angle;
            // Weighted by luminance, plus a trace of solid angle so a black block is centred.
            // Each child counts as a cap of its own solid angle, whose mean resultant
            // length is (1 + cos s) / 2, so a one-texel block keeps its own extent.
            float w = (facet_luminance(radiance) + 1e-6) * solid_angle;
            float child_cos = 1.0 - solid_angle / (2.0 * facet_pi);
            weighted_direction += w * 0.5 * (1.0 + child_cos) * d;
            weight += w;
        }
    }
    vec3 block_direction = normalize(cube_direction(id.z, (vec2(id.xy) + 0.5) / float(n)));
    float mean_length = length(weighted_direction) / weight;  // 1 for a point, (1 + cos s)/2 for a cap
    vec3 direction = mean_length > 1e-6 ? normalize(weighted_direction) : block_direction;
    float cos_sigma = clamp(2.0 * mean_length - 1.0, -1.0, 1.0);
    float sin2_sigma = 1.0 - cos_sigma * cos_sigma;
    uint index = (id.z * n + id.y) * n + id.x;
    texels[2u * index] = vec4(direction, sin2_sigma);
    texels[2u * index + 1u] = vec4(radiance_solid_angle, cube_texel_solid_angle(id.xy, n));
}
