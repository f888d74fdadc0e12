#version 460
// The hybrid specular method's split of the environment (specular_hybrid.comp): every
// level-0 texel whose luminance exceeds T = factor x the environment's mean luminance
// keeps T in the residual cube (its colour kept) and gives the rest, its excess, to the
// block of block x block texels it lies in. One entry per block: the excess radiance
// times solid angle (exact: the sum over the block) and its luminance-weighted mean
// direction, so a sun stays where it is. The residual is of dynamic range at most T over
// the mean, which a few filtered samples resolve; the excess is summed exactly.
#include "facet/shared_constants.h"
#include "ibl/cube.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0, rgba32f) uniform readonly image2DArray level0;
layout(binding = 1, rgba32f) uniform readonly image2DArray top;  // the 1 x 1 mip: each face's mean
layout(binding = 2, rgba32f) uniform writeonly image2DArray residual;
layout(std430, binding = 3) writeonly buffer Blocks { vec4 blocks[]; };  // 2 per block

layout(push_constant) uniform Params {
    uint block;    // texels per block side
    float factor;  // T = factor x mean luminance
} params;

#include "ibl/excess_threshold.glsl"

void main() {
    uint n0 = uint(imageSize(level0).x);
    uint n = max(n0 / params.block, 1u);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    float threshold = excess_threshold(params.factor);
    vec3 excess = vec3(0.0);
    vec3 weighted_direction = vec3(0.0);
    for (uint j = 0u; j < params.block; ++j) {
        for (uint i = 0u; i < params.block; ++i) {
            ivec3 texel = ivec3(id.xy * params.block + uvec2(i, j), id.z);
            vec3 radiance = imageLoad(level0, texel).rgb;
            float luminance = facet_luminance(radiance);
            float keep = luminance > threshold ? threshold / luminance : 1.0;
            imageStore(residual, texel, vec4(radiance * keep, 1.0));
            if (keep < 1.0) {
                float solid_angle = cube_texel_solid_angle(uvec2(texel.xy), n0);
                vec3 d = normalize(cube_direction(id.z, (vec2(texel.xy) + 0.5) / float(n0)));
                vec3 e = radiance * (1.0 - keep) * solid_angle;
                excess += e;
                weighted_direction += facet_luminance(e) * d;
            }
        }
    }
    uint index = (id.z * n + id.y) * n + id.x;
    // The direction unnormalised (blocks merge by adding); the list normalises it.
    blocks[2u * index] = vec4(weighted_direction, 0.0);
    blocks[2u * index + 1u] = vec4(excess, length(weighted_direction) > 0.0 ? 1.0 : 0.0);
}
