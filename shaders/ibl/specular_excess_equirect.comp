#version 460
// The hybrid method's split (as specular_excess.comp makes it) of the equirectangular input
// itself: the residual image (resampled to a cube afterwards) and the excess entries from
// its blocks, so that a sun's entries sit where its texels are, not where a resampling to
// the cube put them, and residual and excess come from the same texels (their sum is the
// input, also where a wide bright region crosses the threshold). T = factor x the mean
// luminance of the environment cube's 1 x 1 mip.
#include "facet/shared_constants.h"
#include "ibl/equirect.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform readonly image2D equirect;
layout(binding = 1, rgba32f) uniform readonly image2DArray top;
layout(std430, binding = 2) writeonly buffer Blocks { vec4 blocks[]; };  // 2 per block
layout(binding = 3, rgba32f) uniform writeonly image2D residual;

layout(push_constant) uniform Params {
    uint block;
    float factor;
} params;

#include "ibl/excess_threshold.glsl"

void main() {
    ivec2 size = imageSize(equirect);
    uvec2 counts = (uvec2(size) + params.block - 1u) / params.block;
    uvec2 id = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(id, counts))) return;
    float threshold = excess_threshold(params.factor);
    vec3 excess = vec3(0.0);
    vec3 weighted_direction = vec3(0.0);
    uvec2 end = min((id + 1u) * params.block, uvec2(size));
    for (uint y = id.y * params.block; y < end.y; ++y) {
        float solid_angle = equirect_texel_solid_angle(y, uvec2(size));
        for (uint x = id.x * params.block; x < end.x; ++x) {
            vec3 radiance = imageLoad(equirect, ivec2(x, y)).rgb;
            float luminance = facet_luminance(radiance);
            float keep = luminance > threshold ? threshold / luminance : 1.0;
            imageStore(residual, ivec2(x, y), vec4(radiance * keep, 1.0));
            if (keep < 1.0) {
                vec3 e = radiance * (1.0 - keep) * solid_angle;
                excess += e;
                weighted_direction += facet_luminance(e) * equirect_direction((vec2(x, y) + 0.5) / vec2(size));
            }
        }
    }
    uint index = id.y * counts.x + id.x;
    // The direction unnormalised (blocks merge by adding); the list normalises it.
    blocks[2u * index] = vec4(weighted_direction, 0.0);
    blocks[2u * index + 1u] = vec4(excess, length(weighted_direction) > 0.0 ? 1.0 : 0.0);
}
